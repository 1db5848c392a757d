// GPU containers (DDS, KTX2, KTX1, PKM, .astc) read as images: level 0, layer 0,
// face 0 (or every level of every surface), through texproc's own container readers; block-compressed formats
// are decoded. (read_texture keeps every level, face and layer.)
#include <algorithm>
#include <cstring>

#include "io/codecs/codecs.h"
#include "texproc/block_decode.h"
#include "texproc/container.h"
#include "texproc/error.h"
#include "texproc/texture.h"

namespace texproc::codecs {
namespace {

const char* container_name(const std::string& path, const FileBytes& f) {
  (void)path;
  ContainerKind kind = ContainerKind::ktx1;
  container_from_signature(f.data(), f.size(), kind);
  return to_string(kind);
}

// The type a texture's texels decode to without loss: 16-bit and float
// formats keep their precision (EAC's 11 bits in u16), the rest are 8-bit.
PixelType natural_type(TexelFormat f) {
  const FormatInfo& i = format_info(f);
  if (i.is_float) return PixelType::f32;
  switch (f) {
    case TexelFormat::r16_unorm:
    case TexelFormat::rg16_unorm:
    case TexelFormat::rgba16_unorm:
    case TexelFormat::eac_r11_unorm:
    case TexelFormat::eac_r11_snorm:
    case TexelFormat::eac_rg11_unorm:
    case TexelFormat::eac_rg11_snorm:
      return PixelType::u16;
    default:
      return PixelType::u8;
  }
}

ImageFileInfo info_of(const std::string& path, const Texture& t, const char* name, const ReadLimits& limits) {
  const FormatInfo& fi = format_info(t.format);
  ImageFileInfo info;
  info.format = name;
  info.width = int(t.width);
  info.height = int(t.height);
  info.channels = fi.channels;
  info.file_type = fi.name;
  info.type = natural_type(t.format);
  info.color_space_tag = fi.srgb ? "sRGB" : "Linear";
  info.color_space_tagged = true;  // the format itself says
  info.subimages = int(t.faces * t.layers);
  info.mip_levels = int(t.levels);
  for (std::uint32_t l = 0; l < t.levels; ++l)
    info.level_sizes.emplace_back(int(t.level_width(l)), int(t.level_height(l)));
  check_size(path, info.width, info.height, info.channels, limits);
  return info;
}

}  // namespace

ImageFileInfo container_probe(const std::string& path, const ReadLimits& limits) {
  const FileBytes f(path);
  return info_of(path, read_texture(path, limits), container_name(path, f), limits);
}

namespace {

// The texture and its facts; `decode` turns it into images, with errors
// named for the file.
template <typename Decode>
auto load(const std::string& path, ImageFileInfo& info, const ReadLimits& limits, Decode&& decode) {
  const char* name;
  {
    const FileBytes f(path);
    name = container_name(path, f);
  }
  const Texture t = read_texture(path, limits);
  info = info_of(path, t, name, limits);
  try {
    return decode(t);
  } catch (const Error& e) {
    const std::string msg = e.what();
    if (msg.rfind(path, 0) == 0) throw;
    throw Error(e.code(), path + ": " + msg);
  }
}

}  // namespace

ImageArray container_read_all(const std::string& path, ImageFileInfo& info, const ReadLimits& limits) {
  return load(path, info, limits, [&](const Texture& t) {
    ImageArray out;
    out.faces = t.faces;
    out.layers = t.layers;
    out.is_array = t.is_array || t.layers > 1;
    for (std::uint32_t a = 0; a < t.layers; ++a)
      for (std::uint32_t f = 0; f < t.faces; ++f) out.images.push_back(decode_texture_image(t, 0, a, f, info.type));
    return out;
  });
}

ImageChains container_read_chains(const std::string& path, ImageFileInfo& info, const ReadLimits& limits,
                                  std::uint32_t max_levels) {
  return load(path, info, limits, [&](const Texture& t) {
    ImageChains out;
    out.faces = t.faces;
    out.layers = t.layers;
    out.is_array = t.is_array || t.layers > 1;
    const std::uint32_t levels = max_levels > 0 ? std::min(max_levels, t.levels) : t.levels;
    for (std::uint32_t a = 0; a < t.layers; ++a)
      for (std::uint32_t f = 0; f < t.faces; ++f) {
        out.chains.emplace_back();
        for (std::uint32_t l = 0; l < levels; ++l)
          out.chains.back().push_back(decode_texture_image(t, l, a, f, info.type));
      }
    return out;
  });
}

Image container_read(const std::string& path, ImageFileInfo& info, const ReadLimits& limits) {
  return load(path, info, limits, [&](const Texture& t) { return decode_texture_image(t, 0, 0, 0, info.type); });
}

}  // namespace texproc::codecs
