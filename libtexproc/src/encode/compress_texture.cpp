// compress_texture: every level of every surface of a chain through
// compress_image, with the layouts and policies `texproc compress` applies
// (block_encode.h).
#include <utility>

#include "texproc/block_encode.h"
#include "texproc/error.h"

namespace texproc {

Image dxt5nm_layout(const ConstImageView& v) {
  Image nm = Image::uninitialized(v.width, v.height, 4, v.type);
  // Through an owning copy's get(): the same conversions as every other channel read.
  Image l(v.width, v.height, v.channels, v.type);
  for (int y = 0; y < v.height; ++y) std::copy_n(v.row<const std::uint8_t>(y), l.row_stride(), l.row<std::uint8_t>(y));
  for (int y = 0; y < v.height; ++y)
    for (int x = 0; x < v.width; ++x) {
      nm.set(x, y, 0, 1.0f);
      nm.set(x, y, 1, l.channels() > 1 ? l.get(x, y, 1) : 0.5f);
      nm.set(x, y, 2, 0.0f);
      nm.set(x, y, 3, l.get(x, y, 0));
    }
  return nm;
}

Texture compress_texture(std::vector<std::vector<Image>>& chains, const SurfaceLayout& layout, TexelFormat format,
                         Quality q, const TextureEncodeOptions& options) {
  const std::uint32_t faces = layout.faces, layers = layout.layers;
  const bool is_array = layout.is_array;
  if (chains.empty() || chains[0].empty() || chains.size() != std::size_t(faces) * layers) {
    throw Error(ErrorCode::bad_arguments, "compress_texture needs faces * layers chains of at least one level");
  }
  for (const auto& c : chains) {
    if (c.size() != chains[0].size())
      throw Error(ErrorCode::bad_arguments, "compress_texture: the chains differ in length");
    for (std::size_t l = 0; l < c.size(); ++l)
      if (c[l].width() != chains[0][l].width() || c[l].height() != chains[0][l].height()) {
        throw Error(ErrorCode::bad_arguments,
                    "compress_texture: the chains differ in size at level " + std::to_string(l));
      }
  }
  const FormatInfo& info = format_info(format);
  const bool dxt5nm = options.normal_map && (format == TexelFormat::bc3_unorm || format == TexelFormat::bc3_srgb);
  const std::size_t surfaces = chains.size();
  Texture t;
  t.format = format;
  t.width = std::uint32_t(chains[0][0].width());
  t.height = std::uint32_t(chains[0][0].height());
  t.levels = std::uint32_t(chains[0].size());
  t.faces = faces;
  t.layers = layers;
  t.is_array = is_array;
  t.images.resize(std::size_t(t.levels) * surfaces);
  // Progress: the levels weighed by their texels.
  double texels = 0.0, texels_before = 0.0;
  for (const auto& c : chains)
    for (const Image& l : c) texels += double(l.width()) * double(l.height());
  for (std::size_t s = 0; s < surfaces; ++s)
    for (std::size_t li = 0; li < chains[s].size(); ++li) {
      Image& l = chains[s][li];
      if (dxt5nm) l = dxt5nm_layout(l.view());
      // The policy applies to each stored level (a chain filtered
      // premultiplied has no fringes; the GPU's filtering of straight alpha
      // would add them back from the colour under alpha 0).
      if (info.channels == 4 && !options.normal_map) apply_transparent_color(l, options.transparent);
      EncodeOptions e = options.encode;
      e.normal_map = options.normal_map && is_astc(format);
      const double level_texels = double(l.width()) * double(l.height());
      if (options.encode.progress) {
        e.progress = [&](double done) { options.encode.progress((texels_before + done * level_texels) / texels); };
      }
      t.images[li * surfaces + s] = PixelBytes(compress_image(l.view(), format, q, e));
      texels_before += level_texels;
    }
  return t;
}

}  // namespace texproc
