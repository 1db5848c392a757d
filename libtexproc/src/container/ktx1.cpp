// KTX 1.1 (Khronos KTX File Format Specification 1.1): for OpenGL ES
// engines. Little-endian (endianness 0x04030201), no key/value data; each
// level is preceded by its imageSize (one face for cubemaps), faces padded to
// 4 bytes, uncompressed rows padded to 4 bytes (GL_UNPACK_ALIGNMENT 4).
#include <algorithm>

#include "astc/astc_decode.h"
#include "container/bytes.h"
#include "container/streams.h"
#include "texproc/container.h"

namespace texproc {
namespace {

constexpr std::uint8_t kIdentifier[12] = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x31, 0x31, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
constexpr std::uint32_t kGlRed = 0x1903, kGlRg = 0x8227, kGlRgb = 0x1907, kGlRgba = 0x1908, kGlBgra = 0x80E1;

std::uint32_t base_format(const FormatInfo& i) {
  if (i.gl_format == kGlBgra) return kGlBgra;
  switch (i.channels) {
    case 1:
      return kGlRed;
    case 2:
      return kGlRg;
    case 3:
      return kGlRgb;
    default:
      return kGlRgba;
  }
}

// Bytes of one row as stored (uncompressed rows are padded to 4).
std::uint64_t stored_row(const FormatInfo& i, std::uint32_t width) {
  return (std::uint64_t(width) * i.block_bytes + 3) & ~std::uint64_t(3);
}

std::uint64_t stored_image(const FormatInfo& i, std::uint32_t w, std::uint32_t h) {
  return i.compressed ? image_bytes(i.format, w, h) : stored_row(i, w) * h;
}

}  // namespace

ByteWriter encode_ktx1_stream(const Texture& t) {
  validate(t);
  const FormatInfo& info = format_info(t.format);
  if (info.gl_internal_format == 0) {
    throw Error(ErrorCode::unsupported, std::string("KTX1 (OpenGL) has no internal format for ") + info.name);
  }
  ByteWriter w;
  w.raw(kIdentifier, 12);
  w.u32(0x04030201);
  w.u32(info.gl_type);
  w.u32(info.compressed ? 1 : std::uint32_t(info.type_size));
  w.u32(info.gl_format);
  w.u32(info.gl_internal_format);
  w.u32(base_format(info));
  w.u32(t.width);
  w.u32(t.height);
  w.u32(0);
  w.u32(t.is_array || t.layers > 1 ? t.layers : 0);
  w.u32(t.faces);
  w.u32(t.levels);
  w.u32(0);  // bytesOfKeyValueData
  const bool cube_only = t.faces == 6 && !(t.is_array || t.layers > 1);
  for (std::uint32_t l = 0; l < t.levels; ++l) {
    const std::uint32_t lw = t.level_width(l), lh = t.level_height(l);
    const std::uint64_t one = stored_image(info, lw, lh);
    w.u32(std::uint32_t(cube_only ? one : one * t.layers * t.faces));
    for (std::uint32_t a = 0; a < t.layers; ++a)
      for (std::uint32_t f = 0; f < t.faces; ++f) {
        const auto& img = t.image(l, a, f);
        if (info.compressed) {
          w.ref(img.data(), img.size());
        } else {
          const std::size_t row = std::size_t(lw) * info.block_bytes;
          for (std::uint32_t y = 0; y < lh; ++y) {
            w.raw(img.data() + y * row, row);
            w.zeros(std::size_t(stored_row(info, lw) - row));
          }
        }
        w.pad_to(4);  // cubePadding
      }
    w.pad_to(4);  // mipPadding
  }
  return w;
}

std::vector<std::uint8_t> encode_ktx1(const Texture& t) { return encode_ktx1_stream(t).bytes(); }

Texture decode_ktx1(const std::uint8_t* data, std::size_t size, const std::string& name, const ReadLimits& limits) {
  ByteReader r(data, size, name);
  if (size < 12 || std::memcmp(r.at(0, 12, "identifier"), kIdentifier, 12) != 0)
    r.fail("not a KTX1 file (bad identifier)");
  if (r.u32(12, "endianness") != 0x04030201) r.unsupported("big-endian KTX1 files are not supported");
  const std::uint32_t internal = r.u32(28, "glInternalFormat");
  const std::uint32_t width = r.u32(36, "pixelWidth"), height = r.u32(40, "pixelHeight"),
                      depth = r.u32(44, "pixelDepth");
  const std::uint32_t elements = r.u32(48, "numberOfArrayElements"), faces = r.u32(52, "numberOfFaces");
  const std::uint32_t levels = r.u32(56, "numberOfMipmapLevels"), kv = r.u32(60, "bytesOfKeyValueData");
  const FormatInfo* fi = find_format_by_gl(internal);
  if (!fi)
    r.unsupported("glInternalFormat 0x" + [&] {
      char b[16];
      std::snprintf(b, sizeof b, "%X", internal);
      return std::string(b);
    }() + " is not one texproc reads");
  // The other GL fields must say the same format.
  auto hex = [](std::uint32_t v) {
    char b[16];
    std::snprintf(b, sizeof b, "0x%X", v);
    return std::string(b);
  };
  const std::uint32_t gl_type = r.u32(16, "glType"), type_size = r.u32(20, "glTypeSize"),
                      gl_format = r.u32(24, "glFormat"), base = r.u32(32, "glBaseInternalFormat");
  const std::uint32_t want_size = fi->compressed ? 1 : std::uint32_t(fi->type_size);
  const std::pair<const char*, std::pair<std::uint32_t, std::uint32_t>> fields[] = {
      {"glType", {gl_type, fi->gl_type}},
      {"glTypeSize", {type_size, want_size}},
      {"glFormat", {gl_format, fi->gl_format}},
      {"glBaseInternalFormat", {base, base_format(*fi)}}};
  for (const auto& [field, values] : fields) {
    if (values.first != values.second) {
      r.fail(std::string(field) + " " + hex(values.first) + " contradicts glInternalFormat " + hex(internal) + " (" +
             fi->name + ": expected " + hex(values.second) + ")");
    }
  }
  if (width == 0 || height == 0) r.fail("zero pixelWidth or pixelHeight");
  if (width > limits.max_texture_dimension || height > limits.max_texture_dimension)
    r.unsupported("texture larger than the limit");
  if (depth > 1) r.unsupported("3D textures are not supported");
  if (faces != 1 && faces != 6) r.fail("numberOfFaces " + std::to_string(faces) + " (valid: 1, 6)");
  if (faces == 6 && width != height) {
    r.fail("cubemap faces are " + std::to_string(width) + "x" + std::to_string(height) +
           " (cube faces must be square)");
  }
  if (elements > limits.max_layers) r.fail("numberOfArrayElements " + std::to_string(elements));
  std::uint32_t max_levels = 1;
  for (std::uint32_t m = std::max(width, height); m > 1; m >>= 1) ++max_levels;
  if (levels > max_levels)
    r.fail("numberOfMipmapLevels " + std::to_string(levels) + " (at most " + std::to_string(max_levels) + ")");
  Texture t;
  t.format = fi->format;
  t.width = width;
  t.height = height;
  t.levels = levels == 0 ? 1 : levels;
  t.faces = faces;
  t.layers = std::max(elements, 1u);
  t.is_array = elements > 0;
  t.images.resize(std::size_t(t.levels) * t.layers * t.faces);
  std::uint64_t p = 64;
  r.at(p, kv, "key/value data");
  p += kv;
  const bool cube_only = t.faces == 6 && elements == 0;
  for (std::uint32_t l = 0; l < t.levels; ++l) {
    const std::uint32_t lw = t.level_width(l), lh = t.level_height(l);
    const std::uint64_t one = stored_image(*fi, lw, lh);
    const std::uint32_t image_size = r.u32(p, "imageSize");
    p += 4;
    const std::uint64_t want = cube_only ? one : one * t.layers * t.faces;
    if (image_size != want)
      r.fail("level " + std::to_string(l) + " imageSize " + std::to_string(image_size) + " (expected " +
             std::to_string(want) + ")");
    for (std::uint32_t a = 0; a < t.layers; ++a)
      for (std::uint32_t f = 0; f < t.faces; ++f) {
        const std::uint8_t* src = r.at(p, one, "image data");
        auto& img = t.image(l, a, f);
        if (fi->compressed) {
          img.assign(src, src + one);
        } else {
          const std::size_t row = std::size_t(lw) * fi->block_bytes;
          img.resize(row * lh);
          for (std::uint32_t y = 0; y < lh; ++y) std::memcpy(img.data() + y * row, src + y * stored_row(*fi, lw), row);
        }
        p += one;
        p = (p + 3) & ~std::uint64_t(3);
      }
    p = (p + 3) & ~std::uint64_t(3);
  }
  if (p != size)
    r.fail(p > size ? "truncated padding" : std::to_string(size - p) + " trailing bytes after the last level");
  // GL has one code for LDR and HDR ASTC (the profile is the context's): a
  // texture with an HDR block is SFLOAT.
  if (is_astc(t.format) && !fi->srgb) {
    for (const PixelBytes& img : t.images) {
      if (astc::has_hdr_blocks(img.data(), img.size(), fi->block_width, fi->block_height)) {
        t.format = astc_format(fi->block_width, fi->block_height, false, true);
        break;
      }
    }
  }
  return t;
}

}  // namespace texproc
