// The texel-format table: block sizes and the codes of every API and
// container, in one place. VkFormat values from the Vulkan registry,
// DXGI_FORMAT from dxgiformat.h, GL enums from the KTX 1.1 specification
// and the GL registry.
#include <Imath/half.h>

#include <cassert>
#include <cctype>
#include <cstring>

#include "format/format_names.h"
#include "texproc/error.h"
#include "texproc/runtime.h"
#include "texproc/texture.h"

namespace texproc {
namespace {

constexpr std::uint32_t kGlRed = 0x1903, kGlRg = 0x8227, kGlRgba = 0x1908, kGlBgra = 0x80E1;
constexpr std::uint32_t kGlUByte = 0x1401, kGlUShort = 0x1403, kGlHalf = 0x140B, kGlFloat = 0x1406;

using F = TexelFormat;
// format, name, block w, h, bytes, channels, srgb, snorm, float, compressed, typeSize, vk, dxgi, gl internal, gl
// format, gl type
using Family = CodecFamily;
const FormatInfo kFormats[] = {
    {F::r8_unorm, "r8_unorm", Family::uncompressed, 1, 1, 1, 1, false, false, false, false, 1, 9, 61, 0x8229, kGlRed,
     kGlUByte},
    {F::r8_srgb, "r8_srgb", Family::uncompressed, 1, 1, 1, 1, true, false, false, false, 1, 15, 0, 0x8FBD, kGlRed,
     kGlUByte},
    {F::rg8_unorm, "rg8_unorm", Family::uncompressed, 1, 1, 2, 2, false, false, false, false, 1, 16, 49, 0x822B, kGlRg,
     kGlUByte},
    {F::rg8_srgb, "rg8_srgb", Family::uncompressed, 1, 1, 2, 2, true, false, false, false, 1, 22, 0, 0x8FBE, kGlRg,
     kGlUByte},
    {F::rgba8_unorm, "rgba8_unorm", Family::uncompressed, 1, 1, 4, 4, false, false, false, false, 1, 37, 28, 0x8058,
     kGlRgba, kGlUByte},
    {F::rgba8_srgb, "rgba8_srgb", Family::uncompressed, 1, 1, 4, 4, true, false, false, false, 1, 43, 29, 0x8C43,
     kGlRgba, kGlUByte},
    {F::bgra8_unorm, "bgra8_unorm", Family::uncompressed, 1, 1, 4, 4, false, false, false, false, 1, 44, 87, 0x93A1,
     kGlBgra, kGlUByte},
    {F::bgra8_srgb, "bgra8_srgb", Family::uncompressed, 1, 1, 4, 4, true, false, false, false, 1, 50, 91, 0, kGlBgra,
     kGlUByte},
    {F::r16_unorm, "r16_unorm", Family::uncompressed, 1, 1, 2, 1, false, false, false, false, 2, 70, 56, 0x822A, kGlRed,
     kGlUShort},
    {F::rg16_unorm, "rg16_unorm", Family::uncompressed, 1, 1, 4, 2, false, false, false, false, 2, 77, 35, 0x822C,
     kGlRg, kGlUShort},
    {F::rgba16_unorm, "rgba16_unorm", Family::uncompressed, 1, 1, 8, 4, false, false, false, false, 2, 91, 11, 0x805B,
     kGlRgba, kGlUShort},
    {F::rgba16_float, "rgba16_float", Family::uncompressed, 1, 1, 8, 4, false, false, true, false, 2, 97, 10, 0x881A,
     kGlRgba, kGlHalf},
    {F::rgba32_float, "rgba32_float", Family::uncompressed, 1, 1, 16, 4, false, false, true, false, 4, 109, 2, 0x8814,
     kGlRgba, kGlFloat},
    {F::bc1_rgb_unorm, "bc1_rgb_unorm", Family::bc1, 4, 4, 8, 3, false, false, false, true, 1, 131, 71, 0x83F0, 0, 0},
    {F::bc1_rgb_srgb, "bc1_rgb_srgb", Family::bc1, 4, 4, 8, 3, true, false, false, true, 1, 132, 72, 0x8C4C, 0, 0},
    {F::bc1_rgba_unorm, "bc1_rgba_unorm", Family::bc1, 4, 4, 8, 4, false, false, false, true, 1, 133, 71, 0x83F1, 0, 0},
    {F::bc1_rgba_srgb, "bc1_rgba_srgb", Family::bc1, 4, 4, 8, 4, true, false, false, true, 1, 134, 72, 0x8C4D, 0, 0},
    {F::bc2_unorm, "bc2_unorm", Family::bc2, 4, 4, 16, 4, false, false, false, true, 1, 135, 74, 0x83F2, 0, 0},
    {F::bc2_srgb, "bc2_srgb", Family::bc2, 4, 4, 16, 4, true, false, false, true, 1, 136, 75, 0x8C4E, 0, 0},
    {F::bc3_unorm, "bc3_unorm", Family::bc3, 4, 4, 16, 4, false, false, false, true, 1, 137, 77, 0x83F3, 0, 0},
    {F::bc3_srgb, "bc3_srgb", Family::bc3, 4, 4, 16, 4, true, false, false, true, 1, 138, 78, 0x8C4F, 0, 0},
    {F::bc4_unorm, "bc4_unorm", Family::bc4, 4, 4, 8, 1, false, false, false, true, 1, 139, 80, 0x8DBB, 0, 0},
    {F::bc4_snorm, "bc4_snorm", Family::bc4, 4, 4, 8, 1, false, true, false, true, 1, 140, 81, 0x8DBC, 0, 0},
    {F::bc5_unorm, "bc5_unorm", Family::bc5, 4, 4, 16, 2, false, false, false, true, 1, 141, 83, 0x8DBD, 0, 0},
    {F::bc5_snorm, "bc5_snorm", Family::bc5, 4, 4, 16, 2, false, true, false, true, 1, 142, 84, 0x8DBE, 0, 0},
    {F::bc6h_ufloat, "bc6h_ufloat", Family::bc6h, 4, 4, 16, 3, false, false, true, true, 1, 143, 95, 0x8E8F, 0, 0},
    {F::bc6h_sfloat, "bc6h_sfloat", Family::bc6h, 4, 4, 16, 3, false, false, true, true, 1, 144, 96, 0x8E8E, 0, 0},
    {F::bc7_unorm, "bc7_unorm", Family::bc7, 4, 4, 16, 4, false, false, false, true, 1, 145, 98, 0x8E8C, 0, 0},
    {F::bc7_srgb, "bc7_srgb", Family::bc7, 4, 4, 16, 4, true, false, false, true, 1, 146, 99, 0x8E8D, 0, 0},
    {F::etc1_rgb, "etc1_rgb", Family::etc1, 4, 4, 8, 3, false, false, false, true, 1, 147, 0, 0x8D64, 0, 0},
    {F::etc2_rgb_unorm, "etc2_rgb_unorm", Family::etc2, 4, 4, 8, 3, false, false, false, true, 1, 147, 0, 0x9274, 0, 0},
    {F::etc2_rgb_srgb, "etc2_rgb_srgb", Family::etc2, 4, 4, 8, 3, true, false, false, true, 1, 148, 0, 0x9275, 0, 0},
    {F::etc2_rgba1_unorm, "etc2_rgba1_unorm", Family::etc2, 4, 4, 8, 4, false, false, false, true, 1, 149, 0, 0x9276, 0,
     0},
    {F::etc2_rgba1_srgb, "etc2_rgba1_srgb", Family::etc2, 4, 4, 8, 4, true, false, false, true, 1, 150, 0, 0x9277, 0,
     0},
    {F::etc2_rgba8_unorm, "etc2_rgba8_unorm", Family::etc2, 4, 4, 16, 4, false, false, false, true, 1, 151, 0, 0x9278,
     0, 0},
    {F::etc2_rgba8_srgb, "etc2_rgba8_srgb", Family::etc2, 4, 4, 16, 4, true, false, false, true, 1, 152, 0, 0x9279, 0,
     0},
    {F::eac_r11_unorm, "eac_r11_unorm", Family::eac, 4, 4, 8, 1, false, false, false, true, 1, 153, 0, 0x9270, 0, 0},
    {F::eac_r11_snorm, "eac_r11_snorm", Family::eac, 4, 4, 8, 1, false, true, false, true, 1, 154, 0, 0x9271, 0, 0},
    {F::eac_rg11_unorm, "eac_rg11_unorm", Family::eac, 4, 4, 16, 2, false, false, false, true, 1, 155, 0, 0x9272, 0, 0},
    {F::eac_rg11_snorm, "eac_rg11_snorm", Family::eac, 4, 4, 16, 2, false, true, false, true, 1, 156, 0, 0x9273, 0, 0},
    {F::astc_4x4_unorm, "astc_4x4_unorm", Family::astc, 4, 4, 16, 4, false, false, false, true, 1, 157, 0, 0x93B0, 0,
     0},
    {F::astc_4x4_srgb, "astc_4x4_srgb", Family::astc, 4, 4, 16, 4, true, false, false, true, 1, 158, 0, 0x93D0, 0, 0},
    {F::astc_4x4_sfloat, "astc_4x4_sfloat", Family::astc, 4, 4, 16, 4, false, false, true, true, 1, 1000066000u, 0,
     0x93B0, 0, 0},
    {F::astc_5x4_unorm, "astc_5x4_unorm", Family::astc, 5, 4, 16, 4, false, false, false, true, 1, 159, 0, 0x93B1, 0,
     0},
    {F::astc_5x4_srgb, "astc_5x4_srgb", Family::astc, 5, 4, 16, 4, true, false, false, true, 1, 160, 0, 0x93D1, 0, 0},
    {F::astc_5x4_sfloat, "astc_5x4_sfloat", Family::astc, 5, 4, 16, 4, false, false, true, true, 1, 1000066001u, 0,
     0x93B1, 0, 0},
    {F::astc_5x5_unorm, "astc_5x5_unorm", Family::astc, 5, 5, 16, 4, false, false, false, true, 1, 161, 0, 0x93B2, 0,
     0},
    {F::astc_5x5_srgb, "astc_5x5_srgb", Family::astc, 5, 5, 16, 4, true, false, false, true, 1, 162, 0, 0x93D2, 0, 0},
    {F::astc_5x5_sfloat, "astc_5x5_sfloat", Family::astc, 5, 5, 16, 4, false, false, true, true, 1, 1000066002u, 0,
     0x93B2, 0, 0},
    {F::astc_6x5_unorm, "astc_6x5_unorm", Family::astc, 6, 5, 16, 4, false, false, false, true, 1, 163, 0, 0x93B3, 0,
     0},
    {F::astc_6x5_srgb, "astc_6x5_srgb", Family::astc, 6, 5, 16, 4, true, false, false, true, 1, 164, 0, 0x93D3, 0, 0},
    {F::astc_6x5_sfloat, "astc_6x5_sfloat", Family::astc, 6, 5, 16, 4, false, false, true, true, 1, 1000066003u, 0,
     0x93B3, 0, 0},
    {F::astc_6x6_unorm, "astc_6x6_unorm", Family::astc, 6, 6, 16, 4, false, false, false, true, 1, 165, 0, 0x93B4, 0,
     0},
    {F::astc_6x6_srgb, "astc_6x6_srgb", Family::astc, 6, 6, 16, 4, true, false, false, true, 1, 166, 0, 0x93D4, 0, 0},
    {F::astc_6x6_sfloat, "astc_6x6_sfloat", Family::astc, 6, 6, 16, 4, false, false, true, true, 1, 1000066004u, 0,
     0x93B4, 0, 0},
    {F::astc_8x5_unorm, "astc_8x5_unorm", Family::astc, 8, 5, 16, 4, false, false, false, true, 1, 167, 0, 0x93B5, 0,
     0},
    {F::astc_8x5_srgb, "astc_8x5_srgb", Family::astc, 8, 5, 16, 4, true, false, false, true, 1, 168, 0, 0x93D5, 0, 0},
    {F::astc_8x5_sfloat, "astc_8x5_sfloat", Family::astc, 8, 5, 16, 4, false, false, true, true, 1, 1000066005u, 0,
     0x93B5, 0, 0},
    {F::astc_8x6_unorm, "astc_8x6_unorm", Family::astc, 8, 6, 16, 4, false, false, false, true, 1, 169, 0, 0x93B6, 0,
     0},
    {F::astc_8x6_srgb, "astc_8x6_srgb", Family::astc, 8, 6, 16, 4, true, false, false, true, 1, 170, 0, 0x93D6, 0, 0},
    {F::astc_8x6_sfloat, "astc_8x6_sfloat", Family::astc, 8, 6, 16, 4, false, false, true, true, 1, 1000066006u, 0,
     0x93B6, 0, 0},
    {F::astc_8x8_unorm, "astc_8x8_unorm", Family::astc, 8, 8, 16, 4, false, false, false, true, 1, 171, 0, 0x93B7, 0,
     0},
    {F::astc_8x8_srgb, "astc_8x8_srgb", Family::astc, 8, 8, 16, 4, true, false, false, true, 1, 172, 0, 0x93D7, 0, 0},
    {F::astc_8x8_sfloat, "astc_8x8_sfloat", Family::astc, 8, 8, 16, 4, false, false, true, true, 1, 1000066007u, 0,
     0x93B7, 0, 0},
    {F::astc_10x5_unorm, "astc_10x5_unorm", Family::astc, 10, 5, 16, 4, false, false, false, true, 1, 173, 0, 0x93B8, 0,
     0},
    {F::astc_10x5_srgb, "astc_10x5_srgb", Family::astc, 10, 5, 16, 4, true, false, false, true, 1, 174, 0, 0x93D8, 0,
     0},
    {F::astc_10x5_sfloat, "astc_10x5_sfloat", Family::astc, 10, 5, 16, 4, false, false, true, true, 1, 1000066008u, 0,
     0x93B8, 0, 0},
    {F::astc_10x6_unorm, "astc_10x6_unorm", Family::astc, 10, 6, 16, 4, false, false, false, true, 1, 175, 0, 0x93B9, 0,
     0},
    {F::astc_10x6_srgb, "astc_10x6_srgb", Family::astc, 10, 6, 16, 4, true, false, false, true, 1, 176, 0, 0x93D9, 0,
     0},
    {F::astc_10x6_sfloat, "astc_10x6_sfloat", Family::astc, 10, 6, 16, 4, false, false, true, true, 1, 1000066009u, 0,
     0x93B9, 0, 0},
    {F::astc_10x8_unorm, "astc_10x8_unorm", Family::astc, 10, 8, 16, 4, false, false, false, true, 1, 177, 0, 0x93BA, 0,
     0},
    {F::astc_10x8_srgb, "astc_10x8_srgb", Family::astc, 10, 8, 16, 4, true, false, false, true, 1, 178, 0, 0x93DA, 0,
     0},
    {F::astc_10x8_sfloat, "astc_10x8_sfloat", Family::astc, 10, 8, 16, 4, false, false, true, true, 1, 1000066010u, 0,
     0x93BA, 0, 0},
    {F::astc_10x10_unorm, "astc_10x10_unorm", Family::astc, 10, 10, 16, 4, false, false, false, true, 1, 179, 0, 0x93BB,
     0, 0},
    {F::astc_10x10_srgb, "astc_10x10_srgb", Family::astc, 10, 10, 16, 4, true, false, false, true, 1, 180, 0, 0x93DB, 0,
     0},
    {F::astc_10x10_sfloat, "astc_10x10_sfloat", Family::astc, 10, 10, 16, 4, false, false, true, true, 1, 1000066011u,
     0, 0x93BB, 0, 0},
    {F::astc_12x10_unorm, "astc_12x10_unorm", Family::astc, 12, 10, 16, 4, false, false, false, true, 1, 181, 0, 0x93BC,
     0, 0},
    {F::astc_12x10_srgb, "astc_12x10_srgb", Family::astc, 12, 10, 16, 4, true, false, false, true, 1, 182, 0, 0x93DC, 0,
     0},
    {F::astc_12x10_sfloat, "astc_12x10_sfloat", Family::astc, 12, 10, 16, 4, false, false, true, true, 1, 1000066012u,
     0, 0x93BC, 0, 0},
    {F::astc_12x12_unorm, "astc_12x12_unorm", Family::astc, 12, 12, 16, 4, false, false, false, true, 1, 183, 0, 0x93BD,
     0, 0},
    {F::astc_12x12_srgb, "astc_12x12_srgb", Family::astc, 12, 12, 16, 4, true, false, false, true, 1, 184, 0, 0x93DD, 0,
     0},
    {F::astc_12x12_sfloat, "astc_12x12_sfloat", Family::astc, 12, 12, 16, 4, false, false, true, true, 1, 1000066013u,
     0, 0x93BD, 0, 0},
};

}  // namespace

const FormatInfo& format_info(TexelFormat f) {
  for (const auto& i : kFormats) {
    if (i.format == f) return i;
  }
  assert(false && "format missing from the table");
  return kFormats[0];
}

bool is_astc(TexelFormat f) { return format_info(f).family == CodecFamily::astc; }

const char* to_string(CodecFamily family) {
  switch (family) {
    case CodecFamily::uncompressed:
      return "uncompressed";
    case CodecFamily::bc1:
      return "bc1";
    case CodecFamily::bc2:
      return "bc2";
    case CodecFamily::bc3:
      return "bc3";
    case CodecFamily::bc4:
      return "bc4";
    case CodecFamily::bc5:
      return "bc5";
    case CodecFamily::bc6h:
      return "bc6h";
    case CodecFamily::bc7:
      return "bc7";
    case CodecFamily::etc1:
      return "etc1";
    case CodecFamily::etc2:
      return "etc2";
    case CodecFamily::eac:
      return "eac";
    case CodecFamily::astc:
      return "astc";
  }
  return "?";
}

TexelFormat astc_format(int block_width, int block_height, bool srgb, bool hdr) {
  for (const auto& i : kFormats) {
    if (is_astc(i.format) && i.block_width == block_width && i.block_height == block_height && i.srgb == srgb &&
        i.is_float == hdr)
      return i.format;
  }
  throw Error(ErrorCode::bad_arguments, "ASTC has no " + std::to_string(block_width) + "x" +
                                            std::to_string(block_height) +
                                            (hdr    ? " HDR"
                                             : srgb ? " sRGB"
                                                    : "") +
                                            " footprint (valid: 4x4, 5x4, 5x5, 6x5, 6x6, 8x5, 8x6, 8x8, 10x5, "
                                            "10x6, 10x8, 10x10, 12x10, 12x12)");
}

const FormatInfo* find_format_by_vk(std::uint32_t vk) {
  for (const auto& i : kFormats) {
    if (i.vk_format == vk && i.format != F::etc1_rgb) return &i;  // 147 is ETC2 RGB
  }
  return nullptr;
}

const FormatInfo* find_format_by_dxgi(std::uint32_t dxgi) {
  if (dxgi == 0) return nullptr;
  // DXGI has one BC1 per color space, which may carry 1-bit alpha.
  if (dxgi == 71) return &format_info(F::bc1_rgba_unorm);
  if (dxgi == 72) return &format_info(F::bc1_rgba_srgb);
  for (const auto& i : kFormats) {
    if (i.dxgi_format == dxgi) return &i;
  }
  return nullptr;
}

const FormatInfo* find_format_by_gl(std::uint32_t gl) {
  if (gl == 0) return nullptr;
  for (const auto& i : kFormats) {
    if (i.gl_internal_format == gl) return &i;
  }
  return nullptr;
}

std::vector<std::string> texel_format_names() {
  std::vector<std::string> v;
  for (const auto& i : kFormats) v.emplace_back(i.name);
  return v;
}

TexelFormat parse_texel_format(std::string_view name) {
  // texproc's names, DXGI's (DXGI_FORMAT_ optional) and Vulkan's (VK_FORMAT_
  // optional), in any case; the first format of the table where two share
  // a name (DXGI's BC1_UNORM: opaque BC1).
  std::string n(name);
  for (char& c : n) c = char(std::toupper(static_cast<unsigned char>(c)));
  for (const char* prefix : {"DXGI_FORMAT_", "VK_FORMAT_"}) {
    if (n.rfind(prefix, 0) == 0) n.erase(0, std::strlen(prefix));
  }
  auto upper = [](std::string s) {
    for (char& c : s) c = char(std::toupper(static_cast<unsigned char>(c)));
    return s;
  };
  for (const auto& i : kFormats) {
    if (n == upper(i.name)) return i.format;
  }
  for (const auto& i : kFormats) {
    // (ETC1 has no Vulkan name of its own: Vulkan's ETC2 RGB name is ETC2's.)
    const bool vk = i.format != TexelFormat::etc1_rgb && n == upper(vk_format_name(i.vk_format));
    if ((i.dxgi_format && n == upper(dxgi_format_name(i.dxgi_format))) || vk) return i.format;
  }
  std::string valid;
  for (const auto& known : texel_format_names()) valid += (valid.empty() ? "" : ", ") + known;
  throw Error(ErrorCode::bad_arguments, "unknown texel format '" + std::string(name) + "' (valid: " + valid + ")");
}

std::uint64_t image_bytes(TexelFormat f, std::uint32_t width, std::uint32_t height) {
  const FormatInfo& i = format_info(f);
  const std::uint64_t bw = (std::uint64_t(width) + i.block_width - 1) / i.block_width;
  const std::uint64_t bh = (std::uint64_t(height) + i.block_height - 1) / i.block_height;
  // width, height < 2^32 and bytes <= 16: the product is below 2^68 only in
  // theory; callers limit sizes first. Guard anyway.
  if (bw && bh > (std::uint64_t(1) << 62) / bw / i.block_bytes) return 0;
  return bw * bh * i.block_bytes;
}

void validate(const Texture& t) {
  auto fail = [](const std::string& what) { throw Error(ErrorCode::bad_arguments, "invalid texture: " + what); };
  if (t.width == 0 || t.height == 0) fail("zero size");
  if (t.faces != 1 && t.faces != 6) fail("faces must be 1 or 6");
  if (t.faces == 6 && t.width != t.height) fail("cubemap faces must be square");
  if (t.layers == 0) fail("no layers");
  std::uint32_t max_levels = 1;
  for (std::uint32_t m = std::max(t.width, t.height); m > 1; m >>= 1) ++max_levels;
  if (t.levels == 0 || t.levels > max_levels) fail("level count " + std::to_string(t.levels));
  if (t.images.size() != std::size_t(t.levels) * t.layers * t.faces) fail("image count does not match");
  for (std::uint32_t l = 0; l < t.levels; ++l) {
    const std::uint64_t want = image_bytes(t.format, t.level_width(l), t.level_height(l));
    for (std::uint32_t a = 0; a < t.layers; ++a)
      for (std::uint32_t f = 0; f < t.faces; ++f) {
        if (t.image(l, a, f).size() != want) {
          fail("level " + std::to_string(l) + " holds " + std::to_string(t.image(l, a, f).size()) +
               " bytes, expected " + std::to_string(want));
        }
      }
  }
}

namespace {
Texture from_levels(const std::vector<Image>& levels, std::vector<Image>* steal, bool srgb, bool half) {
  if (levels.empty()) throw Error(ErrorCode::bad_arguments, "no levels");
  const Image& top = levels[0];
  const int C = top.channels();
  Texture t;
  t.width = std::uint32_t(top.width());
  t.height = std::uint32_t(top.height());
  t.levels = std::uint32_t(levels.size());
  switch (top.type()) {
    case PixelType::u8:
      t.format = C == 1 ? F::r8_unorm : C == 2 ? F::rg8_unorm : srgb ? F::rgba8_srgb : F::rgba8_unorm;
      break;
    case PixelType::u16:
      t.format = C == 1 ? F::r16_unorm : C == 2 ? F::rg16_unorm : F::rgba16_unorm;
      break;
    case PixelType::f32:
      t.format = half ? F::rgba16_float : F::rgba32_float;
      break;
  }
  const FormatInfo& info = format_info(t.format);
  for (const Image& im : levels) {
    const int out_c = info.channels;
    if (out_c == C && !(top.type() == PixelType::f32 && half)) {
      // Stored as in memory: the buffer itself, or one copy with no zero-fill first.
      if (steal) {
        t.images.emplace_back(std::move((*steal)[std::size_t(&im - levels.data())]).release());
      } else {
        t.images.emplace_back(im.data(), im.data() + im.byte_size());
      }
      continue;
    }
    PixelBytes bytes(std::size_t(im.width()) * im.height() * info.block_bytes);
    for_each_row_block(im.height(), 64, [&](int y0, int y1) {
      for (int y = y0; y < y1; ++y)
        for (int x = 0; x < im.width(); ++x) {
          const std::size_t o = (std::size_t(y) * im.width() + x) * out_c;
          for (int c = 0; c < out_c; ++c) {
            // 3 -> 4 channels: alpha 1; float 1/2 channels: gray to RGB, alpha.
            const bool have = c < C && !(C < 4 && out_c == 4 && c == 3 && C != 2);
            switch (top.type()) {
              case PixelType::u8: {
                std::uint8_t v = have ? im.row<std::uint8_t>(y)[x * C + c] : 255;
                bytes[o + c] = v;
                break;
              }
              case PixelType::u16: {
                std::uint16_t v = have ? im.row<std::uint16_t>(y)[x * C + c] : 65535;
                std::memcpy(bytes.data() + (o + c) * 2, &v, 2);
                break;
              }
              case PixelType::f32: {
                const float* p = im.row<float>(y) + x * C;
                float v = c == 3 ? (C == 2 || C == 4 ? p[C - 1] : 1.0f) : (C <= 2 ? p[0] : p[c]);
                if (half) {
                  const Imath::half h(v);
                  const std::uint16_t bits = h.bits();
                  std::memcpy(bytes.data() + (o + c) * 2, &bits, 2);
                } else {
                  std::memcpy(bytes.data() + (o + c) * 4, &v, 4);
                }
                break;
              }
            }
          }
        }
    });
    t.images.push_back(std::move(bytes));
  }
  validate(t);
  return t;
}
}  // namespace

Texture texture_from_levels(const std::vector<Image>& levels, const UncompressedOptions& options) {
  return from_levels(levels, nullptr, options.srgb, options.half);
}

Texture texture_from_surfaces(std::vector<std::vector<Image>>&& chains, const SurfaceLayout& layout,
                              const UncompressedOptions& options) {
  const std::uint32_t faces = layout.faces, layers = layout.layers;
  if (chains.empty() || chains.size() != std::size_t(faces) * layers) {
    throw Error(ErrorCode::bad_arguments, "texture_from_surfaces: " + std::to_string(chains.size()) + " chains for " +
                                              std::to_string(faces) + " faces x " + std::to_string(layers) + " layers");
  }
  std::vector<Texture> each;
  for (auto& c : chains) each.push_back(texture_from_levels(std::move(c), options));
  Texture t = each[0];
  t.images.clear();
  t.faces = faces;
  t.layers = layers;
  t.is_array = layout.is_array;
  for (const Texture& e : each) {
    if (e.format != t.format || e.width != t.width || e.height != t.height || e.levels != t.levels) {
      throw Error(ErrorCode::bad_arguments, "texture_from_surfaces: the surfaces differ in size or format");
    }
  }
  for (std::uint32_t l = 0; l < t.levels; ++l)
    for (auto& e : each) t.images.push_back(std::move(e.images[l]));
  validate(t);
  return t;
}

Texture texture_from_levels(std::vector<Image>&& levels, const UncompressedOptions& options) {
  if (levels.empty()) throw Error(ErrorCode::bad_arguments, "no levels");
  // The fast path reads sizes from `levels` before taking each buffer.
  const std::vector<Image>& view = levels;
  Texture t = from_levels(view, &levels, options.srgb, options.half);
  levels.clear();
  return t;
}

Image image_from_texture(const Texture& t, std::uint32_t level, std::uint32_t layer, std::uint32_t face) {
  const FormatInfo& info = format_info(t.format);
  if (info.compressed) {
    throw Error(ErrorCode::unsupported, std::string(info.name) + " is block-compressed: decompress it first");
  }
  const int w = int(t.level_width(level)), h = int(t.level_height(level)), C = info.channels;
  const PixelBytes& src = t.image(level, layer, face);
  const PixelType type = info.is_float ? PixelType::f32 : info.type_size == 2 ? PixelType::u16 : PixelType::u8;
  Image out = Image::uninitialized(w, h, C, type);
  const bool bgra = t.format == F::bgra8_unorm || t.format == F::bgra8_srgb;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < C; ++c) {
        const int sc = bgra && c < 3 ? 2 - c : c;
        const std::size_t i = (std::size_t(y) * w + x) * C + sc;
        switch (type) {
          case PixelType::u8:
            out.row<std::uint8_t>(y)[x * C + c] = src[i];
            break;
          case PixelType::u16:
            std::memcpy(out.row<std::uint16_t>(y) + x * C + c, src.data() + 2 * i, 2);
            break;
          case PixelType::f32:
            if (t.format == F::rgba16_float) {
              std::uint16_t bits;
              std::memcpy(&bits, src.data() + 2 * i, 2);
              Imath::half hv;
              hv.setBits(bits);
              out.row<float>(y)[x * C + c] = float(hv);
            } else {
              std::memcpy(out.row<float>(y) + x * C + c, src.data() + 4 * i, 4);
            }
            break;
        }
      }
  return out;
}

}  // namespace texproc
