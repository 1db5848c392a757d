// The .astc file of ARM's astc-encoder CLI: a 16-byte header and one level of
// blocks, row by row (astcenc's file format, as its astcenccli_image_load_store
// reads it):
//   u8[4]  magic 0x13 0xAB 0xA1 0x5C (0x5CA1AB13 little-endian)
//   u8     block_x, block_y, block_z (texels; texproc writes 2D: block_z 1)
//   u8[3]  dim_x, u8[3] dim_y, u8[3] dim_z (texels, 24-bit little-endian)
// The header has no colour profile: UNORM, sRGB and HDR share it. texproc
// reads a file as UNORM, or SFLOAT when a block uses HDR endpoints.
#include <cstring>

#include "astc/astc_decode.h"
#include "container/bytes.h"
#include "container/streams.h"
#include "texproc/container.h"

namespace texproc {
namespace {
constexpr std::uint8_t kMagic[4] = {0x13, 0xAB, 0xA1, 0x5C};

void u24(ByteWriter& w, std::uint32_t v) {
  w.u8(std::uint8_t(v));
  w.u8(std::uint8_t(v >> 8));
  w.u8(std::uint8_t(v >> 16));
}
std::uint32_t get_u24(const ByteReader& r, std::size_t at, const char* field) {
  const std::uint8_t* p = r.at(at, 3, field);
  return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16;
}
}  // namespace

ByteWriter encode_astc_stream(const Texture& t) {
  validate(t);
  const FormatInfo& fi = format_info(t.format);
  if (!is_astc(t.format)) {
    throw Error(ErrorCode::unsupported,
                std::string(".astc holds ASTC blocks, not ") + fi.name + ": write .ktx2, .ktx or .dds");
  }
  if (t.levels != 1 || t.faces != 1 || t.layers != 1 || t.is_array) {
    throw Error(ErrorCode::unsupported,
                ".astc holds one level of one image: write .ktx2 or .ktx for mips, cubemaps, arrays");
  }
  if (t.width > 0xFFFFFF || t.height > 0xFFFFFF) throw Error(ErrorCode::unsupported, ".astc sizes are 24-bit");
  ByteWriter w;
  w.raw(kMagic, 4);
  w.u8(std::uint8_t(fi.block_width));
  w.u8(std::uint8_t(fi.block_height));
  w.u8(1);
  u24(w, t.width);
  u24(w, t.height);
  u24(w, 1);
  w.ref(t.images[0].data(), t.images[0].size());
  return w;
}

std::vector<std::uint8_t> encode_astc(const Texture& t) { return encode_astc_stream(t).bytes(); }

Texture decode_astc(const std::uint8_t* data, std::size_t size, const std::string& name, const ReadLimits& limits) {
  ByteReader r(data, size, name);
  if (size < 4 || std::memcmp(r.at(0, 4, "magic"), kMagic, 4) != 0) r.fail("not an .astc file (no 0x5CA1AB13 magic)");
  if (size < 16) r.fail("truncated: the header needs 16 bytes, the file has " + std::to_string(size));
  const std::uint8_t* b = r.at(4, 3, "block size");
  const std::uint32_t bx = b[0], by = b[1], bz = b[2];
  const std::uint32_t w = get_u24(r, 7, "dim_x"), h = get_u24(r, 10, "dim_y"), d = get_u24(r, 13, "dim_z");
  if (bz != 1 || d != 1) {
    if (bz == 0 || d == 0) r.fail("block depth and image depth must be at least 1");
    r.unsupported("3D ASTC (block " + std::to_string(bx) + "x" + std::to_string(by) + "x" + std::to_string(bz) +
                  ", depth " + std::to_string(d) + "): texproc reads 2D footprints");
  }
  Texture t;
  try {
    t.format = astc_format(int(bx), int(by), false, false);
  } catch (const Error& e) {
    r.fail(std::string("block size: ") + e.what());
  }
  t.width = w;
  t.height = h;
  if (w == 0 || h == 0) r.fail("zero width or height");
  // The blocks the header declares must be the file's: a header that lies
  // about its size is malformed (3) before it is too large (5).
  const std::uint64_t bytes = image_bytes(t.format, w, h);
  if (size - 16 != bytes) {
    r.fail(size - 16 < bytes ? "truncated block data: " + std::to_string(w) + "x" + std::to_string(h) + " needs " +
                                   std::to_string(bytes) + " bytes of blocks, the file has " + std::to_string(size - 16)
                             : std::to_string(size - 16 - bytes) + " trailing bytes");
  }
  if (w > limits.max_texture_dimension || h > limits.max_texture_dimension) {
    r.unsupported("texture " + std::to_string(w) + "x" + std::to_string(h) + " is larger than the limit " +
                  std::to_string(limits.max_texture_dimension));
  }
  const std::uint8_t* p = r.at(16, bytes, "block data");
  if (astc::has_hdr_blocks(p, bytes, int(bx), int(by))) t.format = astc_format(int(bx), int(by), false, true);
  t.images.emplace_back(p, p + bytes);
  return t;
}

}  // namespace texproc
