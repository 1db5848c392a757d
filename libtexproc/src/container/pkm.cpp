// PKM, the ETC container of Android's etc1tool and of etc2comp: a 16-byte
// big-endian header ("PKM ", version "10" for ETC1 or "20" for ETC2, data
// type, extended and original sizes) and one level of blocks.
#include <cstdio>
#include <cstring>

#include "container/bytes.h"
#include "container/streams.h"
#include "texproc/container.h"

namespace texproc {
namespace {
void be16(ByteWriter& w, std::uint32_t v) {
  w.u8(std::uint8_t(v >> 8));
  w.u8(std::uint8_t(v));
}
std::uint32_t get_be16(const ByteReader& r, std::size_t at, const char* field) {
  const std::uint8_t* p = r.at(at, 2, field);
  return std::uint32_t(p[0]) << 8 | p[1];
}
}  // namespace

ByteWriter encode_pkm_stream(const Texture& t) {
  validate(t);
  if (t.format != TexelFormat::etc1_rgb && t.format != TexelFormat::etc2_rgb_unorm) {
    throw Error(ErrorCode::unsupported,
                std::string("PKM holds ETC1 and ETC2 RGB only, not ") + format_info(t.format).name +
                    ": write .ktx2 or .ktx" +
                    (t.format == TexelFormat::etc2_rgb_srgb ? ", or add --linear (PKM has no sRGB)" : ""));
  }
  if (t.levels != 1 || t.faces != 1 || t.layers != 1) {
    throw Error(ErrorCode::unsupported,
                "PKM holds one level of one image: write .ktx2 or .ktx for mips, cubemaps, arrays");
  }
  if (t.width > 65535 || t.height > 65535) throw Error(ErrorCode::unsupported, "PKM sizes are 16-bit");
  const bool etc1 = t.format == TexelFormat::etc1_rgb;
  ByteWriter w;
  w.raw("PKM ", 4);
  w.raw(etc1 ? "10" : "20", 2);
  be16(w, etc1 ? 0 : 1);  // ETC1_RGB_NO_MIPMAPS, or ETC2 RGB
  be16(w, (t.width + 3) & ~3u);
  be16(w, (t.height + 3) & ~3u);
  be16(w, t.width);
  be16(w, t.height);
  w.raw(t.images[0].data(), t.images[0].size());
  return w;
}

std::vector<std::uint8_t> encode_pkm(const Texture& t) { return encode_pkm_stream(t).bytes(); }

Texture decode_pkm(const std::uint8_t* data, std::size_t size, const std::string& name, const ReadLimits& limits) {
  ByteReader r(data, size, name);
  if (size < 4 || std::memcmp(r.at(0, 4, "magic"), "PKM ", 4) != 0) r.fail("not a PKM file (no \"PKM \" magic)");
  if (size < 16) r.fail("truncated: the header needs 16 bytes, the file has " + std::to_string(size));
  const std::uint8_t* version = r.at(4, 2, "version");
  const std::uint32_t type = get_be16(r, 6, "data type");
  Texture t;
  if (version[0] == '1' && version[1] == '0' && type == 0) {
    t.format = TexelFormat::etc1_rgb;
  } else if (version[0] == '2' && version[1] == '0' && type == 1) {
    t.format = TexelFormat::etc2_rgb_unorm;
  } else {
    auto shown = [](std::uint8_t c) {
      char b[8];
      if (c >= 0x20 && c < 0x7f) return std::string(1, char(c));
      std::snprintf(b, sizeof b, "\\x%02X", unsigned(c));
      return std::string(b);
    };
    r.unsupported("PKM version '" + shown(version[0]) + shown(version[1]) + "' data type " + std::to_string(type) +
                  " (texproc reads ETC1 \"10\"/0 and ETC2 RGB \"20\"/1)");
  }
  const std::uint32_t ew = get_be16(r, 8, "extended width"), eh = get_be16(r, 10, "extended height");
  t.width = get_be16(r, 12, "width");
  t.height = get_be16(r, 14, "height");
  if (t.width == 0 || t.height == 0) r.fail("zero width or height");
  if (t.width > limits.max_texture_dimension || t.height > limits.max_texture_dimension)
    r.unsupported("texture larger than the limit");
  if (ew != ((t.width + 3) & ~3u) || eh != ((t.height + 3) & ~3u)) r.fail("extended size does not match the size");
  const std::uint64_t bytes = image_bytes(t.format, t.width, t.height);
  if (size - 16 != bytes) {
    r.fail(size - 16 < bytes ? "truncated block data" : std::to_string(size - 16 - bytes) + " trailing bytes");
  }
  const std::uint8_t* p = r.at(16, bytes, "block data");
  t.images.emplace_back(p, p + bytes);
  return t;
}

}  // namespace texproc
