// BC1-BC5 decoding: blocks built by hand from the specification, and
// decoders no one here wrote (libsquish, OpenImageIO's DDS reader).
#include <gtest/gtest.h>
#include <squish.h>

#include <Imath/half.h>

#include <cmath>
#include <cstring>
#include <random>

#include "bc/bc_decode.h"
#include "etc/etc_tables.h"
#include "support/images.h"
#include "texproc/block_decode.h"
#include "texproc/container.h"
#include "texproc/error.h"

using namespace texproc;
using namespace texproc::test;
namespace fs = std::filesystem;

namespace {
int to8(float v) { return int(std::lround(v * 255.0f)); }
}  // namespace

// BC1, four-colour mode: c0 = pure red (0xF800) > c1 = pure blue (0x001F).
// Expanded: red (255, 0, 0), blue (0, 0, 255); c2 = (2 red + blue) / 3 =
// (170, 0, 85), c3 = (85, 0, 170), rounded to nearest. Indices 0, 1, 2, 3
// repeating: bits 11 10 01 00 per byte = 0xE4.
TEST(BcDecode, Bc1FourColour) {
  const std::uint8_t block[8] = {0x00, 0xF8, 0x1F, 0x00, 0xE4, 0xE4, 0xE4, 0xE4};
  float t[16][4];
  decode_block(TexelFormat::bc1_rgb_unorm, block, t);
  const int want[4][3] = {{255, 0, 0}, {0, 0, 255}, {170, 0, 85}, {85, 0, 170}};
  for (int i = 0; i < 16; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(to8(t[i][c]), want[i % 4][c]) << i;
  for (int i = 0; i < 16; ++i) EXPECT_EQ(t[i][3], 1.0f);
}

// BC1, three-colour mode (c0 <= c1): c2 is the average, index 3 is black,
// transparent for BC1 with alpha. Green 0x07E0 (0, 255, 0) and white 0xFFFF.
TEST(BcDecode, Bc1ThreeColourAndPunchThrough) {
  const std::uint8_t block[8] = {0xE0, 0x07, 0xFF, 0xFF, 0xE4, 0xE4, 0xE4, 0xE4};
  float t[16][4];
  decode_block(TexelFormat::bc1_rgba_unorm, block, t);
  EXPECT_EQ(to8(t[2][0]), 128);  // (0 + 255 + 1) / 2
  EXPECT_EQ(to8(t[2][1]), 255);
  EXPECT_EQ(t[3][0], 0.0f);
  EXPECT_EQ(t[3][3], 0.0f);  // transparent
  EXPECT_EQ(t[1][3], 1.0f);
  decode_block(TexelFormat::bc1_rgb_unorm, block, t);
  EXPECT_EQ(t[3][3], 1.0f);  // opaque black without the alpha variant
}

// BC4: r0 = 200 > r1 = 100, 8-value mode: code k in 2..7 is ((8-k) r0 +
// (k-1) r1) / 7 exactly; r0 = 100 <= r1 = 200, 6-value mode with 0 and 1.
// Indices: texel i gets code i % 8 (3 bits each, texel 0 lowest).
TEST(BcDecode, Bc4BothModesExact) {
  std::uint8_t block[8] = {200, 100};
  std::uint64_t bits = 0;
  for (int i = 0; i < 16; ++i) bits |= std::uint64_t(i % 8) << (3 * i);
  for (int b = 0; b < 6; ++b) block[2 + b] = std::uint8_t(bits >> (8 * b));
  float t[16][4];
  decode_block(TexelFormat::bc4_unorm, block, t);
  EXPECT_FLOAT_EQ(t[0][0], 200 / 255.0f);
  EXPECT_FLOAT_EQ(t[1][0], 100 / 255.0f);
  for (int k = 2; k < 8; ++k) EXPECT_FLOAT_EQ(t[k][0], float(((8 - k) * 200 + (k - 1) * 100) / 7.0 / 255.0)) << k;
  block[0] = 100;
  block[1] = 200;
  decode_block(TexelFormat::bc4_unorm, block, t);
  for (int k = 2; k < 6; ++k) EXPECT_FLOAT_EQ(t[k][0], float(((6 - k) * 100 + (k - 1) * 200) / 5.0 / 255.0)) << k;
  EXPECT_EQ(t[6][0], 0.0f);
  EXPECT_EQ(t[7][0], 1.0f);
  // SNORM: -128 decodes as -127 (-1.0); endpoints 127 and -128.
  block[0] = 127;
  block[1] = 0x80;
  decode_block(TexelFormat::bc4_snorm, block, t);
  EXPECT_EQ(t[0][0], 1.0f);
  EXPECT_EQ(t[1][0], -1.0f);
  EXPECT_FLOAT_EQ(t[4][0], float((4 * 127 + 3 * -127) / 7.0 / 127.0));
}

// BC2: explicit 4-bit alpha, a * 17; the colour half always four-colour.
TEST(BcDecode, Bc2ExplicitAlpha) {
  std::uint8_t block[16] = {0x10, 0x32, 0x54, 0x76, 0x98, 0xBA, 0xDC, 0xFE,   // alpha 0..15
                            0x1F, 0x00, 0x00, 0xF8, 0xE4, 0xE4, 0xE4, 0xE4};  // c0 = blue < c1 = red
  float t[16][4];
  decode_block(TexelFormat::bc2_unorm, block, t);
  for (int i = 0; i < 16; ++i) EXPECT_EQ(to8(t[i][3]), i * 17) << i;
  EXPECT_EQ(to8(t[2][2]), 170);  // four-colour even though c0 < c1
  EXPECT_EQ(to8(t[2][0]), 85);
}

// libsquish's decoder (Debian's 1.15, scalar) on random BC1-BC3 blocks:
// identical except where interpolated colours round differently (libsquish
// truncates (2a + b) / 3; texproc rounds to nearest): at most one level.
TEST(BcDecode, MatchesLibsquishWithinOneLevel) {
  std::mt19937 rng(3);
  struct Case {
    TexelFormat f;
    int flags;
    int bytes;
  };

  for (const Case& c :
       {Case{TexelFormat::bc1_rgba_unorm, squish::kDxt1, 8}, Case{TexelFormat::bc2_unorm, squish::kDxt3, 16},
        Case{TexelFormat::bc3_unorm, squish::kDxt5, 16}}) {
    for (int n = 0; n < 4000; ++n) {
      std::uint8_t block[16];
      for (auto& b : block) b = std::uint8_t(rng());
      squish::u8 rgba[64];
      squish::Decompress(rgba, block, c.flags);
      float t[16][4];
      decode_block(c.f, block, t);
      for (int i = 0; i < 16; ++i)
        for (int ch = 0; ch < 4; ++ch) {
          const int d = std::abs(to8(t[i][ch]) - rgba[4 * i + ch]);
          ASSERT_LE(d, 1) << format_info(c.f).name << " block " << n << " texel " << i << " channel " << ch;
        }
      // Endpoints are not interpolated: with every index 0 (colour c0, and
      // alpha a0 for BC3) the two decoders agree exactly.
      std::uint8_t ends[16];
      std::memcpy(ends, block, 16);
      const int color_at = c.bytes == 16 ? 8 : 0;
      std::memset(ends + color_at + 4, 0, 4);
      if (c.f == TexelFormat::bc3_unorm) std::memset(ends + 2, 0, 6);
      squish::Decompress(rgba, ends, c.flags);
      decode_block(c.f, ends, t);
      for (int i = 0; i < 16; ++i)
        for (int ch = 0; ch < 4; ++ch) ASSERT_EQ(to8(t[i][ch]), rgba[4 * i + ch]) << format_info(c.f).name;
    }
  }
}

// 8-bit output decodes each block straight to bytes (the palettes' integers,
// the 8-bit decoders' texels): the same bytes as the float decoder's texels
// stored through Image::set (SNORM biased to [0, 1]), for every 4x4 block
// format, on random blocks, at sizes with and without partial blocks.
TEST(BlockDecode, EightBitOutputEqualsTheFloatDecoderStored) {
  using F = TexelFormat;
  std::mt19937 rng(5);
  for (F f : {F::bc1_rgb_unorm,   F::bc1_rgba_srgb, F::bc2_unorm,     F::bc3_srgb,       F::bc4_unorm,
              F::bc4_snorm,       F::bc5_unorm,     F::bc5_snorm,     F::bc6h_ufloat,    F::bc6h_sfloat,
              F::bc7_unorm,       F::bc7_srgb,      F::etc1_rgb,      F::etc2_rgb_srgb,  F::etc2_rgba1_unorm,
              F::etc2_rgba8_srgb, F::eac_r11_unorm, F::eac_r11_snorm, F::eac_rg11_unorm, F::eac_rg11_snorm}) {
    const FormatInfo& info = format_info(f);
    // Partial blocks; whole blocks only (each row's last block a run's
    // last); one block.
    for (auto [w, h] : {std::pair{37, 22}, std::pair{16, 12}, std::pair{4, 4}}) {
      const int bw = (w + 3) / 4, bh = (h + 3) / 4;
      std::vector<std::uint8_t> blocks(std::size_t(bw) * bh * info.block_bytes);
      for (auto& b : blocks) b = std::uint8_t(rng());
      const Image u8 = decompress_image(blocks, w, h, f, PixelType::u8);
      const Image f32 = decompress_image(blocks, w, h, f, PixelType::f32);
      ASSERT_EQ(u8.channels(), f32.channels()) << info.name;
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          for (int c = 0; c < u8.channels(); ++c) {
            float v = f32.get(x, y, c);
            if (info.snorm) v = (v + 1.0f) * 0.5f;
            const float cl = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;
            ASSERT_EQ(u8.row<const std::uint8_t>(y)[x * u8.channels() + c], std::uint8_t(cl * 255.0f + 0.5f))
                << info.name << " " << w << "x" << h << " at " << x << "," << y << " channel " << c;
          }
    }
  }
}

// BC4's 8-bit palette comes from tables (bc_decode.cpp): every endpoint pair,
// UNORM and SNORM, with indices covering all eight entries, gives the float
// decoder's values through to_unorm8, on the per-block and the row paths.
TEST(BlockDecode, Bc4EightBitTablesMatchTheFloatDecoderForEveryEndpointPair) {
  std::uint8_t block[8] = {0, 0, 0x88, 0xC6, 0xFA, 0x88, 0xC6, 0xFA};  // indices 0..7 twice
  for (bool snorm : {false, true})
    for (int r0 = 0; r0 < 256; ++r0)
      for (int r1 = 0; r1 < 256; ++r1) {
        block[0] = std::uint8_t(r0);
        block[1] = std::uint8_t(r1);
        float f[16][4] = {};
        std::uint8_t u[16][4] = {}, rows[4][4];
        bc::decode_rgtc(block, snorm, 0, f);
        bc::decode_rgtc_u8(block, snorm, 0, u);
        bc::decode_rgtc_run(block, 1, 8, snorm, 1, 0, rows[0], 4);
        for (int i = 0; i < 16; ++i) {
          const std::uint8_t want = bc::to_unorm8(snorm ? (f[i][0] + 1.0f) * 0.5f : f[i][0]);
          ASSERT_EQ(u[i][0], want) << (snorm ? "SNORM " : "UNORM ") << r0 << "," << r1 << " texel " << i;
          ASSERT_EQ(rows[i / 4][i % 4], want) << (snorm ? "SNORM " : "UNORM ") << r0 << "," << r1 << " texel " << i;
        }
      }
}

// EAC R11's 8-bit rows come from a table of the 11-bit values
// (etc_decode.cpp): every base, multiplier and modifier table, UNORM and
// SNORM, with indices covering all eight entries, gives decode_eac11's value
// stored as Image::set stores value / 2047 (SNORM value / 1023, biased), in
// one and two channels.
TEST(BlockDecode, EacEightBitRowsMatchTheElevenBitDecoderForEveryBlockHeader) {
  // Indices 0..7 twice (texel k's index in bits 47 - 3k down).
  std::uint64_t indices = 0;
  for (int k = 0; k < 16; ++k) indices |= std::uint64_t(k & 7) << (45 - 3 * k);
  for (bool snorm : {false, true})
    for (int header = 0; header < 1 << 16; ++header) {
      std::uint8_t block[8];
      etc::store_be64(std::uint64_t(header) << 48 | indices, block);
      int v[16];
      etc::decode_eac11(block, snorm, v);
      std::uint8_t one[4][4], two[4][8];
      etc::decode_eac11_u8_run(block, 1, 8, snorm, 1, 0, one[0], 4);
      etc::decode_eac11_u8_run(block, 1, 8, snorm, 2, 1, two[0], 8);
      for (int i = 0; i < 16; ++i) {
        const std::uint8_t want = bc::to_unorm8(snorm ? (float(v[i]) / 1023.0f + 1.0f) * 0.5f : float(v[i]) / 2047.0f);
        ASSERT_EQ(one[i / 4][i % 4], want) << (snorm ? "SNORM " : "UNORM ") << "header " << header << " texel " << i;
        ASSERT_EQ(two[i / 4][2 * (i % 4) + 1], want)
            << (snorm ? "SNORM " : "UNORM ") << "header " << header << " texel " << i;
      }
    }
}

// BC6H's float rows (each palette entry converted once, in SSE2 lanes where
// the target has them) hold, bit for bit, the halves decode_bc6h gives
// converted by Imath, for UF16 and SF16 on random blocks (every mode, the
// reserved ones included) and on blocks of one mode each with random
// bits, rows apart by a stride wider than a block.
TEST(BlockDecode, Bc6hFloatRowsAreTheHalvesConverted) {
  std::mt19937 rng(61);
  const int modes[] = {0,  1, 2, 6,  10, 14, 18, 22, 26,
                       30, 3, 7, 11, 15, 19, 23, 27, 31};  // 5-bit and 2-bit mode numbers
  for (bool is_signed : {false, true})
    for (int n = 0; n < 40000; ++n) {
      std::uint8_t block[16];
      for (auto& b : block) b = std::uint8_t(rng());
      if (n % 2) {  // one of the modes (and the reserved numbers), the rest random
        const int m = modes[(n / 2) % 18];
        block[0] = std::uint8_t((block[0] & ~(m < 2 ? 3 : 31)) | m);
      }
      std::uint16_t halves[16][3];
      bc::decode_bc6h(block, is_signed, halves);
      float rows[4][20];
      for (auto& r : rows)
        for (float& v : r) v = 7.0f;
      bc::decode_bc6h_f32_rows(block, is_signed, rows[0], 20);
      for (int i = 0; i < 16; ++i)
        for (int c = 0; c < 3; ++c) {
          Imath::half h;
          h.setBits(halves[i][c]);
          const float want = float(h), got = rows[i / 4][3 * (i % 4) + c];
          std::uint32_t wb, gb;
          std::memcpy(&wb, &want, 4);
          std::memcpy(&gb, &got, 4);
          ASSERT_EQ(gb, wb) << (is_signed ? "SF16" : "UF16") << " block " << n << " texel " << i << " channel " << c;
        }
      for (auto& r : rows)
        for (int x = 12; x < 20; ++x) ASSERT_EQ(r[x], 7.0f) << "wrote past the block's 12 floats";
    }
}
