// sRGB transfer functions and color spaces.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "texproc/color.h"
#include "texproc/error.h"

using namespace texproc;

TEST(Srgb, EightBitCodesRoundTripExactly) {
  for (int k = 0; k < 256; ++k) EXPECT_EQ(linear_to_srgb8(srgb8_to_linear(std::uint8_t(k))), k) << k;
}

TEST(Srgb, SixteenBitCodesRoundTripExactly) {
  for (int k = 0; k < 65536; ++k) ASSERT_EQ(linear_to_srgb16(srgb16_to_linear(std::uint16_t(k))), k) << k;
}

// Correct rounding: the table-and-threshold encoder must agree with the
// double-precision formula rounded to nearest, for every float we try.
TEST(Srgb, EightBitEncodeIsCorrectlyRounded) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 200000; ++i) {
    const float x = i < 100000 ? u(rng) : u(rng) * 0.01f;  // dense near 0, where the curve is steep
    const double exact = linear_to_srgb(x) * 255.0;
    if (std::abs(exact - std::floor(exact) - 0.5) < 1e-9) continue;  // a tie: either is right
    ASSERT_EQ(linear_to_srgb8(x), int(std::lround(exact))) << x;
  }
  EXPECT_EQ(linear_to_srgb8(-1.0f), 0);
  EXPECT_EQ(linear_to_srgb8(2.0f), 255);
  EXPECT_EQ(linear_to_srgb8(std::nanf("")), 0);
}

// Known values: linear 0.5 is sRGB 0.7354, i.e. 187.5 in 8 bits (the
// checkerboard test below relies on it); 0.2140 is sRGB 0.5 (127.5).
TEST(Srgb, KnownValues) {
  EXPECT_NEAR(linear_to_srgb(0.5), 0.735356983, 1e-9);
  EXPECT_NEAR(srgb_to_linear(0.5), 0.214041140, 1e-9);
  EXPECT_DOUBLE_EQ(srgb_to_linear(0.0), 0.0);
  EXPECT_DOUBLE_EQ(srgb_to_linear(1.0), 1.0);
  EXPECT_NEAR(srgb8_to_linear(188), 0.5029, 1e-4);
}

TEST(ColorSpace, BuiltinNames) {
  EXPECT_TRUE(ColorSpace::from_name("linear").is_linear());
  EXPECT_TRUE(ColorSpace::from_name("raw").is_linear());
  EXPECT_TRUE(ColorSpace::from_name("sRGB").is_srgb());
  EXPECT_TRUE(ColorSpace::from_name("srgb").is_srgb());
}

TEST(ColorSpace, UnknownNameListsValidOnes) {
  try {
    ColorSpace::from_name("no-such-space");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::bad_arguments);
    const std::string msg = e.what();
    EXPECT_NE(msg.find("no-such-space"), std::string::npos);
    EXPECT_NE(msg.find("ACEScg"), std::string::npos) << msg;
    EXPECT_NE(msg.find("srgb"), std::string::npos) << msg;
  }
}

// The built-in OCIO config's "sRGB - Texture" must match texproc's exact sRGB.
TEST(ColorSpace, OcioSrgbMatchesBuiltin) {
  const ColorSpace ocio = ColorSpace::from_name("sRGB - Texture");
  EXPECT_FALSE(ocio.is_srgb());
  std::uint8_t px[256 * 3];
  for (int i = 0; i < 256 * 3; ++i) px[i] = std::uint8_t(i / 3);
  float a[256 * 3], b[256 * 3];
  ocio.decode_row(px, PixelType::u8, 3, 256, a);
  ColorSpace::srgb().decode_row(px, PixelType::u8, 3, 256, b);
  for (int i = 0; i < 256 * 3; ++i) EXPECT_NEAR(a[i], b[i], 2e-5) << i;
  std::uint8_t back[256 * 3];
  ocio.encode_row(a, 3, 256, back, PixelType::u8);
  for (int i = 0; i < 256 * 3; ++i) EXPECT_EQ(back[i], px[i]) << i;
}

// ACEScg primaries are wider than Rec.709: pure ACEScg red has negative
// green and blue in linear Rec.709, red about 1.705 (the AP1 -> Rec.709
// Bradford matrix). Round trip returns the input.
TEST(ColorSpace, OcioAcesCgRoundTrip) {
  const ColorSpace cg = ColorSpace::from_name("ACEScg");
  float px[4] = {1.0f, 0.0f, 0.0f, 0.5f};
  float lin[4];
  cg.decode_row(px, PixelType::f32, 4, 1, lin);
  EXPECT_NEAR(lin[0], 1.705, 2e-3);
  EXPECT_LT(lin[1], 0.0f);
  EXPECT_FLOAT_EQ(lin[3], 0.5f);  // alpha untouched
  float back[4];
  cg.encode_row(lin, 4, 1, back, PixelType::f32);
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(back[c], px[c], 1e-5);
}

// The RGBA8 sRGB row codecs: every SIMD target against the scalar reference,
// bit for bit, on every code and on hostile floats (NaN, negatives, > 1,
// zero and tiny alpha, values on the rounding thresholds).
#include <hwy/targets.h>

#include "image/srgb_rows.h"

TEST(SrgbRows, SimdTwinsMatchReferenceOnEveryTarget) {
  std::vector<std::uint8_t> bytes(4 * 1031);
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = std::uint8_t((i * 37 + i / 4) & 255);
  std::vector<float> floats(4 * 1031);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-0.2f, 1.3f);
  for (std::size_t i = 0; i < floats.size(); ++i) {
    switch (i % 11) {
      case 0:
        floats[i] = std::nanf("");
        break;
      case 1:
        floats[i] = float(srgb_to_linear((i % 255 + 0.5) / 255.0));
        break;  // near a threshold
      case 2:
        floats[i] = 1e-30f;
        break;
      case 3:
        floats[i] = 0.0f;
        break;
      default:
        floats[i] = u(rng);
    }
  }
  const int n = int(bytes.size() / 4);
  std::vector<float> dec_ref(bytes.size()), dec(bytes.size());
  std::vector<std::uint8_t> enc_ref(bytes.size()), enc(bytes.size());
  ref::decode_srgb8_rgba_premultiplied(bytes.data(), n, dec_ref.data());
  ref::encode_srgb8_rgba_unpremultiplied(floats.data(), n, enc_ref.data());
  for (int64_t target : hwy::SupportedAndGeneratedTargets()) {
    hwy::SetSupportedTargetsForTest(target);
    SCOPED_TRACE(hwy::TargetName(target));
    decode_srgb8_rgba_premultiplied(bytes.data(), n, dec.data());
    encode_srgb8_rgba_unpremultiplied(floats.data(), n, enc.data());
    EXPECT_EQ(0, std::memcmp(dec.data(), dec_ref.data(), dec.size() * sizeof(float)));
    EXPECT_EQ(enc, enc_ref);
  }
  hwy::SetSupportedTargetsForTest(0);
  // And the reference agrees with the plain per-value functions.
  for (int i = 0; i < n; ++i) {
    const float a = bytes[4 * i + 3] * (1.0f / 255.0f);  // as decode_row scales alpha
    EXPECT_EQ(dec_ref[4 * i], srgb8_to_linear(bytes[4 * i]) * a);
    const float fa = floats[4 * i + 3];
    const float inv = fa > 0.0f ? 1.0f / fa : 0.0f;
    EXPECT_EQ(enc_ref[4 * i + 1], linear_to_srgb8(floats[4 * i + 1] * inv));
  }
}

// Every float in [0, 1] (a stride through all 1.07e9 of them) encodes to
// round(255 * srgb(x)) computed in double.
TEST(Srgb, EncoderExactOnAStrideOfAllFloats) {
  for (std::uint32_t bits = 0; bits <= 0x3F800000u; bits += 997) {
    float x;
    std::memcpy(&x, &bits, 4);
    const double exact = linear_to_srgb(x) * 255.0;
    if (std::abs(exact - std::floor(exact) - 0.5) < 1e-9) continue;
    ASSERT_EQ(linear_to_srgb8(x), int(std::lround(exact))) << x;
  }
}
