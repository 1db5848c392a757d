// BC4/BC5 encoding: known answers, against exhaustive search, and through
// the containers and the decoder.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "support/images.h"
#include "texproc/block_decode.h"
#include "texproc/block_encode.h"
#include "texproc/error.h"
#include "texproc/runtime.h"

using namespace texproc;
using namespace texproc::test;

// A flat block is exact for every value, in every quality, UNORM and SNORM.
TEST(Bc4Encode, FlatBlocksAreExact) {
  for (Quality q : {Quality::fast, Quality::normal, Quality::high}) {
    for (int v = 0; v <= 255; ++v) {
      float vals[16];
      std::fill(vals, vals + 16, float(v));
      std::uint8_t b[8];
      encode_bc4_block(vals, false, q, b);
      ASSERT_EQ(bc4_block_error(b, vals, false), 0.0) << v;
    }
    for (int v = -127; v <= 127; ++v) {
      float vals[16];
      std::fill(vals, vals + 16, float(v));
      std::uint8_t b[8];
      encode_bc4_block(vals, true, q, b);
      ASSERT_EQ(bc4_block_error(b, vals, true), 0.0) << v;
    }
  }
}

// Eight distinct levels that are exactly an eight-value palette, here
// r0 = 147 and r1 = 7: (147 (7 - k) + 7 k) / 7 = 147 - 20 k, all integers.
// The encoder must find the lossless block.
TEST(Bc4Encode, EightPaletteLevelsAreLossless) {
  float vals[16];
  for (int i = 0; i < 16; ++i) vals[i] = float(147 - 20 * (i % 8));
  for (Quality q : {Quality::fast, Quality::normal, Quality::high}) {
    std::uint8_t b[8];
    encode_bc4_block(vals, false, q, b);
    EXPECT_EQ(bc4_block_error(b, vals, false), 0.0) << to_string(q);
  }
  // 0 and 255 plus the six levels of a six-value palette (r0 = 40, r1 = 140:
  // steps of 20): the six-value mode, whose ends 0 and 255 come free, is exact.
  for (int i = 0; i < 16; ++i) vals[i] = i % 8 == 0 ? 0.0f : i % 8 == 1 ? 255.0f : float(40 + 20 * (i % 8 - 2));
  std::uint8_t b[8];
  encode_bc4_block(vals, false, Quality::normal, b);
  EXPECT_EQ(bc4_block_error(b, vals, false), 0.0);
}

// On small images, `high` is never more than 0.05 dB below the exhaustive
// search over every endpoint pair in both modes.
TEST(Bc4Encode, HighIsWithinAHundredthOfADecibelOfExhaustive) {
  std::mt19937 rng(2);
  std::normal_distribution<float> noise(0.0f, 6.0f);
  double se_high = 0, se_max = 0, se_fast = 0;
  for (int blk = 0; blk < 300; ++blk) {
    float vals[16];
    const float base = float(rng() % 200), slope = float(rng() % 9);
    for (int i = 0; i < 16; ++i) vals[i] = std::clamp(base + slope * (i % 4 + i / 4) + noise(rng), 0.0f, 255.0f);
    std::uint8_t b[8];
    encode_bc4_block(vals, false, Quality::high, b);
    se_high += bc4_block_error(b, vals, false);
    encode_bc4_block(vals, false, Quality::max, b);
    const double em = bc4_block_error(b, vals, false);
    se_max += em;
    encode_bc4_block(vals, false, Quality::fast, b);
    se_fast += bc4_block_error(b, vals, false);
  }
  auto psnr = [](double se) { return 10 * std::log10(255.0 * 255.0 / (se / (300 * 16))); };
  EXPECT_GE(psnr(se_high), psnr(se_max) - 0.05);
  EXPECT_GE(psnr(se_max), psnr(se_high) - 1e-9);  // the exhaustive search is the best there is
  EXPECT_GT(psnr(se_high), psnr(se_fast));
  RecordProperty("psnr_fast_high_max", std::to_string(psnr(se_fast)) + " " + std::to_string(psnr(se_high)) + " " +
                                           std::to_string(psnr(se_max)));
}

// Whole images: BC5 SNORM of a normal map's X and Y, partial blocks, same
// bytes for any thread count, and decoded values close to the input.
TEST(Bc5Encode, ImagesDeterministicAndClose) {
  const Image img = random_image(37, 22, 3, PixelType::u8, 4);
  std::vector<std::uint8_t> one, two;
  {
    ThreadLimit t(1);
    one = compress_image(img.view(), TexelFormat::bc5_snorm, Quality::normal);
  }
  {
    ThreadLimit t(2);
    two = compress_image(img.view(), TexelFormat::bc5_snorm, Quality::normal);
  }
  EXPECT_EQ(one, two);
  ASSERT_EQ(one.size(), std::size_t(10 * 6 * 16));
  // A smooth image decodes back within half a palette step: a block spans at
  // most 0.4 * 0.3 * 3 = 0.36 of the range (about 92 levels), so 8 palette
  // values leave at most 92 / 14 = 6.6 levels of error.
  Image smooth(37, 22, 2, PixelType::u8);
  for (int y = 0; y < 22; ++y)
    for (int x = 0; x < 37; ++x) {
      smooth.set(x, y, 0, 0.5f + 0.4f * std::sin(x * 0.2f));
      smooth.set(x, y, 1, 0.5f + 0.4f * std::cos(y * 0.3f));
    }
  Texture t;
  t.format = TexelFormat::bc5_unorm;
  t.width = 37;
  t.height = 22;
  t.images.push_back(compress_image(smooth.view(), TexelFormat::bc5_unorm, Quality::high));
  const Image back = decode_texture_image(t, 0, 0, 0, PixelType::f32);
  for (int y = 0; y < 22; ++y)
    for (int x = 0; x < 37; ++x)
      for (int c = 0; c < 2; ++c) ASSERT_NEAR(back.get(x, y, c), smooth.get(x, y, c), 7.0 / 255) << x << "," << y;
  EXPECT_THROW(compress_image(img.view(), TexelFormat::bc1_rgb_unorm, Quality::normal), Error);
}
