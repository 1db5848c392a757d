// compress_texture_mips: a mip chain block-compressed as it is filtered.
// Each level's rows arrive from generate_mips_rows in no fixed order; a
// block row is encoded, by the thread that completes it, as soon as its
// texel rows are all there, so neither the chain nor a level is ever held.
// Blocks are coded independently of their neighbours, so a block row
// encoded alone has the bytes it has inside the whole level.
#include <atomic>
#include <memory>
#include <mutex>

#include "texproc/block_encode.h"
#include "texproc/error.h"
#include "texproc/mip.h"

namespace texproc {
namespace {

// The layouts compress_texture applies to a stored level, texel by texel
// (the bleeding transparent colour, which reads neighbours, is not one).
struct LevelLayout {
  bool dxt5nm = false;
  bool transparent_zero = false;
  bool astc_normal = false;
};

Image laid_out(Image level, const LevelLayout& lay) {
  if (lay.dxt5nm) level = dxt5nm_layout(level.view());
  if (lay.transparent_zero) apply_transparent_color(level, TransparentColor::zero);
  return level;
}

// Rows in, blocks out, for levels 1.. of one surface.
class BlockRowSink final : public MipRowSink {
 public:
  BlockRowSink(Texture& t, std::size_t surface, std::size_t surfaces, Quality q, const LevelLayout& lay,
               const EncodeOptions& e, const std::function<void(double)>& texels_done)
      : t_(t), surface_(surface), surfaces_(surfaces), q_(q), lay_(lay), e_(e), texels_done_(texels_done) {}

  void begin(int levels, PixelType type, int channels) override {
    type_ = type;
    channels_ = channels;
    const FormatInfo& f = format_info(t_.format);
    levels_.resize(levels);
    for (int l = 1; l < levels; ++l) {
      Level& lv = levels_[l];
      lv.width = int(t_.level_width(l));
      lv.height = int(t_.level_height(l));
      lv.block_rows = (lv.height + f.block_height - 1) / f.block_height;
      lv.row_bytes = std::size_t((lv.width + f.block_width - 1) / f.block_width) * f.block_bytes;
      lv.strips = std::vector<std::unique_ptr<Image>>(lv.block_rows);
      lv.rows_in = std::make_unique<std::atomic<int>[]>(lv.block_rows);
      for (int b = 0; b < lv.block_rows; ++b) lv.rows_in[b] = 0;
      t_.images[std::size_t(l) * surfaces_ + surface_] = PixelBytes(lv.row_bytes * lv.block_rows);
    }
  }

  void* row(int level, int y) override {
    Level& lv = levels_[level];
    const int bh = format_info(t_.format).block_height;
    const int b = y / bh;
    std::lock_guard<std::mutex> lock(m_);
    if (!lv.strips[b]) {
      lv.strips[b] =
          std::make_unique<Image>(Image::uninitialized(lv.width, std::min(bh, lv.height - b * bh), channels_, type_));
    }
    return lv.strips[b]->row<void>(y - b * bh);
  }

  void row_done(int level, int y) override {
    Level& lv = levels_[level];
    const int bh = format_info(t_.format).block_height;
    const int b = y / bh;
    const int rows = std::min(bh, lv.height - b * bh);
    if (lv.rows_in[b].fetch_add(1) + 1 != rows) return;
    std::unique_ptr<Image> strip;
    {
      std::lock_guard<std::mutex> lock(m_);
      strip = std::move(lv.strips[b]);
    }
    const Image coded = laid_out(std::move(*strip), lay_);
    strip.reset();
    EncodeOptions e = e_;
    e.progress = nullptr;
    const std::vector<std::uint8_t> blocks = compress_image(coded.view(), t_.format, q_, e);
    PixelBytes& out = t_.images[std::size_t(level) * surfaces_ + surface_];
    std::copy(blocks.begin(), blocks.end(), out.begin() + std::ptrdiff_t(lv.row_bytes * b));
    if (texels_done_) texels_done_(double(lv.width) * rows);
  }

 private:
  struct Level {
    int width = 0, height = 0, block_rows = 0;
    std::size_t row_bytes = 0;
    std::vector<std::unique_ptr<Image>> strips;   // per block row, while its rows arrive
    std::unique_ptr<std::atomic<int>[]> rows_in;  // per block row, rows written
  };
  Texture& t_;
  std::size_t surface_, surfaces_;
  Quality q_;
  LevelLayout lay_;
  EncodeOptions e_;
  const std::function<void(double)>& texels_done_;
  PixelType type_ = PixelType::u8;
  int channels_ = 0;
  std::vector<Level> levels_;
  std::mutex m_;
};

}  // namespace

Texture compress_texture_mips(std::vector<Image>& surfaces, const MipOptions& mip, const SurfaceLayout& layout,
                              TexelFormat format, Quality q, const TextureEncodeOptions& options) {
  const std::uint32_t faces = layout.faces, layers = layout.layers;
  const bool is_array = layout.is_array;
  if (surfaces.empty() || surfaces.size() != std::size_t(faces) * layers) {
    throw Error(ErrorCode::bad_arguments, "compress_texture_mips needs faces * layers images");
  }
  if (mip.output_type || !mip.output_color_space.empty()) {
    throw Error(ErrorCode::bad_arguments,
                "compress_texture_mips: level 0 is the image as given (MipOptions::output_type and "
                "output_color_space must be unset)");
  }
  const FormatInfo& info = format_info(format);
  const bool four = info.channels == 4 && !options.normal_map;
  // astc-encoder searches a whole level at once, and bleeding reads
  // neighbours: those chains are filtered whole, then encoded.
  if (is_astc(format) || (four && options.transparent == TransparentColor::bleed)) {
    std::vector<std::vector<Image>> chains;
    for (Image& s : surfaces) chains.push_back(generate_mips(std::move(s), mip).levels);
    Texture t = compress_texture(chains, layout, format, q, options);
    for (std::size_t s = 0; s < surfaces.size(); ++s) surfaces[s] = std::move(chains[s][0]);
    return t;
  }
  for (const Image& s : surfaces) {
    if (s.width() != surfaces[0].width() || s.height() != surfaces[0].height()) {
      throw Error(ErrorCode::bad_arguments, "compress_texture_mips: the images differ in size");
    }
  }
  LevelLayout lay;
  lay.dxt5nm = options.normal_map && (format == TexelFormat::bc3_unorm || format == TexelFormat::bc3_srgb);
  lay.transparent_zero = four && options.transparent == TransparentColor::zero;
  Texture t;
  t.format = format;
  t.width = std::uint32_t(surfaces[0].width());
  t.height = std::uint32_t(surfaces[0].height());
  t.levels = std::uint32_t(mip_level_count(surfaces[0].width(), surfaces[0].height(), mip.max_levels, mip.min_size));
  t.faces = faces;
  t.layers = layers;
  t.is_array = is_array;
  const std::size_t n = surfaces.size();
  t.images.resize(std::size_t(t.levels) * n);
  // Progress: texels encoded over all levels of all surfaces, one call at a time.
  double total = 0.0;
  for (std::uint32_t l = 0; l < t.levels; ++l) total += double(t.level_width(l)) * t.level_height(l) * double(n);
  std::mutex progress_mutex;
  double done = 0.0;
  std::function<void(double)> texels_done;
  if (options.encode.progress) {
    texels_done = [&](double texels) {
      std::lock_guard<std::mutex> lock(progress_mutex);
      done += texels;
      options.encode.progress(std::min(1.0, done / total));
    };
  }
  for (std::size_t s = 0; s < n; ++s) {
    BlockRowSink sink(t, s, n, q, lay, options.encode, texels_done);
    generate_mips_rows(surfaces[s].view(), mip, sink);
    // Level 0 last: the chain was filtered from it as given.
    surfaces[s] = laid_out(std::move(surfaces[s]), lay);
    EncodeOptions e = options.encode;
    const double level0 = double(t.width) * t.height;
    if (texels_done) {
      e.progress = [&, before = done](double f) {
        std::lock_guard<std::mutex> lock(progress_mutex);
        options.encode.progress(std::min(1.0, (before + f * level0) / total));
      };
    }
    t.images[s] = PixelBytes(compress_image(surfaces[s].view(), format, q, e));
    if (texels_done) texels_done(level0);
  }
  return t;
}

}  // namespace texproc
