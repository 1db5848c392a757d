// DDS: the legacy header whenever a FourCC or masks can say the format, the
// DX10 extension when the format needs it (sRGB, SNORM, float, arrays).
// Layout per Microsoft's "DDS_HEADER" and "DDS_HEADER_DXT10" references:
// "DDS " magic, a 124-byte header with a 32-byte pixel format, optionally a
// 20-byte DX10 header, then for each array element (cube face) its whole
// mip chain, top level first.
#include <algorithm>

#include "container/bytes.h"
#include "format/format_names.h"
#include "container/streams.h"
#include "texproc/container.h"

namespace texproc {
namespace {

constexpr std::uint32_t kMagic = 0x20534444;  // "DDS "
constexpr std::uint32_t kHeaderSize = 124, kPixelFormatSize = 32;
// dwFlags
constexpr std::uint32_t kCaps = 0x1, kHeight = 0x2, kWidth = 0x4, kPitch = 0x8, kPixelFormat = 0x1000,
                        kMipMapCount = 0x20000, kLinearSize = 0x80000;
// ddspf.dwFlags
constexpr std::uint32_t kAlphaPixels = 0x1, kFourCC = 0x4, kRgb = 0x40, kLuminance = 0x20000;
// dwCaps, dwCaps2
constexpr std::uint32_t kCapsComplex = 0x8, kCapsTexture = 0x1000, kCapsMipMap = 0x400000;
constexpr std::uint32_t kCaps2Cubemap = 0x200, kCaps2AllFaces = 0xFC00;
// DX10
constexpr std::uint32_t kDimensionTexture2D = 3, kMiscTextureCube = 0x4;
constexpr std::uint32_t kAlphaModeStraight = 1;

constexpr std::uint32_t fourcc(const char (&s)[5]) {
  return std::uint32_t(s[0]) | std::uint32_t(s[1]) << 8 | std::uint32_t(s[2]) << 16 | std::uint32_t(s[3]) << 24;
}

// What the legacy pixel format can say (DirectXTex's DDSPF_* set, the
// subset texproc writes; the reader accepts the same).
struct LegacyFormat {
  TexelFormat format;
  std::uint32_t flags, fourcc, bits, r, g, b, a;
};
const LegacyFormat kLegacy[] = {
    {TexelFormat::bc1_rgba_unorm, kFourCC, fourcc("DXT1"), 0, 0, 0, 0, 0},
    {TexelFormat::bc2_unorm, kFourCC, fourcc("DXT3"), 0, 0, 0, 0, 0},
    {TexelFormat::bc3_unorm, kFourCC, fourcc("DXT5"), 0, 0, 0, 0, 0},
    {TexelFormat::bc4_unorm, kFourCC, fourcc("ATI1"), 0, 0, 0, 0, 0},
    {TexelFormat::bc5_unorm, kFourCC, fourcc("ATI2"), 0, 0, 0, 0, 0},
    {TexelFormat::rgba8_unorm, kRgb | kAlphaPixels, 0, 32, 0xFF, 0xFF00, 0xFF0000, 0xFF000000},
    {TexelFormat::bgra8_unorm, kRgb | kAlphaPixels, 0, 32, 0xFF0000, 0xFF00, 0xFF, 0xFF000000},
    {TexelFormat::r8_unorm, kLuminance, 0, 8, 0xFF, 0, 0, 0},
    {TexelFormat::rg8_unorm, kLuminance | kAlphaPixels, 0, 16, 0xFF, 0, 0, 0xFF00},
    {TexelFormat::r16_unorm, kLuminance, 0, 16, 0xFFFF, 0, 0, 0},
    {TexelFormat::rg16_unorm, kRgb, 0, 32, 0xFFFF, 0xFFFF0000, 0, 0},
};
// Readers also meet these FourCCs for formats texproc writes with DX10.
struct ExtraFourCC {
  std::uint32_t code;
  TexelFormat format;
};
const ExtraFourCC kExtraFourCC[] = {
    {fourcc("BC4U"), TexelFormat::bc4_unorm}, {fourcc("BC4S"), TexelFormat::bc4_snorm},
    {fourcc("BC5U"), TexelFormat::bc5_unorm}, {fourcc("BC5S"), TexelFormat::bc5_snorm},
    {36, TexelFormat::rgba16_unorm},          {113, TexelFormat::rgba16_float},
    {116, TexelFormat::rgba32_float},
};

const LegacyFormat* legacy_for(TexelFormat f) {
  // bc1_rgb_* is DXGI BC1 too: written as DXT1.
  if (f == TexelFormat::bc1_rgb_unorm) f = TexelFormat::bc1_rgba_unorm;
  for (const auto& l : kLegacy) {
    if (l.format == f) return &l;
  }
  return nullptr;
}

std::uint32_t dxgi_for(TexelFormat f) { return format_info(f).dxgi_format; }

}  // namespace

ByteWriter encode_dds_stream(const Texture& t, DdsHeader header) {
  validate(t);
  const FormatInfo& info = format_info(t.format);
  if (info.dxgi_format == 0) {
    throw Error(ErrorCode::unsupported,
                std::string("DDS cannot hold ") + info.name +
                    (is_astc(t.format) ? " (Direct3D has no ASTC formats): write .ktx2, .ktx or .astc"
                                       : " (Direct3D has no ETC formats): write .ktx2, .ktx or .pkm"));
  }
  const LegacyFormat* legacy = legacy_for(t.format);
  // Asked for a legacy header: the D3DFMT codes that old readers take as FourCCs
  // (36 A16B16G16R16, 113 A16B16G16R16F, 116 A32B32G32R32F) say these too.
  static const LegacyFormat kNumbered[] = {{TexelFormat::rgba16_unorm, kFourCC, 36, 0, 0, 0, 0, 0},
                                           {TexelFormat::rgba16_float, kFourCC, 113, 0, 0, 0, 0, 0},
                                           {TexelFormat::rgba32_float, kFourCC, 116, 0, 0, 0, 0, 0}};
  if (!legacy && header == DdsHeader::dx9) {
    for (const LegacyFormat& n : kNumbered)
      if (n.format == t.format) legacy = &n;
  }
  const bool array = t.is_array || t.layers > 1;
  bool dx10 = header == DdsHeader::dx10 || (header == DdsHeader::automatic && (!legacy || array));
  if (header == DdsHeader::dx9 && (!legacy || array)) {
    throw Error(ErrorCode::unsupported, std::string("a legacy (DX9) DDS header cannot say ") + info.name +
                                            (array ? " arrays" : "") + ": use --dds-header dx10 or auto" +
                                            (info.srgb ? ", or --linear for the UNORM format (DX9 has no sRGB)" : ""));
  }
  const bool mips = t.levels > 1;
  const bool cube = t.faces == 6;
  ByteWriter w;
  w.u32(kMagic);
  w.u32(kHeaderSize);
  std::uint32_t flags = kCaps | kHeight | kWidth | kPixelFormat;
  if (mips) flags |= kMipMapCount;
  flags |= info.compressed ? kLinearSize : kPitch;
  w.u32(flags);
  w.u32(t.height);
  w.u32(t.width);
  // Pitch of a row for uncompressed formats, byte size of level 0 for block formats.
  w.u32(info.compressed ? std::uint32_t(image_bytes(t.format, t.width, t.height))
                        : t.width * std::uint32_t(info.block_bytes));
  w.u32(0);  // depth
  w.u32(mips ? t.levels : 0);
  w.zeros(11 * 4);
  // DDS_PIXELFORMAT
  w.u32(kPixelFormatSize);
  if (dx10) {
    w.u32(kFourCC);
    w.u32(fourcc("DX10"));
    w.zeros(5 * 4);
  } else {
    w.u32(legacy->flags);
    w.u32(legacy->fourcc);
    w.u32(legacy->bits);
    w.u32(legacy->r);
    w.u32(legacy->g);
    w.u32(legacy->b);
    w.u32(legacy->a);
  }
  std::uint32_t caps = kCapsTexture;
  if (mips || cube || array) caps |= kCapsComplex;
  if (mips) caps |= kCapsMipMap;
  w.u32(caps);
  w.u32(cube ? kCaps2Cubemap | kCaps2AllFaces : 0);
  w.zeros(3 * 4);  // caps3, caps4, reserved2
  if (dx10) {
    w.u32(dxgi_for(t.format));
    w.u32(kDimensionTexture2D);
    w.u32(cube ? kMiscTextureCube : 0);
    w.u32(t.layers);  // for cubemaps: the number of cubes
    w.u32(info.channels == 4 && !info.compressed ? kAlphaModeStraight : 0);
  }
  for (std::uint32_t a = 0; a < t.layers; ++a)
    for (std::uint32_t f = 0; f < t.faces; ++f)
      for (std::uint32_t l = 0; l < t.levels; ++l) {
        const auto& img = t.image(l, a, f);
        w.ref(img.data(), img.size());
      }
  return w;
}

std::vector<std::uint8_t> encode_dds(const Texture& t, DdsHeader header) {
  return encode_dds_stream(t, header).bytes();
}

Texture decode_dds(const std::uint8_t* data, std::size_t size, const std::string& name, const ReadLimits& limits) {
  ByteReader r(data, size, name);
  if (size < 4 || r.u32(0, "magic") != kMagic) r.fail("not a DDS file (no \"DDS \" magic)");
  if (r.u32(4, "dwSize") != kHeaderSize)
    r.fail("header dwSize " + std::to_string(r.u32(4, "dwSize")) + " (valid: 124)");
  const std::uint32_t flags = r.u32(8, "dwFlags");
  const std::uint32_t height = r.u32(12, "dwHeight"), width = r.u32(16, "dwWidth");
  const std::uint32_t depth = r.u32(24, "dwDepth");
  const std::uint32_t mip_count = r.u32(28, "dwMipMapCount");
  if (r.u32(76, "ddspf.dwSize") != kPixelFormatSize) r.fail("pixel format dwSize (valid: 32)");
  const std::uint32_t pf_flags = r.u32(80, "ddspf.dwFlags"), pf_fourcc = r.u32(84, "ddspf.dwFourCC");
  const std::uint32_t caps2 = r.u32(112, "dwCaps2");
  if (width == 0 || height == 0) r.fail("zero width or height");
  if (width > limits.max_texture_dimension || height > limits.max_texture_dimension) {
    r.unsupported(std::to_string(width) + "x" + std::to_string(height) + " is larger than " +
                  std::to_string(limits.max_texture_dimension) + " texels a side");
  }
  if ((caps2 & 0x200000) || depth > 1) r.unsupported("volume textures are not supported");
  std::uint32_t max_levels = 1;
  for (std::uint32_t m = std::max(width, height); m > 1; m >>= 1) ++max_levels;
  const std::uint32_t levels = mip_count == 0 ? 1 : mip_count;
  if (levels > max_levels) {
    r.fail("dwMipMapCount " + std::to_string(mip_count) + " is more than a " + std::to_string(width) + "x" +
           std::to_string(height) + " texture has (" + std::to_string(max_levels) + ")");
  }
  Texture t;
  t.width = width;
  t.height = height;
  t.levels = levels;
  std::size_t offset = 4 + kHeaderSize;
  bool found = false;
  if ((pf_flags & kFourCC) && pf_fourcc == fourcc("DX10")) {
    const std::uint32_t dxgi = r.u32(offset, "DX10 dxgiFormat");
    const std::uint32_t dim = r.u32(offset + 4, "DX10 resourceDimension");
    const std::uint32_t misc = r.u32(offset + 8, "DX10 miscFlag");
    const std::uint32_t array_size = r.u32(offset + 12, "DX10 arraySize");
    const std::uint32_t alpha_mode = r.u32(offset + 16, "DX10 miscFlags2") & 0x7;
    if (misc & ~kMiscTextureCube) {
      r.fail("DX10 miscFlag 0x" + std::to_string(misc) + " has bits other than TEXTURECUBE (0x4)");
    }
    if (alpha_mode > 4) r.fail("DX10 alpha mode " + std::to_string(alpha_mode) + " (valid: 0 to 4)");
    if ((misc & kMiscTextureCube) && (caps2 & kCaps2Cubemap) && (caps2 & kCaps2AllFaces) != kCaps2AllFaces) {
      r.unsupported("cubemaps without all six faces");
    }
    offset += 20;
    const FormatInfo* fi = find_format_by_dxgi(dxgi);
    if (!fi) {
      const std::string what = dxgi_format_name(dxgi);
      r.unsupported("DXGI format " + std::to_string(dxgi) + (what.empty() ? "" : " (" + what + ")") +
                    " is not one texproc reads");
    }
    if (dim != kDimensionTexture2D)
      r.unsupported("resource dimension " + std::to_string(dim) + " (texproc reads 2D textures)");
    if (array_size == 0 || array_size > limits.max_layers) r.fail("DX10 arraySize " + std::to_string(array_size));
    t.format = fi->format;
    t.layers = array_size;
    t.is_array = array_size > 1;
    t.faces = (misc & kMiscTextureCube) ? 6 : 1;
    found = true;
  } else if (pf_flags & kFourCC) {
    for (const auto& l : kLegacy) {
      if ((l.flags & kFourCC) && l.fourcc == pf_fourcc) {
        t.format = l.format;
        found = true;
      }
    }
    for (const auto& e : kExtraFourCC) {
      if (e.code == pf_fourcc) {
        t.format = e.format;
        found = true;
      }
    }
    if (!found) {
      char cc[5] = {char(pf_fourcc), char(pf_fourcc >> 8), char(pf_fourcc >> 16), char(pf_fourcc >> 24), 0};
      r.unsupported(std::string("FourCC '") + cc + "' is not a format texproc reads");
    }
  } else {
    const std::uint32_t bits = r.u32(88, "ddspf.dwRGBBitCount");
    const std::uint32_t rm = r.u32(92, "ddspf.dwRBitMask"), gm = r.u32(96, "ddspf.dwGBitMask"),
                        bm = r.u32(100, "ddspf.dwBBitMask"), am = r.u32(104, "ddspf.dwABitMask");
    for (const auto& l : kLegacy) {
      if (l.flags & kFourCC) continue;
      const bool alpha = (pf_flags & kAlphaPixels) != 0;
      if (l.bits == bits && l.r == rm && (l.g == gm || (l.flags & kLuminance)) &&
          (l.b == bm || (l.flags & kLuminance)) && (l.a == am || !alpha) &&
          ((l.flags & kLuminance) == (pf_flags & kLuminance))) {
        t.format = l.format;
        found = true;
        break;
      }
    }
    if (!found) r.unsupported("pixel format (" + std::to_string(bits) + "-bit masks) is not one texproc reads");
  }
  if ((caps2 & kCaps2Cubemap) && t.faces == 1) {
    if ((caps2 & kCaps2AllFaces) != kCaps2AllFaces) r.unsupported("cubemaps without all six faces");
    t.faces = 6;
  }
  if (t.faces == 6 && width != height) r.fail("cubemap faces are not square");
  // A pitch or linear size the header claims must be the format's (0: not given, as many writers leave it).
  {
    const FormatInfo& info = format_info(t.format);
    const std::uint32_t pitch = r.u32(20, "dwPitchOrLinearSize");
    const std::uint64_t want =
        info.compressed ? image_bytes(t.format, width, height) : std::uint64_t(width) * std::uint32_t(info.block_bytes);
    const bool says = (flags & (info.compressed ? kLinearSize : kPitch)) != 0;
    if (says && pitch != 0 && pitch != want) {
      r.fail(std::string(info.compressed ? "dwPitchOrLinearSize (linear size) " : "dwPitchOrLinearSize (pitch) ") +
             std::to_string(pitch) + " (expected " + std::to_string(want) + " for " + std::to_string(width) + "x" +
             std::to_string(height) + " " + info.name + ")");
    }
  }
  std::vector<std::uint64_t> level_bytes(levels);
  std::uint64_t total = 0;
  for (std::uint32_t l = 0; l < levels; ++l) {
    level_bytes[l] = image_bytes(t.format, t.level_width(l), t.level_height(l));
    total += level_bytes[l];
  }
  const std::uint64_t images = std::uint64_t(t.layers) * t.faces;
  if (total > (std::uint64_t(1) << 40) / images) r.fail("sizes overflow");
  const std::uint64_t need = total * images;
  if (size < offset) {
    r.fail("truncated: the header needs " + std::to_string(offset) + " bytes, the file has " + std::to_string(size));
  }
  if (size - offset < need) {
    r.fail("truncated: the texture data needs " + std::to_string(need) + " bytes after the header, the file has " +
           std::to_string(size - offset));
  }
  if (size - offset > need) r.fail(std::to_string(size - offset - need) + " trailing bytes after the texture data");
  t.images.resize(std::size_t(levels) * images);
  if (limits.headers_only) return t;
  for (std::uint32_t a = 0; a < t.layers; ++a)
    for (std::uint32_t f = 0; f < t.faces; ++f)
      for (std::uint32_t l = 0; l < levels; ++l) {
        const std::uint8_t* p = r.at(offset, level_bytes[l], "texture data");
        t.image(l, a, f).assign(p, p + level_bytes[l]);
        offset += level_bytes[l];
      }
  return t;
}

}  // namespace texproc
