// Texture containers: round trips, header bytes from the specifications,
// hostile files, and readers that no one here wrote.
#include <gtest/gtest.h>
#include <zlib.h>
#include <zstd.h>

#include <cstring>
#include <filesystem>
#include <random>

#include "support/images.h"
#include "support/run.h"
#include "texproc/container.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/mip.h"

using namespace texproc;
using namespace texproc::test;
namespace fs = std::filesystem;

namespace {

Texture random_texture(TexelFormat f, std::uint32_t w, std::uint32_t h, std::uint32_t levels, std::uint32_t faces,
                       std::uint32_t layers, unsigned seed) {
  Texture t;
  t.format = f;
  t.width = w;
  t.height = h;
  t.levels = levels;
  t.faces = faces;
  t.layers = layers;
  t.is_array = layers > 1;
  std::mt19937 rng(seed);
  for (std::uint32_t l = 0; l < levels; ++l)
    for (std::uint32_t i = 0; i < layers * faces; ++i) {
      std::vector<std::uint8_t> b(image_bytes(f, t.level_width(l), t.level_height(l)));
      for (auto& v : b) v = std::uint8_t(rng());
      if (is_astc(f)) {
        // Constant-colour (void-extent) blocks, LDR or HDR as the format
        // says: the .astc and KTX1 readers tell the profile from the blocks.
        const bool hdr = format_info(f).is_float;
        for (std::size_t k = 0; k < b.size(); k += 16) {
          b[k] = 0xFC;
          b[k + 1] = hdr ? 0xFF : 0xFD;
          for (int j = 2; j < 8; ++j) b[k + j] = 0xFF;
          if (hdr) {
            for (int j = 8; j < 16; j += 2) b[k + j + 1] = std::uint8_t(b[k + j + 1] & 0x3B);  // finite halves
          }
        }
      }
      if (format_info(f).is_float && f == TexelFormat::rgba32_float) {
        for (std::size_t k = 0; k + 4 <= b.size(); k += 4) {  // finite floats
          const float x = float(rng() % 1000) / 7.0f;
          std::memcpy(&b[k], &x, 4);
        }
      }
      t.images.push_back(std::move(b));
    }
  return t;
}

void expect_same(const Texture& a, const Texture& b, const std::string& what) {
  EXPECT_EQ(a.format, b.format) << what;
  EXPECT_EQ(a.width, b.width) << what;
  EXPECT_EQ(a.height, b.height) << what;
  EXPECT_EQ(a.levels, b.levels) << what;
  EXPECT_EQ(a.faces, b.faces) << what;
  EXPECT_EQ(a.layers, b.layers) << what;
  EXPECT_TRUE(a.images == b.images) << what;
}

std::vector<TexelFormat> all_formats() {
  std::vector<TexelFormat> v;
  for (const auto& n : texel_format_names()) v.push_back(parse_texel_format(n));
  return v;
}

std::uint32_t full_levels(std::uint32_t w, std::uint32_t h) {
  std::uint32_t n = 1;
  for (std::uint32_t m = std::max(w, h); m > 1; m >>= 1) ++n;
  return n;
}

Texture decode(ContainerKind k, const std::vector<std::uint8_t>& b) {
  switch (k) {
    case ContainerKind::dds:
      return decode_dds(b.data(), b.size(), "t.dds");
    case ContainerKind::ktx2:
      return decode_ktx2(b.data(), b.size(), "t.ktx2");
    case ContainerKind::ktx1:
      return decode_ktx1(b.data(), b.size(), "t.ktx");
    case ContainerKind::pkm:
      return decode_pkm(b.data(), b.size(), "t.pkm");
    case ContainerKind::astc:
      return decode_astc(b.data(), b.size(), "t.astc");
  }
  return {};
}

std::vector<std::uint8_t> encode(ContainerKind k, const Texture& t) {
  switch (k) {
    case ContainerKind::dds:
      return encode_dds(t);
    case ContainerKind::ktx2:
      return encode_ktx2(t, "test");
    case ContainerKind::ktx1:
      return encode_ktx1(t);
    case ContainerKind::pkm:
      return encode_pkm(t);
    case ContainerKind::astc:
      return encode_astc(t);
  }
  return {};
}

bool holds(ContainerKind k, TexelFormat f) {
  const FormatInfo& i = format_info(f);
  switch (k) {
    case ContainerKind::dds:
      return i.dxgi_format != 0;
    case ContainerKind::ktx2:
      return true;
    case ContainerKind::ktx1:
      return i.gl_internal_format != 0;
    case ContainerKind::pkm:
      return f == TexelFormat::etc1_rgb || f == TexelFormat::etc2_rgb_unorm;
    case ContainerKind::astc:
      return is_astc(f);
  }
  return false;
}

// What a reader may legitimately report instead of the written format.
TexelFormat as_read(ContainerKind k, TexelFormat f) {
  if (k == ContainerKind::dds && f == TexelFormat::bc1_rgb_unorm) return TexelFormat::bc1_rgba_unorm;
  if (k == ContainerKind::dds && f == TexelFormat::bc1_rgb_srgb) return TexelFormat::bc1_rgba_srgb;
  if (k == ContainerKind::ktx2 && f == TexelFormat::etc1_rgb) return TexelFormat::etc2_rgb_unorm;
  // .astc has no colour profile: sRGB reads as UNORM (HDR from its blocks).
  if (k == ContainerKind::astc && is_astc(f) && format_info(f).srgb) {
    return astc_format(format_info(f).block_width, format_info(f).block_height, false, false);
  }
  return f;
}

}  // namespace

// Every format in every container that can hold it, for 1x1, 3x5, 4x4,
// 100x60 and 256x256, with and without mips: write, read, same bytes.
TEST(Container, RoundTripEveryFormatSizeAndContainer) {
  int checked = 0;
  for (ContainerKind k :
       {ContainerKind::dds, ContainerKind::ktx2, ContainerKind::ktx1, ContainerKind::pkm, ContainerKind::astc}) {
    for (TexelFormat f : all_formats()) {
      if (!holds(k, f)) {
        EXPECT_THROW(encode(k, random_texture(f, 4, 4, 1, 1, 1, 1)), Error)
            << to_string(k) << " " << format_info(f).name;
        continue;
      }
      for (auto [w, h] : {std::pair{1u, 1u}, {3u, 5u}, {4u, 4u}, {100u, 60u}, {256u, 256u}}) {
        for (bool mips : {false, true}) {
          if (mips && (k == ContainerKind::pkm || k == ContainerKind::astc)) continue;
          const Texture t = random_texture(f, w, h, mips ? full_levels(w, h) : 1, 1, 1, w * 7 + h);
          Texture back = decode(k, encode(k, t));
          Texture want = t;
          want.format = as_read(k, f);
          expect_same(back, want,
                      std::string(to_string(k)) + " " + format_info(f).name + " " + std::to_string(w) + "x" +
                          std::to_string(h) + (mips ? " mips" : ""));
          ++checked;
        }
      }
    }
  }
  EXPECT_GT(checked, 300);
}

TEST(Container, CubemapsAndArraysRoundTrip) {
  for (ContainerKind k : {ContainerKind::dds, ContainerKind::ktx2, ContainerKind::ktx1}) {
    for (TexelFormat f : {TexelFormat::rgba8_srgb, TexelFormat::bc3_unorm, TexelFormat::rgba16_float}) {
      for (auto [faces, layers] : {std::pair{6u, 1u}, {1u, 3u}, {6u, 2u}}) {
        const Texture t = random_texture(f, 16, 16, 5, faces, layers, faces * 10 + layers);
        expect_same(decode(k, encode(k, t)), t, std::string(to_string(k)) + " faces/layers");
      }
    }
  }
}

// DDS header bytes, derived from Microsoft's DDS_HEADER reference: a 4x4
// RGBA8 UNORM texture, one level, legacy header (masks say the format).
TEST(Container, DdsLegacyHeaderBytes) {
  const Texture t = random_texture(TexelFormat::rgba8_unorm, 4, 4, 1, 1, 1, 3);
  const std::vector<std::uint8_t> b = encode_dds(t);
  ASSERT_EQ(b.size(), 4u + 124u + 64u);
  auto u32 = [&](std::size_t at) {
    std::uint32_t v;
    std::memcpy(&v, &b[at], 4);
    return v;
  };
  EXPECT_EQ(std::string(b.begin(), b.begin() + 4), "DDS ");
  EXPECT_EQ(u32(4), 124u);                             // dwSize
  EXPECT_EQ(u32(8), 0x1u | 0x2 | 0x4 | 0x8 | 0x1000);  // CAPS|HEIGHT|WIDTH|PITCH|PIXELFORMAT: no mips
  EXPECT_EQ(u32(12), 4u);                              // height
  EXPECT_EQ(u32(16), 4u);                              // width
  EXPECT_EQ(u32(20), 16u);                             // pitch: 4 texels * 4 bytes
  EXPECT_EQ(u32(28), 0u);                              // no mip count without mips
  EXPECT_EQ(u32(76), 32u);                             // ddspf.dwSize
  EXPECT_EQ(u32(80), 0x40u | 0x1);                     // DDPF_RGB | DDPF_ALPHAPIXELS
  EXPECT_EQ(u32(88), 32u);                             // bits
  EXPECT_EQ(u32(92), 0x000000FFu);                     // R mask: byte 0
  EXPECT_EQ(u32(96), 0x0000FF00u);
  EXPECT_EQ(u32(100), 0x00FF0000u);
  EXPECT_EQ(u32(104), 0xFF000000u);
  EXPECT_EQ(u32(108), 0x1000u);  // DDSCAPS_TEXTURE only
  EXPECT_EQ(0, std::memcmp(&b[128], t.images[0].data(), 64));
}

// DX10: BC1 sRGB needs it (no FourCC says sRGB). 8x8, 4 levels.
TEST(Container, DdsDx10HeaderBytes) {
  const Texture t = random_texture(TexelFormat::bc1_rgba_srgb, 8, 8, 4, 1, 1, 4);
  const std::vector<std::uint8_t> b = encode_dds(t);
  auto u32 = [&](std::size_t at) {
    std::uint32_t v;
    std::memcpy(&v, &b[at], 4);
    return v;
  };
  EXPECT_EQ(u32(8), 0x1u | 0x2 | 0x4 | 0x1000 | 0x20000 | 0x80000);  // + MIPMAPCOUNT, LINEARSIZE
  EXPECT_EQ(u32(20), 32u);                                           // linear size of level 0: 2x2 blocks of 8 bytes
  EXPECT_EQ(u32(28), 4u);                                            // mip count
  EXPECT_EQ(u32(80), 0x4u);                                          // DDPF_FOURCC
  EXPECT_EQ(u32(84), 0x30315844u);                                   // "DX10"
  EXPECT_EQ(u32(108), 0x1000u | 0x8 | 0x400000);                     // TEXTURE | COMPLEX | MIPMAP
  EXPECT_EQ(u32(128), 72u);                                          // DXGI_FORMAT_BC1_UNORM_SRGB
  EXPECT_EQ(u32(132), 3u);                                           // TEXTURE2D
  EXPECT_EQ(u32(136), 0u);                                           // not a cube
  EXPECT_EQ(u32(140), 1u);                                           // array size
  // Levels 8x8, 4x4, 2x2, 1x1: 32 + 8 + 8 + 8 bytes after the 148-byte headers.
  EXPECT_EQ(b.size(), 148u + 32 + 8 + 8 + 8);
  // The same texture in linear space has a FourCC: DXT1.
  Texture lin = t;
  lin.format = TexelFormat::bc1_rgba_unorm;
  const auto l = encode_dds(lin);
  EXPECT_EQ(std::string(l.begin() + 84, l.begin() + 88), "DXT1");
  EXPECT_EQ(l.size(), 128u + 56);
  EXPECT_THROW(encode_dds(t, DdsHeader::dx9), Error);
  EXPECT_EQ(encode_dds(lin, DdsHeader::dx10)[84], 'D');
}

// KTX2 bytes from the KTX 2.0 specification and the Khronos Data Format
// Specification: a 2x2 RGBA8 sRGB texture, one level.
TEST(Container, Ktx2HeaderAndDfdBytes) {
  const Texture t = random_texture(TexelFormat::rgba8_srgb, 2, 2, 1, 1, 1, 5);
  const std::vector<std::uint8_t> b = encode_ktx2(t, "w");
  auto u32 = [&](std::size_t at) {
    std::uint32_t v;
    std::memcpy(&v, &b[at], 4);
    return v;
  };
  auto u64 = [&](std::size_t at) {
    std::uint64_t v;
    std::memcpy(&v, &b[at], 8);
    return v;
  };
  const std::uint8_t id[12] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
  EXPECT_EQ(0, std::memcmp(b.data(), id, 12));
  EXPECT_EQ(u32(12), 43u);  // VK_FORMAT_R8G8B8A8_SRGB
  EXPECT_EQ(u32(16), 1u);   // typeSize
  EXPECT_EQ(u32(20), 2u);
  EXPECT_EQ(u32(24), 2u);
  EXPECT_EQ(u32(28), 0u);  // depth
  EXPECT_EQ(u32(32), 0u);  // layerCount 0: not an array
  EXPECT_EQ(u32(36), 1u);  // faces
  EXPECT_EQ(u32(40), 1u);  // levels
  EXPECT_EQ(u32(44), 0u);  // no supercompression
  // Index: the DFD follows the 80-byte header+index and one 24-byte level entry.
  EXPECT_EQ(u32(48), 104u);
  EXPECT_EQ(u32(52), 92u);  // 4 (total size) + 24 (block header) + 4 samples * 16
  // DFD: RGBSDA, BT.709, sRGB transfer, straight alpha; 4 bytes per texel.
  EXPECT_EQ(u32(104), 92u);
  EXPECT_EQ(u32(108), 0u);                       // Khronos, basic block
  EXPECT_EQ(u32(112), 2u | 88u << 16);           // version 2, block size 88
  EXPECT_EQ(u32(116), 1u | 1u << 8 | 2u << 16);  // model RGBSDA, BT709, SRGB
  EXPECT_EQ(u32(120), 0u);                       // 1x1x1x1 texel block
  EXPECT_EQ(u32(124), 4u);                       // bytesPlane0
  EXPECT_EQ(u32(128), 0u);
  // Samples: R at bit 0, G 8, B 16, 8 bits each, [0, 255]; alpha (15) at 24
  // with the LINEAR qualifier (0x10): alpha never goes through sRGB.
  for (int s = 0; s < 4; ++s) {
    const std::size_t at = 132 + 16 * s;
    const std::uint32_t channel = s == 3 ? 15u | 0x10u : std::uint32_t(s);
    EXPECT_EQ(u32(at), std::uint32_t(8 * s) | 7u << 16 | channel << 24) << s;
    EXPECT_EQ(u32(at + 4), 0u);
    EXPECT_EQ(u32(at + 8), 0u);
    EXPECT_EQ(u32(at + 12), 255u);
  }
  // Key/value data right after the DFD: one KTXwriter entry, padded to 4.
  EXPECT_EQ(u32(56), 196u);
  EXPECT_EQ(u32(196), 12u);  // "KTXwriter\0w\0"
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(&b[200]), 9), "KTXwriter");
  EXPECT_EQ(u32(60), 16u);
  EXPECT_EQ(u64(64), 0u);  // no supercompression global data
  EXPECT_EQ(u64(72), 0u);
  // The level: at 212 (aligned to lcm(4, 4)), 16 bytes.
  EXPECT_EQ(u64(80), 212u);
  EXPECT_EQ(u64(88), 16u);
  EXPECT_EQ(u64(96), 16u);
  EXPECT_EQ(b.size(), 228u);
}

// Compressed DFDs, as libktx's createDFDCompressed writes them.
TEST(Container, Ktx2CompressedDfds) {
  auto words = [](TexelFormat f) {
    const std::vector<std::uint8_t> d = ktx2_dfd(f);
    std::vector<std::uint32_t> w(d.size() / 4);
    std::memcpy(w.data(), d.data(), d.size());
    return w;
  };
  // BC1 RGB: one 64-bit sample, channel BC1A_COLOR (0), [0, 0xFFFFFFFF].
  EXPECT_EQ(words(TexelFormat::bc1_rgb_unorm), (std::vector<std::uint32_t>{44, 0, 2 | 40 << 16, 128 | 1 << 8 | 1 << 16,
                                                                           0x0303, 8, 0, 63 << 16, 0, 0, 0xFFFFFFFF}));
  // BC1 RGBA: channel ALPHAPRESENT (1); sRGB transfer for the _SRGB format.
  EXPECT_EQ(words(TexelFormat::bc1_rgba_srgb)[3], 128u | 1 << 8 | 2 << 16);
  EXPECT_EQ(words(TexelFormat::bc1_rgba_srgb)[7], 63u << 16 | 1u << 24);
  // BC3: alpha (15) at bit 0, color (0) at bit 64, 16 bytes per block.
  const auto bc3 = words(TexelFormat::bc3_unorm);
  EXPECT_EQ(bc3[5], 16u);
  EXPECT_EQ(bc3[7], 63u << 16 | 15u << 24);
  EXPECT_EQ(bc3[11], 64u | 63u << 16);
  // BC5 SNORM: red and green, SIGNED (0x40), [0x80000000, 0x7FFFFFFF].
  const auto bc5 = words(TexelFormat::bc5_snorm);
  EXPECT_EQ(bc5[3] & 0xFF, 132u);
  EXPECT_EQ(bc5[7], 63u << 16 | 0x40u << 24);
  EXPECT_EQ(bc5[9], 0x80000000u);
  EXPECT_EQ(bc5[10], 0x7FFFFFFFu);
  EXPECT_EQ(bc5[11], 64u | 63u << 16 | (1u | 0x40u) << 24);
  // ETC2 RGBA8: alpha (15) then color (2) at 64; punch-through: color and alpha both at 0.
  const auto e = words(TexelFormat::etc2_rgba8_srgb);
  EXPECT_EQ(e[3], 161u | 1 << 8 | 2 << 16);
  EXPECT_EQ(e[7], 63u << 16 | (15u | 0x10u) << 24);  // an sRGB format's alpha sample is LINEAR
  EXPECT_EQ(e[11], 64u | 63u << 16 | 2u << 24);
  const auto a1 = words(TexelFormat::etc2_rgba1_unorm);
  EXPECT_EQ(a1[7], 63u << 16 | 2u << 24);
  EXPECT_EQ(a1[11], 63u << 16 | 15u << 24);
  // Every sRGB format with an alpha sample marks it LINEAR, and only that one
  // (ktx validate's rule for KHR_DF_TRANSFER_SRGB): BC2, BC3, ETC2 A1 and A8.
  for (TexelFormat f : {TexelFormat::bc2_srgb, TexelFormat::bc3_srgb, TexelFormat::etc2_rgba1_srgb,
                        TexelFormat::etc2_rgba8_srgb, TexelFormat::rgba8_srgb, TexelFormat::bgra8_srgb}) {
    const auto w = words(f);
    const std::size_t samples = (w.size() - 7) / 4;
    int alpha = 0;
    for (std::size_t s = 0; s < samples; ++s) {
      const std::uint32_t channel = w[7 + 4 * s] >> 24;
      if ((channel & 0x0F) == 15) {
        EXPECT_EQ(channel & 0x10, 0x10u) << format_info(f).name;
        ++alpha;
      } else {
        EXPECT_EQ(channel & 0x10, 0u) << format_info(f).name << " sample " << s;
      }
    }
    EXPECT_EQ(alpha, 1) << format_info(f).name;
  }
  // R8 sRGB: one sample, no alpha to mark LINEAR; transfer sRGB.
  const auto r8s = words(TexelFormat::r8_srgb);
  EXPECT_EQ(r8s[0], 44u);
  EXPECT_EQ(r8s[3], 1u | 1 << 8 | 2 << 16);
  EXPECT_EQ(r8s[5], 1u);
  EXPECT_EQ(r8s[7], 7u << 16);
  EXPECT_EQ(r8s[10], 255u);
  // Half floats: FLOAT|SIGNED, [-1.0f, 1.0f] as float bits, 16-bit samples, typeSize 2.
  const auto h = words(TexelFormat::rgba16_float);
  EXPECT_EQ(h[7], 15u << 16 | 0xC0u << 24);
  EXPECT_EQ(h[9], 0xBF800000u);
  EXPECT_EQ(h[10], 0x3F800000u);
}

// Levels are stored smallest first, each aligned to lcm(block bytes, 4).
TEST(Container, Ktx2LevelOrderAndAlignment) {
  for (TexelFormat f :
       {TexelFormat::r8_unorm, TexelFormat::bc1_rgb_unorm, TexelFormat::bc3_unorm, TexelFormat::rgba32_float}) {
    const Texture t = random_texture(f, 37, 11, full_levels(37, 11), 1, 1, 9);
    const std::vector<std::uint8_t> b = encode_ktx2(t, "w");
    const std::size_t align = std::max<std::size_t>(4, std::size_t(format_info(f).block_bytes));
    std::uint64_t prev = ~std::uint64_t(0);
    for (std::uint32_t l = 0; l < t.levels; ++l) {
      std::uint64_t off;
      std::memcpy(&off, &b[80 + 24 * l], 8);
      EXPECT_EQ(off % align, 0u) << format_info(f).name << " level " << l;
      EXPECT_LT(off, prev) << "level " << l << " must be stored before level " << l - 1;
      prev = off;
    }
  }
}

// Every truncation of a valid file, and every header word set to zero and to
// all ones, must be rejected with an Error or read consistently; never a
// crash or an out-of-bounds read (run under AddressSanitizer: the asan preset).
TEST(Container, HostileFilesAreRejectedSafely) {
  const Texture mips = random_texture(TexelFormat::bc3_unorm, 12, 8, 4, 1, 1, 11);
  const Texture cube = random_texture(TexelFormat::rgba8_unorm, 8, 8, 2, 6, 1, 12);
  const Texture etc = random_texture(TexelFormat::etc1_rgb, 9, 7, 1, 1, 1, 13);
  const Texture astc = random_texture(TexelFormat::astc_5x4_unorm, 11, 9, 1, 1, 1, 14);
  for (ContainerKind k :
       {ContainerKind::dds, ContainerKind::ktx2, ContainerKind::ktx1, ContainerKind::pkm, ContainerKind::astc}) {
    for (const Texture* t : {&mips, &cube, &etc, &astc}) {
      if (!holds(k, t->format) || ((k == ContainerKind::pkm || k == ContainerKind::astc) && t->levels > 1)) continue;
      const std::vector<std::uint8_t> good = encode(k, *t);
      for (std::size_t n = 0; n < good.size(); ++n) {
        const std::vector<std::uint8_t> cut(good.begin(), good.begin() + std::ptrdiff_t(n));
        EXPECT_THROW(decode(k, cut), Error) << to_string(k) << " truncated to " << n;
      }
      std::vector<std::uint8_t> longer = good;
      longer.push_back(0);
      EXPECT_THROW(decode(k, longer), Error) << to_string(k) << " trailing byte";
      const std::size_t header = std::min<std::size_t>(good.size(), 200);
      for (std::size_t at = 0; at + 4 <= header; at += 2) {
        for (std::uint32_t v : {0u, 0xFFFFFFFFu, 0x7FFFFFFFu, 0x10000u}) {
          std::vector<std::uint8_t> bad = good;
          std::memcpy(&bad[at], &v, 4);
          try {
            const Texture r = decode(k, bad);
            validate(r);  // whatever was accepted must be a consistent texture
          } catch (const Error&) {
          }
        }
      }
    }
  }
}

TEST(Container, ReaderLimitsAndMessages) {
  Texture t = random_texture(TexelFormat::r8_unorm, 64, 2, 1, 1, 1, 2);
  std::vector<std::uint8_t> b = encode_dds(t);
  ReadLimits small;
  small.max_texture_dimension = 32;
  try {
    decode_dds(b.data(), b.size(), "big.dds", small);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::unsupported);
    EXPECT_NE(std::string(e.what()).find("big.dds: 64x2 is larger than 32"), std::string::npos) << e.what();
  }
  // A mip count beyond what the size allows.
  std::uint32_t many = 9;
  std::memcpy(&b[28], &many, 4);
  try {
    decode_dds(b.data(), b.size(), "m.dds");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("dwMipMapCount 9 is more than a 64x2 texture has (7)"), std::string::npos)
        << e.what();
  }
}

// NVIDIA Texture Tools' nvddsinfo reads the DX10 header texproc writes.
TEST(Container, NvddsinfoReadsDx10Headers) {
  if (std::system("command -v nvddsinfo >/dev/null 2>&1") != 0) GTEST_SKIP() << "nvddsinfo not installed";
  const std::string dir = temp_dir("dds_nv");
  struct Case {
    TexelFormat f;
    const char* want;
  };
  for (const Case& c :
       {Case{TexelFormat::rgba8_srgb, "DXGI Format: 29"}, Case{TexelFormat::bc5_snorm, "DXGI Format: 84"},
        Case{TexelFormat::bc4_snorm, "DXGI Format: 81"}, Case{TexelFormat::rgba16_float, "DXGI Format: 10"}}) {
    const std::string path = dir + "/t.dds";
    write_texture(path, random_texture(c.f, 16, 8, 5, 1, 1, 3));
    const std::string out = dir + "/info.txt";
    ASSERT_EQ(std::system(("nvddsinfo " + path + " > " + out + " 2>&1").c_str()), 0);
    const std::string info = slurp(out);
    EXPECT_NE(info.find(c.want), std::string::npos) << format_info(c.f).name << "\n" << info;
    EXPECT_NE(info.find("Mipmap count: 5"), std::string::npos) << info;
    EXPECT_NE(info.find("Width: 16"), std::string::npos) << info;
  }
  fs::remove_all(dir);
}

// A second KTX2 parser: the ktx-parse npm package (installed by
// scripts/setup.sh into tests/tools), read by node.
TEST(Container, KtxParseReadsKtx2) {
  const std::string tools = std::string(TEXPROC_SAMPLES_DIR) + "/../tests/tools";
  if (!fs::exists(tools + "/node_modules/ktx-parse") || std::system("command -v node >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "ktx-parse not installed (scripts/setup.sh installs it)";
  }
  const std::string dir = temp_dir("ktx2_parse");
  struct Case {
    TexelFormat f;
    std::uint32_t faces, layers;
  };
  for (const Case& c :
       {Case{TexelFormat::rgba8_srgb, 1, 1}, Case{TexelFormat::bc1_rgb_unorm, 1, 1}, Case{TexelFormat::bc5_snorm, 6, 1},
        Case{TexelFormat::etc2_rgba8_srgb, 1, 3}, Case{TexelFormat::rgba16_float, 1, 1}}) {
    const std::uint32_t w = c.faces == 6 ? 16 : 20, h = c.faces == 6 ? 16 : 12;  // cube faces are square
    const Texture t = random_texture(c.f, w, h, full_levels(w, h), c.faces, c.layers, 5);
    const std::string path = dir + "/t.ktx2";
    write_texture(path, t);
    const std::string out = dir + "/p.json";
    ASSERT_EQ(std::system(("cd " + tools + " && node ktx2_check.mjs " + path + " > " + out + " 2>&1").c_str()), 0)
        << slurp(out);
    const std::string j = slurp(out);
    const FormatInfo& fi = format_info(c.f);
    EXPECT_NE(j.find("\"vkFormat\":" + std::to_string(fi.vk_format) + ","), std::string::npos) << j;
    EXPECT_NE(j.find("\"faces\":" + std::to_string(c.faces) + ","), std::string::npos) << j;
    EXPECT_NE(j.find("\"levels\":" + std::to_string(t.levels) + ","), std::string::npos) << j;
    EXPECT_NE(j.find("\"transfer\":" + std::string(fi.srgb ? "2" : "1")), std::string::npos) << j;
    EXPECT_NE(j.find("\"bytesPlane0\":" + std::to_string(fi.block_bytes)), std::string::npos) << j;
    const std::uint64_t level0 = image_bytes(c.f, w, h) * c.faces * c.layers;
    EXPECT_NE(j.find("\"levelBytes\":[" + std::to_string(level0) + ","), std::string::npos) << j;
  }
  fs::remove_all(dir);
}

// texproc mip writes uncompressed chains into the containers, readable back.
TEST(Container, MipChainsThroughTheContainers) {
  const std::string dir = temp_dir("mip_containers");
  const Image img = random_image(40, 24, 4, PixelType::u8, 7);
  const MipChain c = generate_mips(img.view(), MipOptions{});
  const Texture t = texture_from_levels(c.levels, {.srgb = true});
  EXPECT_EQ(t.format, TexelFormat::rgba8_srgb);
  for (const char* ext : {".dds", ".ktx2", ".ktx"}) {
    write_texture(dir + "/m" + ext, t);
    const Texture back = read_texture(dir + "/m" + ext);
    ASSERT_EQ(back.levels, c.levels.size());
    for (std::uint32_t l = 0; l < back.levels; ++l) {
      const Image im = image_from_texture(back, l);
      EXPECT_EQ(0, std::memcmp(im.data(), c.levels[l].data(), im.byte_size())) << ext << " level " << l;
    }
  }
  // RGB input gets alpha 255; float goes to half or float RGBA.
  const Image rgb = random_image(5, 3, 3, PixelType::u8, 1);
  const Texture rt = texture_from_levels({rgb});
  EXPECT_EQ(rt.format, TexelFormat::rgba8_unorm);
  EXPECT_EQ(image_from_texture(rt, 0).get(2, 1, 3), 1.0f);
  const Image f = random_image(5, 3, 1, PixelType::f32, 1);
  const Image back = image_from_texture(texture_from_levels({f}, {.half = true}), 0);
  EXPECT_NEAR(back.get(3, 2, 0), f.get(3, 2, 0), 1e-3);
  EXPECT_NEAR(back.get(3, 2, 2), f.get(3, 2, 0), 1e-3);
  fs::remove_all(dir);
}

// KTX1 bytes (KTX 1.1 specification): a 3x2 R8 texture, one level. Rows of
// 3 bytes are padded to 4 (GL_UNPACK_ALIGNMENT); imageSize counts the padding.
TEST(Container, Ktx1HeaderBytes) {
  Texture t = random_texture(TexelFormat::r8_unorm, 3, 2, 1, 1, 1, 8);
  const std::vector<std::uint8_t> b = encode_ktx1(t);
  auto u32 = [&](std::size_t at) {
    std::uint32_t v;
    std::memcpy(&v, &b[at], 4);
    return v;
  };
  const std::uint8_t id[12] = {0xAB, 'K', 'T', 'X', ' ', '1', '1', 0xBB, '\r', '\n', 0x1A, '\n'};
  EXPECT_EQ(0, std::memcmp(b.data(), id, 12));
  EXPECT_EQ(u32(12), 0x04030201u);  // endianness
  EXPECT_EQ(u32(16), 0x1401u);      // glType UNSIGNED_BYTE
  EXPECT_EQ(u32(20), 1u);           // glTypeSize
  EXPECT_EQ(u32(24), 0x1903u);      // glFormat RED
  EXPECT_EQ(u32(28), 0x8229u);      // glInternalFormat R8
  EXPECT_EQ(u32(32), 0x1903u);      // glBaseInternalFormat RED
  EXPECT_EQ(u32(36), 3u);
  EXPECT_EQ(u32(40), 2u);
  EXPECT_EQ(u32(44), 0u);  // depth
  EXPECT_EQ(u32(48), 0u);  // not an array
  EXPECT_EQ(u32(52), 1u);  // faces
  EXPECT_EQ(u32(56), 1u);  // levels
  EXPECT_EQ(u32(60), 0u);  // no key/value data
  EXPECT_EQ(u32(64), 8u);  // imageSize: 2 rows of 4 bytes
  EXPECT_EQ(b.size(), 76u);
  EXPECT_EQ(0, std::memcmp(&b[68], t.images[0].data(), 3));
  EXPECT_EQ(b[71], 0);  // row padding
  EXPECT_EQ(0, std::memcmp(&b[72], t.images[0].data() + 3, 3));
}

// PKM bytes (etc1tool's format): "PKM ", "10", type 0, padded then real
// sizes, all big-endian; 5x3 ETC1 is 2x1 blocks of 8 bytes.
TEST(Container, PkmHeaderBytes) {
  const Texture t = random_texture(TexelFormat::etc1_rgb, 5, 3, 1, 1, 1, 9);
  const std::vector<std::uint8_t> b = encode_pkm(t);
  const std::uint8_t want[16] = {'P', 'K', 'M', ' ', '1', '0', 0, 0, 0, 8, 0, 4, 0, 5, 0, 3};
  ASSERT_EQ(b.size(), 16u + 16u);
  EXPECT_EQ(0, std::memcmp(b.data(), want, 16));
  Texture e2 = t;
  e2.format = TexelFormat::etc2_rgb_unorm;
  const auto b2 = encode_pkm(e2);
  EXPECT_EQ(b2[4], '2');
  EXPECT_EQ(b2[7], 1);  // ETC2 RGB
}

// Pillow (python3-pil), a third DDS reader, reads texproc's legacy RGBA8 DDS.
TEST(Container, PillowReadsLegacyDds) {
  if (std::system("/usr/bin/python3 -c 'import PIL' >/dev/null 2>&1") != 0) GTEST_SKIP() << "python3-pil not installed";
  const std::string dir = temp_dir("dds_pil");
  const Texture t = random_texture(TexelFormat::rgba8_unorm, 7, 5, 1, 1, 1, 31);
  write_texture(dir + "/p.dds", t);
  const std::string out = dir + "/hex.txt";
  const std::string cmd = "/usr/bin/python3 -c \"from PIL import Image; im = Image.open('" + dir +
                          "/p.dds'); print(im.mode, im.size[0], im.size[1], im.tobytes().hex())\" > " + out + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(out);
  std::string hex;
  for (std::uint8_t v : t.images[0]) {
    char h[3];
    std::snprintf(h, sizeof h, "%02x", v);
    hex += h;
  }
  EXPECT_EQ(slurp(out), "RGBA 7 5 " + hex + "\n");
  fs::remove_all(dir);
}

// Malformed files that the readers once accepted or described wrongly: each
// is refused with a message naming the field, the value and what was expected.
TEST(Container, MalformedFilesAreRefusedByName) {
  auto refused = [](const std::vector<std::uint8_t>& b,
                    Texture (*decode)(const std::uint8_t*, std::size_t, const std::string&, const ReadLimits&),
                    const std::string& want) {
    try {
      decode(b.data(), b.size(), "f", ReadLimits{});
      ADD_FAILURE() << "accepted; expected: " << want;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(want), std::string::npos) << e.what();
    }
  };
  // KTX1: a cubemap of 4x1 faces.
  {
    const Texture t = random_texture(TexelFormat::rgba8_unorm, 4, 4, 1, 6, 1, 3);
    std::vector<std::uint8_t> b = encode_ktx1(t);
    const std::uint32_t one = 1;
    std::memcpy(&b[40], &one, 4);  // pixelHeight
    refused(b, decode_ktx1, "cube faces must be square");
  }
  const Texture t = random_texture(TexelFormat::rgba8_unorm, 16, 16, 5, 1, 1, 4);
  const std::vector<std::uint8_t> good = encode_ktx2(t, "w");
  // KTX2: key/value data 2 bytes long.
  {
    std::vector<std::uint8_t> b = good;
    const std::uint32_t two = 2;
    std::memcpy(&b[60], &two, 4);
    refused(b, decode_ktx2, "fewer than an entry's 4-byte keyAndValueByteLength");
  }
  // KTX2: level 3's byteOffset 0 (inside the header).
  {
    std::vector<std::uint8_t> b = good;
    const std::uint64_t zero = 0;
    std::memcpy(&b[80 + 24 * 3], &zero, 8);
    refused(b, decode_ktx2, "level 3 byteOffset 0 lies inside the header");
  }
  // KTX2: levelCount 2 with 5 levels stored: the three smallest lie before
  // level 1, covered by no index entry.
  {
    std::vector<std::uint8_t> b = good;
    const std::uint32_t two = 2;
    std::memcpy(&b[40], &two, 4);
    refused(b, decode_ktx2, "that no level index entry covers (levelCount 2");
  }
  // KTX2: uncompressedByteLength that differs from byteLength is named as such.
  {
    std::vector<std::uint8_t> b = good;
    const std::uint64_t wrong = 7;
    std::memcpy(&b[80 + 16], &wrong, 8);
    refused(b, decode_ktx2, "level 0 uncompressedByteLength 7 (expected 1024");
  }
  // DDS cut at byte 120: truncated, with the sizes.
  {
    const std::vector<std::uint8_t> d = encode_dds(t);
    refused(std::vector<std::uint8_t>(d.begin(), d.begin() + 120), decode_dds, "truncated");
  }
  // PKM cut at byte 10 has its magic: truncated, not "no magic"; a bad version is shown printably.
  {
    Texture e = random_texture(TexelFormat::etc1_rgb, 8, 8, 1, 1, 1, 5);
    std::vector<std::uint8_t> p = encode_pkm(e);
    refused(std::vector<std::uint8_t>(p.begin(), p.begin() + 10), decode_pkm,
            "the header needs 16 bytes, the file has 10");
    p[4] = 0x01;
    p[5] = 0xFF;
    refused(p, decode_pkm, "PKM version '\\x01\\xFF'");
  }
}

// Zstandard- and zlib-supercompressed KTX2 (what `ktx deflate` and glTF
// assets carry) read as the uncompressed file they came from; a level that
// does not inflate to its size is refused by name.
TEST(Container, Ktx2SupercompressedLevelsRead) {
  const Texture t = random_texture(TexelFormat::bc3_srgb, 36, 20, full_levels(36, 20), 1, 2, 7);
  const std::vector<std::uint8_t> plain = encode_ktx2(t, "w");
  for (std::uint32_t scheme : {2u, 3u}) {
    SCOPED_TRACE(scheme);
    // Header, index, DFD and key/value data as they were; then each level compressed, smallest first.
    std::uint64_t first_level = ~std::uint64_t(0);
    for (std::uint32_t l = 0; l < t.levels; ++l) {
      std::uint64_t off;
      std::memcpy(&off, &plain[80 + 24 * l], 8);
      first_level = std::min(first_level, off);
    }
    // Up to the end of the key/value data: supercompressed levels need no alignment padding.
    std::uint32_t kvd_off, kvd_len;
    std::memcpy(&kvd_off, &plain[56], 4);
    std::memcpy(&kvd_len, &plain[60], 4);
    ASSERT_LE(kvd_off + kvd_len, first_level);
    std::vector<std::uint8_t> out(plain.begin(), plain.begin() + std::ptrdiff_t(kvd_off + kvd_len));
    std::memcpy(&out[44], &scheme, 4);
    for (std::uint32_t l = t.levels; l-- > 0;) {
      std::uint64_t off, len;
      std::memcpy(&off, &plain[80 + 24 * l], 8);
      std::memcpy(&len, &plain[80 + 24 * l + 8], 8);
      std::vector<std::uint8_t> packed;
      if (scheme == 2) {
        packed.resize(ZSTD_compressBound(len));
        packed.resize(ZSTD_compress(packed.data(), packed.size(), &plain[off], len, 3));
      } else {
        uLongf n = compressBound(uLong(len));
        packed.resize(n);
        ASSERT_EQ(compress(packed.data(), &n, &plain[off], uLong(len)), Z_OK);
        packed.resize(n);
      }
      const std::uint64_t at = out.size(), plen = packed.size();
      out.insert(out.end(), packed.begin(), packed.end());
      std::memcpy(&out[80 + 24 * l], &at, 8);
      std::memcpy(&out[80 + 24 * l + 8], &plen, 8);
      std::memcpy(&out[80 + 24 * l + 16], &len, 8);
    }
    const Texture back = decode_ktx2(out.data(), out.size(), "z.ktx2");
    ASSERT_EQ(back.images.size(), t.images.size());
    for (std::size_t i = 0; i < t.images.size(); ++i) EXPECT_TRUE(back.images[i] == t.images[i]) << i;
    // Level 0 claims one byte more than it inflates to.
    std::vector<std::uint8_t> bad = out;
    std::uint64_t ulen;
    std::memcpy(&ulen, &bad[80 + 16], 8);
    ++ulen;
    std::memcpy(&bad[80 + 16], &ulen, 8);
    EXPECT_THROW(decode_ktx2(bad.data(), bad.size(), "bad.ktx2"), Error);
  }
}

// Fields that contradict the format are refused, naming the field: KTX1's
// glType, glTypeSize, glFormat and glBaseInternalFormat against its
// glInternalFormat; a DDS pitch or linear size, DX10 misc flags.
TEST(Container, ContradictingFieldsAreRefused) {
  const Texture t = random_texture(TexelFormat::rgba8_unorm, 8, 8, 1, 1, 1, 2);
  const std::vector<std::uint8_t> k1 = encode_ktx1(t);
  for (const auto& [at, field] : std::vector<std::pair<std::size_t, std::string>>{
           {16, "glType"}, {20, "glTypeSize"}, {24, "glFormat"}, {32, "glBaseInternalFormat"}}) {
    std::vector<std::uint8_t> b = k1;
    b[at] ^= 0x01;
    try {
      decode_ktx1(b.data(), b.size(), "k.ktx");
      ADD_FAILURE() << field << " accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(field + " 0x"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("contradicts glInternalFormat"), std::string::npos) << e.what();
    }
  }
  const Texture bc = random_texture(TexelFormat::bc3_unorm, 8, 8, 1, 1, 1, 2);
  std::vector<std::uint8_t> d = encode_dds(bc);
  const std::uint32_t wrong = 40;
  std::memcpy(&d[20], &wrong, 4);  // linear size of an 8x8 BC3 level is 64
  EXPECT_THROW(decode_dds(d.data(), d.size(), "d.dds"), Error);
  std::vector<std::uint8_t> x = encode_dds(random_texture(TexelFormat::rgba8_srgb, 8, 8, 1, 1, 1, 2));  // DX10 header
  const std::uint32_t misc = 0x5;
  std::memcpy(&x[128 + 8], &misc, 4);
  EXPECT_THROW(decode_dds(x.data(), x.size(), "x.dds"), Error);
}

// KTXorientation and KTXswizzle are honoured or refused, never ignored.
TEST(Container, Ktx2OrientationAndSwizzle) {
  auto patched = [](const Texture& t, const std::string& writer, const std::string& entry) {
    std::vector<std::uint8_t> b = encode_ktx2(t, writer);
    std::uint32_t kvd;
    std::memcpy(&kvd, &b[56], 4);
    std::uint32_t len;
    std::memcpy(&len, &b[kvd], 4);
    EXPECT_EQ(len, entry.size());
    std::memcpy(&b[kvd + 4], entry.data(), entry.size());
    return b;
  };
  const Texture t = random_texture(TexelFormat::rgba8_unorm, 4, 3, 1, 1, 1, 6);
  // "KTXwriter\0abcdefg\0" and "KTXorientation\0ru\0" are both 18 bytes.
  const std::string ru("KTXorientation\0ru", 18);
  std::vector<std::uint8_t> b = patched(t, "abcdefg", ru);
  const Texture flipped = decode_ktx2(b.data(), b.size(), "ru.ktx2");
  for (int y = 0; y < 3; ++y)
    EXPECT_EQ(0, std::memcmp(&flipped.image(0)[std::size_t(y) * 16], &t.image(0)[std::size_t(2 - y) * 16], 16)) << y;
  const std::string rd("KTXorientation\0rd", 18);
  b = patched(t, "abcdefg", rd);
  EXPECT_TRUE(decode_ktx2(b.data(), b.size(), "rd.ktx2").image(0) == t.image(0));
  // Block formats cannot be flipped row by row: refused, by name.
  const Texture c = random_texture(TexelFormat::bc1_rgb_unorm, 8, 8, 1, 1, 1, 6);
  b = patched(c, "abcdefg", ru);
  try {
    decode_ktx2(b.data(), b.size(), "c.ktx2");
    ADD_FAILURE() << "accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::unsupported);
    EXPECT_NE(std::string(e.what()).find("KTXorientation 'ru'"), std::string::npos) << e.what();
  }
  // "KTXwriter\0abcde\0" and "KTXswizzle\0bgra\0" are both 16 bytes.
  b = patched(t, "abcde", std::string("KTXswizzle\0bgra", 16));
  EXPECT_THROW(decode_ktx2(b.data(), b.size(), "s.ktx2"), Error);
  b = patched(t, "abcde", std::string("KTXswizzle\0rgba", 16));
  EXPECT_TRUE(decode_ktx2(b.data(), b.size(), "s.ktx2").image(0) == t.image(0));
}

// Zstandard-supercompressed writing: the same texture back, smaller for
// compressible data, levels unaligned; a level outside 1-22 is refused.
TEST(Container, Ktx2ZstdWrite) {
  Texture t = random_texture(TexelFormat::rgba8_unorm, 64, 32, full_levels(64, 32), 6 / 6, 3, 4);
  for (auto& img : t.images)
    for (std::size_t i = 0; i < img.size(); ++i) img[i] = std::uint8_t(i / 64);  // compressible
  const std::vector<std::uint8_t> plain = encode_ktx2(t, "w"), packed = encode_ktx2(t, "w", 9);
  EXPECT_LT(packed.size(), plain.size() / 4);
  std::uint32_t scheme;
  std::memcpy(&scheme, &packed[44], 4);
  EXPECT_EQ(scheme, 2u);
  const Texture back = decode_ktx2(packed.data(), packed.size(), "z.ktx2");
  ASSERT_EQ(back.images.size(), t.images.size());
  for (std::size_t i = 0; i < t.images.size(); ++i) EXPECT_TRUE(back.images[i] == t.images[i]) << i;
  EXPECT_THROW(encode_ktx2(t, "w", 99), Error);
}
