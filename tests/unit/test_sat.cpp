// Summed-area tables against brute force, worst cases, the file format, blur.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "support/images.h"
#include "support/run.h"
#include "texproc/color.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/runtime.h"
#include "texproc/sat.h"

using namespace texproc;
using namespace texproc::test;
namespace fs = std::filesystem;

namespace {
// The stored value as the table sums it: integer codes, or floats.
double code(const Image& img, int x, int y, int c) {
  switch (img.type()) {
    case PixelType::u8:
      return img.row<std::uint8_t>(y)[x * img.channels() + c];
    case PixelType::u16:
      return img.row<std::uint16_t>(y)[x * img.channels() + c];
    case PixelType::f32:
      return img.row<float>(y)[x * img.channels() + c];
  }
  return 0;
}
double brute_sum(const Image& img, int x0, int y0, int x1, int y1, int c) {
  double s = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) s += code(img, x, y, c);
  return s;
}
}  // namespace

// Every box of small odd-sized images, every precision, channel count and
// input type: integer tables exact, float tables within their stated bound.
TEST(Sat, EveryBoxMatchesBruteForce) {
  for (auto [w, h] : {std::pair{1, 1}, {5, 1}, {1, 6}, {13, 7}, {19, 11}}) {
    for (int ch = 1; ch <= 4; ++ch) {
      for (PixelType t : {PixelType::u8, PixelType::u16, PixelType::f32}) {
        const Image img = random_image(w, h, ch, t, unsigned(w * 100 + h * 10 + ch));
        for (SatPrecision p : {SatPrecision::u32, SatPrecision::u64, SatPrecision::f32, SatPrecision::f64}) {
          if (t == PixelType::f32 && (p == SatPrecision::u32 || p == SatPrecision::u64)) {
            EXPECT_THROW(build_sat(img.view(), p), Error);
            continue;
          }
          const SummedAreaTable s = build_sat(img.view(), p);
          const double bound = s.error_bound();
          if (p != SatPrecision::f32 && t != PixelType::f32) {
            EXPECT_EQ(bound, 0.0);
          }
          std::vector<double> got(ch);
          for (int y0 = 0; y0 <= h; ++y0)
            for (int y1 = y0; y1 <= h; ++y1)
              for (int x0 = 0; x0 <= w; ++x0)
                for (int x1 = x0; x1 <= w; ++x1) {
                  s.box_sum(x0, y0, x1, y1, got.data());
                  for (int c = 0; c < ch; ++c) {
                    const double want = brute_sum(img, x0, y0, x1, y1, c);
                    if (bound == 0.0) {
                      ASSERT_EQ(got[c], want) << to_string(p) << " " << w << "x" << h;
                    } else {
                      ASSERT_NEAR(got[c], want, bound * (1 + 1e-9) + std::abs(want) * 1e-15) << to_string(p);
                    }
                  }
                }
        }
      }
    }
  }
}

// 8192x8192 of 255 in a wrapping u32 table: the table's own entries overflow
// 2^32 many times over, yet every box up to the limit (16843009 texels, so
// any 4096x4096 box and the 4104x4104 maximum) sums exactly.
TEST(Sat, WrappingU32ExactUpToItsBoxLimit) {
  Image img = Image::uninitialized(8192, 8192, 1, PixelType::u8);
  std::memset(img.data(), 255, img.byte_size());
  const SummedAreaTable s = build_sat(img.view(), SatPrecision::u32);
  EXPECT_EQ(s.max_exact_box(), 16843009u);
  EXPECT_EQ(default_sat_precision(PixelType::u8, 8192, 8192), SatPrecision::u64);
  EXPECT_EQ(default_sat_precision(PixelType::u8, 4096, 4096), SatPrecision::u32);
  std::mt19937 rng(5);
  double got;
  for (int i = 0; i < 2000; ++i) {
    const int bw = 1 + int(rng() % 4096), bh = 1 + int(rng() % 4096);
    const int x0 = int(rng() % (8192 - bw + 1)), y0 = int(rng() % (8192 - bh + 1));
    s.box_sum(x0, y0, x0 + bw, y0 + bh, &got);
    ASSERT_EQ(got, 255.0 * bw * bh) << x0 << "," << y0 << " " << bw << "x" << bh;
  }
  s.box_sum(8192 - 4104, 8192 - 4104, 8192, 8192, &got);
  EXPECT_EQ(got, 255.0 * 4104 * 4104);
  s.box_sum(0, 0, 4096, 4096, &got);
  EXPECT_EQ(got, 255.0 * 4096 * 4096);
}

// f32 with the mean subtracted stays within half an 8-bit step for single
// texels on real images, where a plain f32 table is off by many steps.
TEST(Sat, F32MeanSubtractedHoldsSingleTexelsOnCorpusImages) {
  if (!have_corpus()) GTEST_SKIP() << "no corpus";
  for (const char* f : {"albedo_srgb/qt3d_galaxy_starfield_4096x2048.jpg", "albedo_srgb/wz2100_backdrop0_2048.png",
                        "photo/skimage_astronaut_512.png", "height/trigger_swiss_h_1024.png"}) {
    SCOPED_TRACE(f);
    const Image img = read_image(corpus_dir() + "/" + f);
    const SummedAreaTable s = build_sat(img.view(), SatPrecision::f32);
    std::mt19937 rng(1);
    double worst = 0.0;
    std::vector<double> got(img.channels());
    for (int i = 0; i < 20000; ++i) {
      const int x = int(rng() % img.width()), y = int(rng() % img.height());
      s.box_sum(x, y, x + 1, y + 1, got.data());
      for (int c = 0; c < img.channels(); ++c) worst = std::max(worst, std::abs(got[c] - code(img, x, y, c)));
    }
    EXPECT_LE(worst, 0.5);
    EXPECT_LE(worst, s.error_bound());
    RecordProperty(std::string("worst_single_texel_error_") + fs::path(f).stem().string(), std::to_string(worst));
  }
  // The contrast: a plain float table (float sums, nothing subtracted) of the
  // 2048x2048 backdrop misses single texels by whole steps.
  const Image img = read_image(corpus_dir() + "/albedo_srgb/wz2100_backdrop0_2048.png");
  const int W = img.width(), H = img.height();
  std::vector<float> plain(std::size_t(W) * H);
  for (int y = 0; y < H; ++y) {
    float run = 0;
    for (int x = 0; x < W; ++x) {
      run += float(code(img, x, y, 0));
      plain[std::size_t(y) * W + x] = run + (y ? plain[std::size_t(y - 1) * W + x] : 0.0f);
    }
  }
  double worst = 0;
  for (int y = H - 64; y < H; ++y)
    for (int x = W - 64; x < W; ++x) {
      const double v = double(plain[std::size_t(y) * W + x]) - plain[std::size_t(y) * W + x - 1] -
                       plain[std::size_t(y - 1) * W + x] + plain[std::size_t(y - 1) * W + x - 1];
      worst = std::max(worst, std::abs(v - code(img, x, y, 0)));
    }
  EXPECT_GT(worst, 10.0) << "a plain f32 table should fail here, or the test proves nothing";
}

TEST(Sat, SameBytesForAnyThreadCount) {
  const Image img = random_image(300, 333, 4, PixelType::u16, 2);
  for (SatPrecision p : {SatPrecision::u32, SatPrecision::u64, SatPrecision::f32, SatPrecision::f64}) {
    SummedAreaTable a, b;
    {
      ThreadLimit t(1);
      a = build_sat(img.view(), p);
    }
    {
      ThreadLimit t(2);
      b = build_sat(img.view(), p);
    }
    ASSERT_EQ(a.data.size(), b.data.size());
    EXPECT_EQ(0, std::memcmp(a.data.data(), b.data.data(), a.data.size())) << to_string(p);
  }
}

// The file: round trip, every truncation, and hostile header fields.
TEST(SatFile, RoundTripAndHostileFiles) {
  const std::string dir = temp_dir("satfile");
  const Image img = random_image(9, 7, 3, PixelType::u8, 4);
  const SummedAreaTable s = build_sat(img.view(), SatPrecision::f32);
  write_sat_file(dir + "/t.sat", s);
  const SummedAreaTable r = read_sat_file(dir + "/t.sat");
  EXPECT_EQ(r.width, 9);
  EXPECT_EQ(r.precision, SatPrecision::f32);
  EXPECT_EQ(r.block_means, s.block_means);
  EXPECT_EQ(r.max_abs_entry, s.max_abs_entry);
  EXPECT_EQ(0, std::memcmp(r.data.data(), s.data.data(), s.data.size()));
  const std::string good = slurp(dir + "/t.sat");
  auto rejects = [&](const std::string& bytes, const char* what) {
    std::ofstream(dir + "/bad.sat", std::ios::binary) << bytes;
    try {
      read_sat_file(dir + "/bad.sat");
      ADD_FAILURE() << "accepted: " << what;
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::invalid_file) << what;
      EXPECT_NE(std::string(e.what()).find("bad.sat"), std::string::npos);
    }
  };
  for (std::size_t n = 0; n < good.size(); ++n) rejects(good.substr(0, n), "truncated");
  rejects(good + "x", "trailing byte");
  // Each 4-byte header field set to 0 and to all ones; the magic, version and
  // reserved bytes flipped. (max |entry| as all ones is a NaN: rejected too.)
  for (std::size_t at = 0; at < 64; at += 4) {
    for (std::uint32_t v : {0u, 0xFFFFFFFFu}) {
      std::string b = good;
      std::memcpy(b.data() + at, &v, 4);
      if (b == good) continue;
      // The doubles at 32 and 56 (error-bound inputs): any low half, and a
      // zero high half, are still valid finite values; all-ones high is a NaN.
      if (at == 32 || at == 56 || ((at == 36 || at == 60) && v == 0)) continue;
      rejects(b, ("field at " + std::to_string(at)).c_str());
    }
  }
  // Sizes whose product would overflow 32 bits must not pass or crash.
  std::string big = good;
  const std::uint32_t side = 1u << 20;
  std::memcpy(big.data() + 8, &side, 4);
  std::memcpy(big.data() + 12, &side, 4);
  rejects(big, "huge sizes");
  fs::remove_all(dir);
}

namespace {
// Brute-force box blur of linear float data with integer radius.
Image brute_blur(const Image& img, int r, WrapMode wrap) {
  Image out(img.width(), img.height(), img.channels(), PixelType::f32);
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x)
      for (int c = 0; c < img.channels(); ++c) {
        double s = 0;
        for (int j = -r; j <= r; ++j)
          for (int i = -r; i <= r; ++i)
            s += img.get(wrap_index(x + i, img.width(), wrap), wrap_index(y + j, img.height(), wrap), c);
        out.set(x, y, c, float(s / ((2 * r + 1) * (2 * r + 1))));
      }
  return out;
}
}  // namespace

TEST(SatBlur, MatchesBruteForceConstantAndSeamless) {
  const Image img = random_image(23, 17, 3, PixelType::f32, 8);
  for (WrapMode w : {WrapMode::clamp, WrapMode::repeat}) {
    for (int r : {0, 1, 3, 20}) {
      BoxBlurOptions o;
      o.radius = float(r);
      o.wrap = w;
      const Image got = box_blur(img.view(), o), want = brute_blur(img, r, w);
      for (int y = 0; y < 17; ++y)
        for (int x = 0; x < 23; ++x)
          for (int c = 0; c < 3; ++c) ASSERT_NEAR(got.get(x, y, c), want.get(x, y, c), 1e-5) << r;
    }
  }
  // A constant (8-bit sRGB, with alpha) stays exactly constant.
  const float v[4] = {0.3f, 0.6f, 0.9f, 0.5f};
  const Image flat = constant_image(31, 9, 4, PixelType::u8, v);
  BoxBlurOptions o;
  o.radius = 5.5f;
  const Image f = box_blur(flat.view(), o);
  EXPECT_EQ(0, std::memcmp(f.data(), flat.data(), flat.byte_size()));
  // Repeat is seamless: shifting a tiling input shifts the output.
  const Image a = random_image(16, 16, 1, PixelType::f32, 3);
  Image b(16, 16, 1, PixelType::f32);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) b.set((x + 5) % 16, (y + 3) % 16, 0, a.get(x, y, 0));
  o = BoxBlurOptions{};
  o.radius = 4;
  o.wrap = WrapMode::repeat;
  const Image ba = box_blur(a.view(), o), bb = box_blur(b.view(), o);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) ASSERT_NEAR(bb.get((x + 5) % 16, (y + 3) % 16, 0), ba.get(x, y, 0), 1e-6);
}

// Gamma-correct: a one-texel checkerboard blurred with radius 1 over 3x3
// averages 4 or 5 whites of 9 in linear light, not in sRGB codes.
TEST(SatBlur, GammaCorrectAndRadiusMap) {
  const Image cb = checkerboard(16, 16, 3);
  BoxBlurOptions o;
  o.radius = 1;
  o.wrap = WrapMode::repeat;
  const Image out = box_blur(cb.view(), o);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const int whites = (x + y) % 2 ? 5 : 4;
      EXPECT_EQ(out.row<std::uint8_t>(y)[3 * x], linear_to_srgb8(whites / 9.0f));
    }
  // A radius map of zero leaves the image unchanged; of one, it is the full radius.
  Image zero(16, 16, 1, PixelType::u8), one(16, 16, 1, PixelType::u8);
  std::memset(one.data(), 255, one.byte_size());
  const ConstImageView zv = zero.view(), ov = one.view();
  o.radius_map = &zv;
  EXPECT_EQ(0, std::memcmp(box_blur(cb.view(), o).data(), cb.data(), cb.byte_size()));
  o.radius_map = &ov;
  EXPECT_EQ(0, std::memcmp(box_blur(cb.view(), o).data(), out.data(), out.byte_size()));
}

// The SIMD RGBA rows against their scalar twin on every target.
#include <hwy/targets.h>

#include "sat/sat_rows.h"

TEST(Sat, SimdRowsMatchReferenceOnEveryTarget) {
  std::mt19937 rng(12);
  for (int width : {1, 3, 17, 1000}) {
    std::vector<std::uint8_t> in8(4 * width);
    std::vector<std::uint16_t> in16(4 * width);
    std::vector<std::uint32_t> prev(4 * width), want(4 * width), got(4 * width);
    for (auto& v : in8) v = std::uint8_t(rng());
    for (auto& v : in16) v = std::uint16_t(rng());
    for (auto& v : prev) v = std::uint32_t(rng());  // wraps: arbitrary earlier rows
    for (int64_t target : hwy::SupportedAndGeneratedTargets()) {
      hwy::SetSupportedTargetsForTest(target);
      ref::sat_row_rgba8_u32(in8.data(), width, prev.data(), want.data());
      sat_row_rgba8_u32(in8.data(), width, prev.data(), got.data());
      EXPECT_EQ(got, want) << hwy::TargetName(target);
      ref::sat_row_rgba16_u32(in16.data(), width, prev.data(), want.data());
      sat_row_rgba16_u32(in16.data(), width, prev.data(), got.data());
      EXPECT_EQ(got, want) << hwy::TargetName(target);
    }
    hwy::SetSupportedTargetsForTest(0);
  }
}
