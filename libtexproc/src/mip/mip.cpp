// The mip chain: decode at the row boundary, filter level to level in linear
// premultiplied float, encode each level with correct rounding.
#include "texproc/mip.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>

#include "image/srgb_rows.h"
#include "mip/chain_rows.h"
#include "mip/resample.h"
#include "texproc/error.h"
#include "texproc/runtime.h"

namespace texproc {

int mip_level_dim(int size, int level) { return std::max(1, size >> level); }

int mip_level_count(int width, int height, int max_levels, int min_size) {
  int n = 1;
  while (width > 1 || height > 1) {
    width = std::max(1, width / 2);
    height = std::max(1, height / 2);
    if (std::max(width, height) < min_size) break;
    ++n;
  }
  if (max_levels > 0) n = std::min(n, max_levels);
  return n;
}

namespace mip_rows {

Scratch& scratch() {
  thread_local Scratch s;
  return s;
}

namespace {

void premultiply_row(float* px, int channels, int width) {
  if (channels == 4) {
    for (int x = 0; x < width; ++x, px += 4) {
      px[0] *= px[3];
      px[1] *= px[3];
      px[2] *= px[3];
    }
    return;
  }
  for (int x = 0; x < width; ++x) {
    float* p = px + x * channels;
    const float a = p[channels - 1];
    for (int c = 0; c < channels - 1; ++c) p[c] *= a;
  }
}

void unpremultiply_row(float* px, int channels, int width) {
  if (channels == 4) {
    for (int x = 0; x < width; ++x, px += 4) {
      const float a = px[3];
      const float inv = a > 0.0f ? 1.0f / a : 0.0f;
      px[0] *= inv;
      px[1] *= inv;
      px[2] *= inv;
    }
    return;
  }
  for (int x = 0; x < width; ++x) {
    float* p = px + x * channels;
    const float a = p[channels - 1];
    if (a > 0.0f) {
      for (int c = 0; c < channels - 1; ++c) p[c] /= a;
    } else {
      for (int c = 0; c < channels - 1; ++c) p[c] = 0.0f;
    }
  }
}

}  // namespace

void renormalize_row(float* px, int channels, int width) {
  for (int x = 0; x < width; ++x) {
    float* p = px + x * channels;
    const float vx = p[0] * 2.0f - 1.0f, vy = p[1] * 2.0f - 1.0f, vz = p[2] * 2.0f - 1.0f;
    const float len = std::sqrt(vx * vx + vy * vy + vz * vz);
    if (len > 1e-12f) {
      p[0] = vx / len * 0.5f + 0.5f;
      p[1] = vy / len * 0.5f + 0.5f;
      p[2] = vz / len * 0.5f + 0.5f;
    } else {
      p[0] = 0.5f;
      p[1] = 0.5f;
      p[2] = 1.0f;
    }
  }
}

void decode_input_row(const ChainSetup& s, const ConstImageView& in, int y, float* dst) {
  if (s.rgba8_srgb_fast) return decode_srgb8_rgba_premultiplied(in.row<const std::uint8_t>(y), in.width, dst);
  s.in_cs.decode_row(in.row<const void>(y), in.type, s.channels, in.width, dst);
  if (s.premultiply) premultiply_row(dst, s.channels, in.width);
}

void encode_level_row(const ChainSetup& s, const float* src, int w, float alpha_scale, void* dst) {
  if (s.rgba8_srgb_fast && alpha_scale == 1.0f) {
    return encode_srgb8_rgba_unpremultiplied(src, w, static_cast<std::uint8_t*>(dst));
  }
  const int C = s.channels;
  FloatBuffer& row = scratch().row_out;
  row.resize(std::size_t(w) * C);
  std::memcpy(row.data(), src, row.size() * sizeof(float));
  if (s.premultiply) unpremultiply_row(row.data(), C, w);
  if (s.alpha && alpha_scale != 1.0f) {
    for (int x = 0; x < w; ++x) row[x * C + C - 1] = std::min(1.0f, row[x * C + C - 1] * alpha_scale);
  }
  s.out_cs.encode_row(row.data(), C, w, dst, s.out_type);
}

}  // namespace mip_rows

namespace {

using namespace mip_rows;

// A level as the filter sees it: rows of linear (premultiplied) floats.
// Level 0 is decoded from the input on demand; later levels are stored.
struct LevelRows {
  const ConstImageView* input = nullptr;  // level 0
  const float* stored = nullptr;          // levels >= 1
  int width = 0, height = 0;
};

bool has_alpha(int channels) { return channels == 2 || channels == 4; }

void encode_level(const ChainSetup& s, const float* src, int level, int w, int h, float alpha_scale, MipRowSink& sink) {
  for_each_row_block(h, kBlockRows, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      encode_level_row(s, src + std::size_t(y) * w * s.channels, w, alpha_scale, sink.row(level, y));
      sink.row_done(level, y);
    }
  });
}

// Filters `src` down to dw x dh. With `encoded`, each row is also encoded
// into it while still in cache (when no whole-level statistic such as alpha
// coverage must be known first).
FloatBuffer downsample(const ChainSetup& s, const LevelRows& src, int dw, int dh, const Filter& filter, int level,
                       MipRowSink* encoded) {
  const int C = s.channels;
  const int sw = src.width, sh = src.height;
  const AxisWeights wx = compute_axis_weights(sw, dw, filter);
  const AxisWeights wy = compute_axis_weights(sh, dh, filter);
  FloatBuffer dst(std::size_t(dw) * dh * C);
  const std::size_t src_row = std::size_t(sw) * C;

  for_each_row_block(dh, kBlockRows, [&](int y0, int y1) {
    int lo = INT_MAX, hi = INT_MIN;
    for (int y = y0; y < y1; ++y) {
      lo = std::min(lo, wy.first[y]);
      hi = std::max(hi, wy.first[y] + wy.taps - 1);
    }
    Scratch& sc = scratch();
    std::vector<const float*>& rows = sc.rows;
    rows.resize(hi - lo + 1);
    FloatBuffer& decoded = sc.decoded;
    if (src.input) {
      decoded.resize(rows.size() * src_row);
      for (int j = lo; j <= hi; ++j) {
        float* d = decoded.data() + (j - lo) * src_row;
        decode_input_row(s, *src.input, wrap_index(j, sh, s.wrap), d);
        rows[j - lo] = d;
      }
    } else {
      for (int j = lo; j <= hi; ++j) rows[j - lo] = src.stored + wrap_index(j, sh, s.wrap) * src_row;
    }
    FloatBuffer& tmp = sc.row;
    tmp.resize(std::size_t(wx.pad_before + sw + wx.pad_after) * C);
    float* mid = tmp.data() + std::size_t(wx.pad_before) * C;
    std::vector<const float*>& taps = sc.taps;
    taps.resize(wy.taps);
    for (int y = y0; y < y1; ++y) {
      for (int k = 0; k < wy.taps; ++k) taps[k] = rows[wy.first[y] + k - lo];
      vertical_pass(taps.data(), wy.weights.data() + std::size_t(y) * wy.taps, wy.taps, int(src_row), mid);
      for (int p = 1; p <= wx.pad_before; ++p) {
        std::memcpy(mid - p * C, mid + wrap_index(-p, sw, s.wrap) * C, C * sizeof(float));
      }
      for (int p = 0; p < wx.pad_after; ++p) {
        std::memcpy(mid + (sw + p) * C, mid + wrap_index(sw + p, sw, s.wrap) * C, C * sizeof(float));
      }
      float* out = dst.data() + std::size_t(y) * dw * C;
      horizontal_pass(mid, C, wx.first.data(), wx.weights.data(), wx.taps, dw, out);
      if (s.normal_map) renormalize_row(out, C, dw);
      if (encoded) {
        encode_level_row(s, out, dw, 1.0f, encoded->row(level, y));
        encoded->row_done(level, y);
      }
    }
  });
  return dst;
}

// Fraction of alpha values (stride `channels`, offset channels-1) with a * scale >= ref.
float coverage_of(const float* px, std::size_t count, int channels, float ref, float scale) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < count; ++i) n += px[i * channels + channels - 1] * scale >= ref;
  return count ? float(double(n) / double(count)) : 0.0f;
}

// The factor k such that the fraction of a * k >= ref is `target` (as close as
// the texels allow): k = ref / (the ceil(target * n)-th largest alpha).
float coverage_scale(const float* px, std::size_t count, int channels, float ref, float target) {
  std::vector<float> a(count);
  for (std::size_t i = 0; i < count; ++i) a[i] = px[i * channels + channels - 1];
  const std::size_t want = std::size_t(std::llround(double(target) * count));
  constexpr float kMaxScale = 1.0e4f;
  if (want == 0) {
    const float mx = *std::max_element(a.begin(), a.end());
    return mx >= ref && mx > 0.0f ? std::nextafter(ref / mx, 0.0f) : 1.0f;
  }
  std::nth_element(a.begin(), a.begin() + (want - 1), a.end(), std::greater<float>());
  const float t = a[want - 1];
  if (t <= 0.0f) return kMaxScale;
  return std::min(kMaxScale, ref / t);
}

bool level0_is_input(const ChainSetup& s, const ConstImageView& in) {
  return in.type == s.out_type && s.in_cs.name() == s.out_cs.name();
}

// Level 0 row by row: a byte copy of the input, or the input converted.
void convert_level0_rows(const ChainSetup& s, const ConstImageView& in, MipRowSink& sink) {
  const bool copy = level0_is_input(s, in);
  const std::size_t bytes = std::size_t(in.width) * s.channels * bytes_per_channel(s.out_type);
  for_each_row_block(in.height, copy ? 64 : kBlockRows, [&](int y0, int y1) {
    FloatBuffer& row = scratch().row;
    row.resize(std::size_t(in.width) * s.channels);
    for (int y = y0; y < y1; ++y) {
      void* dst = sink.row(0, y);
      if (copy) {
        std::memcpy(dst, in.row<const void>(y), bytes);
      } else {
        s.in_cs.decode_row(in.row<const void>(y), in.type, s.channels, in.width, row.data());
        s.out_cs.encode_row(row.data(), s.channels, in.width, dst, s.out_type);
      }
      sink.row_done(0, y);
    }
  });
}

Image convert_level0(const ChainSetup& s, const ConstImageView& in) {
  Image out = Image::uninitialized(in.width, in.height, s.channels, s.out_type);
  struct Into final : MipRowSink {
    Image* out = nullptr;
    void* row(int, int y) override { return out->row<void>(y); }
  } sink;
  sink.out = &out;
  convert_level0_rows(s, in, sink);
  return out;
}

}  // namespace

float alpha_coverage(const ConstImageView& image, float ref, float scale) {
  if (!has_alpha(image.channels)) return 1.0f;
  std::size_t n = 0;
  const int C = image.channels;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      float a = 0.0f;
      switch (image.type) {
        case PixelType::u8:
          a = image.row<std::uint8_t>(y)[x * C + C - 1] / 255.0f;
          break;
        case PixelType::u16:
          a = image.row<std::uint16_t>(y)[x * C + C - 1] / 65535.0f;
          break;
        case PixelType::f32:
          a = image.row<float>(y)[x * C + C - 1];
          break;
      }
      n += a * scale >= ref;
    }
  }
  return float(double(n) / (double(image.width) * image.height));
}

namespace {
// Levels 1.. into the sink: in waves (cascade) or, where a whole level must
// be known before it is written (alpha coverage) or asked for, whole float
// levels one after the other.
void stream_levels(const ChainSetup& s, const ConstImageView& image, int levels, const MipOptions& o, bool whole_levels,
                   MipRowSink& sink, MipChain& chain) {
  const bool coverage = s.alpha && o.alpha_coverage_ref && !o.normal_map;
  float target = 0.0f;
  if (coverage) {
    target = alpha_coverage(image, *o.alpha_coverage_ref);
    chain.alpha_coverage.push_back(target);
    chain.alpha_scale.push_back(1.0f);
  }
  if (!coverage && !whole_levels) {
    if (levels > 1) cascade(s, image, levels, o.filter, sink);
    return;
  }
  FloatBuffer prev;
  LevelRows src{&image, nullptr, image.width, image.height};
  for (int level = 1; level < levels; ++level) {
    const int dw = mip_level_dim(image.width, level), dh = mip_level_dim(image.height, level);
    FloatBuffer cur = downsample(s, src, dw, dh, o.filter, level, coverage ? nullptr : &sink);
    if (coverage) {
      // Coverage is judged on straight alpha, which premultiplication leaves alone.
      const float scale = coverage_scale(cur.data(), std::size_t(dw) * dh, s.channels, *o.alpha_coverage_ref, target);
      chain.alpha_coverage.push_back(
          coverage_of(cur.data(), std::size_t(dw) * dh, s.channels, *o.alpha_coverage_ref, scale));
      chain.alpha_scale.push_back(scale);
      encode_level(s, cur.data(), level, dw, dh, scale, sink);
    }
    prev = std::move(cur);
    src = LevelRows{nullptr, prev.data(), dw, dh};
  }
}

ChainSetup setup_chain(const ConstImageView& image, const MipOptions& o) {
  assert(image.data && image.width > 0 && image.height > 0);
  if (image.channels < 1 || image.channels > 4) {
    throw Error(ErrorCode::unsupported,
                "images with " + std::to_string(image.channels) + " channels are not supported (valid: 1 to 4)");
  }
  if (o.filter.kind == FilterKind::gaussian && !(o.filter.sigma > 0.0f && o.filter.sigma <= 4.0f)) {
    throw Error(ErrorCode::bad_arguments, "MipOptions::filter.sigma " + std::to_string(o.filter.sigma) +
                                              " is out of range (valid: 0 < sigma <= 4)");
  }
  if (o.normal_map && image.channels < 3) {
    throw Error(ErrorCode::bad_arguments, "MipOptions::normal_map needs an RGB or RGBA image, this one has " +
                                              std::to_string(image.channels) + " channel(s)");
  }
  if (o.alpha_coverage_ref && !(*o.alpha_coverage_ref > 0.0f && *o.alpha_coverage_ref <= 1.0f)) {
    throw Error(ErrorCode::bad_arguments, "MipOptions::alpha_coverage_ref " + std::to_string(*o.alpha_coverage_ref) +
                                              " is out of range (valid: 0 < ref <= 1)");
  }
  if (o.min_size < 1) throw Error(ErrorCode::bad_arguments, "MipOptions::min_size must be at least 1");

  ChainSetup s;
  s.channels = image.channels;
  s.alpha = has_alpha(image.channels);
  s.normal_map = o.normal_map;
  s.premultiply = s.alpha && o.premultiplied_alpha && !o.normal_map;
  s.wrap = o.wrap;
  s.out_type = o.output_type.value_or(image.type);
  if (o.normal_map) {
    s.in_cs = s.out_cs = ColorSpace::linear();
  } else {
    s.in_cs = !o.color_space.empty() ? ColorSpace::from_name(o.color_space)
              : is_float(image.type) ? ColorSpace::linear()
                                     : ColorSpace::srgb();
    if (!o.output_color_space.empty()) {
      s.out_cs = ColorSpace::from_name(o.output_color_space);
    } else if (is_float(s.out_type) && !is_float(image.type)) {
      s.out_cs = ColorSpace::linear();
    } else {
      s.out_cs = s.in_cs;
    }
  }
  s.rgba8_srgb_fast = s.channels == 4 && s.premultiply && image.type == PixelType::u8 && s.out_type == PixelType::u8 &&
                      s.in_cs.is_srgb() && s.out_cs.is_srgb();
  return s;
}

// Writes rows into the chain's images.
class ChainSink final : public MipRowSink {
 public:
  explicit ChainSink(std::vector<Image>& levels) : levels_(levels) {}
  void* row(int level, int y) override { return levels_[level].row<void>(y); }

 private:
  std::vector<Image>& levels_;
};

MipChain generate(const ConstImageView& image, Image* owned, const MipOptions& o, bool whole_levels) {
  const ChainSetup s = setup_chain(image, o);
  MipChain chain;
  chain.color_space = s.out_cs.name();
  const int levels = mip_level_count(image.width, image.height, o.max_levels, o.min_size);
  chain.levels.reserve(levels);
  // Level 0 is the input itself when nothing converts it; the filter reads
  // the input view, which stays valid while `owned` moves into the chain.
  if (owned && level0_is_input(s, image)) {
    chain.levels.push_back(std::move(*owned));
  } else {
    chain.levels.push_back(convert_level0(s, image));
  }
  for (int level = 1; level < levels; ++level) {
    chain.levels.push_back(Image::uninitialized(mip_level_dim(image.width, level), mip_level_dim(image.height, level),
                                                s.channels, s.out_type));
  }
  ChainSink sink(chain.levels);
  stream_levels(s, image, levels, o, whole_levels, sink, chain);
  return chain;
}

}  // namespace

MipChain generate_mips(const ConstImageView& image, const MipOptions& o) { return generate(image, nullptr, o, false); }

MipChain generate_mips(Image&& image, const MipOptions& o) {
  const ImageView view = image.view();
  return generate(view, &image, o, false);
}

MipChain generate_mips_rows(const ConstImageView& image, const MipOptions& o, MipRowSink& sink) {
  const ChainSetup s = setup_chain(image, o);
  MipChain chain;
  chain.color_space = s.out_cs.name();
  const int levels = mip_level_count(image.width, image.height, o.max_levels, o.min_size);
  sink.begin(levels, s.out_type, s.channels);
  if (sink.wants_level0()) convert_level0_rows(s, image, sink);
  stream_levels(s, image, levels, o, false, sink, chain);
  return chain;
}

namespace detail {
MipChain generate_mips_whole_levels(const ConstImageView& image, const MipOptions& o) {
  return generate(image, nullptr, o, true);
}
}  // namespace detail

}  // namespace texproc
