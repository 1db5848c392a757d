// The mip chain, against known answers and a brute-force oracle.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numeric>

#include "support/filters.h"
#include "support/images.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/mip.h"
#include "texproc/runtime.h"

using namespace texproc;
using namespace texproc::test;

namespace {

MipOptions options(FilterKind k, WrapMode w) {
  MipOptions o;
  o.filter.kind = k;
  o.wrap = w;
  return o;
}

bool same_bytes(const Image& a, const Image& b) {
  return a.width() == b.width() && a.height() == b.height() && a.channels() == b.channels() && a.type() == b.type() &&
         std::memcmp(a.data(), b.data(), a.byte_size()) == 0;
}
}  // namespace

// Library errors speak the API's terms: a C++ caller reads the option's name.
TEST(MipErrors, NameTheOptionInApiTerms) {
  const Image gray(8, 8, 1, PixelType::u8);
  MipOptions o;
  o.normal_map = true;
  try {
    generate_mips(gray.view(), o);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("MipOptions::normal_map needs an RGB or RGBA image"), std::string::npos)
        << e.what();
  }
  o = MipOptions{};
  o.filter.sigma = 9.0f;
  try {
    generate_mips(Image(8, 8, 3, PixelType::u8).view(), o);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("MipOptions::filter.sigma"), std::string::npos) << e.what();
  }
}

TEST(MipLevels, SizesFollowFloorHalving) {
  auto sizes = [](int w, int h) {
    std::vector<std::pair<int, int>> s;
    for (int l = 0; l < mip_level_count(w, h); ++l) s.emplace_back(mip_level_dim(w, l), mip_level_dim(h, l));
    return s;
  };
  using V = std::vector<std::pair<int, int>>;
  EXPECT_EQ(sizes(1, 1), (V{{1, 1}}));
  EXPECT_EQ(sizes(3, 5), (V{{3, 5}, {1, 2}, {1, 1}}));
  EXPECT_EQ(sizes(100, 60), (V{{100, 60}, {50, 30}, {25, 15}, {12, 7}, {6, 3}, {3, 1}, {1, 1}}));
  EXPECT_EQ(mip_level_count(4096, 1), 13);
  EXPECT_EQ(mip_level_dim(4096, 12), 1);
  EXPECT_EQ(mip_level_count(4096, 4096, 3), 3);
  EXPECT_EQ(mip_level_count(256, 64, 0, 16), 5);  // 256, 128, 64, 32, 16
}

TEST(MipLevels, ChainHasThoseSizes) {
  for (auto [w, h] : {std::pair{1, 1}, {3, 5}, {100, 60}, {4096, 1}}) {
    const Image img = random_image(w, h, 3, PixelType::u8, 1);
    const MipChain c = generate_mips(img.view(), MipOptions{});
    ASSERT_EQ(int(c.levels.size()), mip_level_count(w, h));
    for (int l = 0; l < int(c.levels.size()); ++l) {
      EXPECT_EQ(c.levels[l].width(), mip_level_dim(w, l));
      EXPECT_EQ(c.levels[l].height(), mip_level_dim(h, l));
    }
    EXPECT_TRUE(same_bytes(c.levels[0], img));  // level 0 is the input
  }
}

// A one-texel black/white checkerboard averages to linear 0.5, which is sRGB
// 187.5: a gamma-correct filter gives 187 or 188 everywhere (with repeat, no
// edge effects); a gamma-ignorant one gives 127-128. Every symmetric filter
// weighs the two colors equally when halving, so this holds for all of them.
TEST(MipGamma, CheckerboardGives187or188) {
  const Image img = checkerboard(64, 32, 3);
  for (FilterKind k : kAllFilters) {
    const MipChain c = generate_mips(img.view(), options(k, WrapMode::repeat));
    for (std::size_t l = 1; l < c.levels.size(); ++l) {
      const Image& lv = c.levels[l];
      for (int y = 0; y < lv.height(); ++y)
        for (int x = 0; x < lv.width() * 3; ++x) {
          const int v = lv.row<std::uint8_t>(y)[x];
          ASSERT_TRUE(v == 187 || v == 188) << to_string(k) << " level " << l << " got " << v;
        }
    }
  }
}

// The same data declared linear: the average 127.5 gives 127 or 128.
TEST(MipGamma, LinearCheckerboardGives127or128) {
  const Image img = checkerboard(32, 32, 4);
  MipOptions o = options(FilterKind::gaussian, WrapMode::repeat);
  o.color_space = "linear";
  const MipChain c = generate_mips(img.view(), o);
  for (std::size_t l = 1; l < c.levels.size(); ++l)
    for (int y = 0; y < c.levels[l].height(); ++y)
      for (int x = 0; x < c.levels[l].width(); ++x) {
        const std::uint8_t* p = c.levels[l].row<std::uint8_t>(y) + 4 * x;
        for (int ch = 0; ch < 3; ++ch) ASSERT_TRUE(p[ch] == 127 || p[ch] == 128) << int(p[ch]);
        ASSERT_EQ(p[3], 255);
      }
}

// Normalized weights: a constant stays that constant, exactly, at every level,
// for every filter, wrap, odd size, type and channel count.
TEST(MipExact, ConstantImageStaysConstant) {
  const float value[4] = {0.2f, 0.55f, 0.9f, 0.6f};
  for (PixelType t : {PixelType::u8, PixelType::u16}) {
    for (int ch : {1, 2, 3, 4}) {
      const Image img = constant_image(37, 23, ch, t, value);
      for (FilterKind k : kAllFilters)
        for (WrapMode w : kAllWraps) {
          const MipChain c = generate_mips(img.view(), options(k, w));
          for (std::size_t l = 1; l < c.levels.size(); ++l) {
            const Image& lv = c.levels[l];
            for (int y = 0; y < lv.height(); ++y)
              for (int x = 0; x < lv.width(); ++x)
                for (int i = 0; i < ch; ++i)
                  ASSERT_EQ(lv.get(x, y, i), img.get(0, 0, i))
                      << to_string(k) << " " << to_string(w) << " " << to_string(t) << " ch " << ch;
          }
        }
    }
  }
}

// With repeat and even sizes every source texel contributes exactly 1/4 of a
// destination texel's weight in total, so the linear mean is kept.
TEST(MipExact, LinearMeanPreservedWithRepeat) {
  const Image img = random_image(128, 64, 3, PixelType::f32, 3);
  for (FilterKind k : kAllFilters) {
    const MipChain c = generate_mips(img.view(), options(k, WrapMode::repeat));
    double mean0[3] = {};
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 128; ++x)
        for (int i = 0; i < 3; ++i) mean0[i] += img.get(x, y, i) / (128.0 * 64.0);
    for (std::size_t l = 1; l < c.levels.size(); ++l) {
      const Image& lv = c.levels[l];
      double mean[3] = {};
      for (int y = 0; y < lv.height(); ++y)
        for (int x = 0; x < lv.width(); ++x)
          for (int i = 0; i < 3; ++i) mean[i] += lv.get(x, y, i) / (double(lv.width()) * lv.height());
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(mean[i], mean0[i], 2e-6) << to_string(k) << " level " << l;
    }
  }
}

// Brute force: level 1 straight from the definition, in double, as a full 2D
// sum over every source texel (no separability, no padding, no SIMD).
TEST(MipOracle, LevelOneMatchesDirectTwoDimensionalSum) {
  for (auto [w, h] : {std::pair{16, 12}, {13, 7}, {9, 3}}) {
    const Image img = random_image(w, h, 2, PixelType::f32, 11);
    for (FilterKind k : {FilterKind::triangle, FilterKind::gaussian, FilterKind::lanczos3, FilterKind::mitchell})
      for (WrapMode wm : kAllWraps) {
        MipOptions o = options(k, wm);
        o.premultiplied_alpha = false;
        const MipChain c = generate_mips(img.view(), o);
        const Image& l1 = c.levels[1];
        const int dw = l1.width(), dh = l1.height();
        const double sx = double(w) / dw, sy = double(h) / dh;
        const Filter f{k, 0.5f};
        const double r = filter_support(f);
        for (int y = 0; y < dh; ++y)
          for (int x = 0; x < dw; ++x)
            for (int ch = 0; ch < 2; ++ch) {
              const double cx = (x + 0.5) * sx - 0.5, cy = (y + 0.5) * sy - 0.5;
              double sum = 0.0, norm = 0.0;
              for (int j = int(std::ceil(cy - r * sy)); j <= int(std::floor(cy + r * sy)); ++j)
                for (int i = int(std::ceil(cx - r * sx)); i <= int(std::floor(cx + r * sx)); ++i) {
                  const double wt = filter_eval(f, (i - cx) / sx) * filter_eval(f, (j - cy) / sy);
                  sum += wt * img.get(wrap_index(i, w, wm), wrap_index(j, h, wm), ch);
                  norm += wt;
                }
              ASSERT_NEAR(l1.get(x, y, ch), sum / norm, 2e-6)
                  << to_string(k) << " " << to_string(wm) << " " << w << "x" << h << " at " << x << "," << y;
            }
      }
  }
}

// A one-texel dot in the top-left corner: with repeat the filter reaches
// across the edge, so level 1's opposite corner sees it; with clamp it does not.
TEST(MipWrap, RepeatReachesAcrossTheEdgeClampDoesNot) {
  Image img(16, 16, 1, PixelType::f32);
  img.set(0, 0, 0, 1.0f);
  const MipChain rep = generate_mips(img.view(), options(FilterKind::gaussian, WrapMode::repeat));
  const MipChain clp = generate_mips(img.view(), options(FilterKind::gaussian, WrapMode::clamp));
  EXPECT_GT(rep.levels[1].get(7, 0, 0), 1e-4f);
  EXPECT_GT(rep.levels[1].get(0, 7, 0), 1e-4f);
  EXPECT_GT(rep.levels[1].get(7, 7, 0), 1e-6f);
  EXPECT_EQ(clp.levels[1].get(7, 0, 0), 0.0f);
  EXPECT_EQ(clp.levels[1].get(0, 7, 0), 0.0f);
  // Repeat is seamless: a tiling image shifted by one level-1 texel (two
  // level-0 texels) gives a shifted level 1, at every level.
  const Image a = random_image(32, 32, 3, PixelType::u8, 5);
  Image b(32, 32, 3, PixelType::u8);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x)
      for (int ch = 0; ch < 3; ++ch) b.set((x + 2) % 32, y, ch, a.get(x, y, ch));
  const MipChain ca = generate_mips(a.view(), options(FilterKind::lanczos3, WrapMode::repeat));
  const MipChain cb = generate_mips(b.view(), options(FilterKind::lanczos3, WrapMode::repeat));
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x)
      for (int ch = 0; ch < 3; ++ch) ASSERT_EQ(cb.levels[1].get((x + 1) % 16, y, ch), ca.levels[1].get(x, y, ch));
}

// Premultiplied filtering: opaque red beside fully transparent black must not
// darken the red at the seam (the classic dark fringe).
TEST(MipAlpha, NoDarkFringes) {
  Image img(8, 8, 4, PixelType::u8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 4; ++x) {
      img.set(x, y, 0, 1.0f);
      img.set(x, y, 3, 1.0f);
    }
  const MipChain c = generate_mips(img.view(), options(FilterKind::gaussian, WrapMode::clamp));
  const Image& l1 = c.levels[1];
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      if (l1.get(x, y, 3) == 0.0f) continue;
      EXPECT_EQ(l1.get(x, y, 0), 1.0f) << x;  // still pure red wherever visible
      EXPECT_EQ(l1.get(x, y, 1), 0.0f);
    }
  MipOptions straight = options(FilterKind::gaussian, WrapMode::clamp);
  straight.premultiplied_alpha = false;
  const MipChain s = generate_mips(img.view(), straight);
  EXPECT_LT(s.levels[1].get(1, 1, 0), 1.0f);  // without premultiplication the seam darkens
}

namespace {
// A cutout: a disc of alpha with a soft, noisy edge, like foliage.
Image cutout(int n) {
  Image img(n, n, 4, PixelType::u8);
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> u(-0.15f, 0.15f);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const float d = std::hypot(x - n / 2.0f, y - n / 2.0f) / (n / 2.0f);
      const float leaf = 0.5f + 0.5f * std::sin(x * 0.9f) * std::sin(y * 0.7f);
      img.set(x, y, 0, 0.2f);
      img.set(x, y, 1, 0.6f);
      img.set(x, y, 3, std::clamp((1.0f - d) * 3.0f * leaf + u(rng), 0.0f, 1.0f));
    }
  return img;
}
}  // namespace

TEST(MipAlpha, CoverageKeptWithinOnePercentagePoint) {
  const Image img = cutout(256);
  MipOptions o;
  o.alpha_coverage_ref = 0.5f;
  const MipChain c = generate_mips(img.view(), o);
  const float target = alpha_coverage(img.view(), 0.5f);
  ASSERT_GT(target, 0.05f);
  MipChain plain = generate_mips(img.view(), MipOptions{});
  bool plain_drifts = false;
  for (std::size_t l = 1; l < c.levels.size(); ++l) {
    const Image& lv = c.levels[l];
    if (lv.width() < 8) break;  // a handful of texels cannot hold a fraction to 1%
    EXPECT_NEAR(alpha_coverage(lv.view(), 0.5f), target, 0.01f) << "level " << l;
    plain_drifts |= std::abs(alpha_coverage(plain.levels[l].view(), 0.5f) - target) > 0.02f;
  }
  EXPECT_TRUE(plain_drifts) << "the test image should lose coverage without the correction";
}

TEST(MipAlpha, CoverageOnCorpusCutout) {
  const std::string path = corpus_dir() + "/alpha/trigger_palm_tree2_1000.png";
  if (!have_corpus()) GTEST_SKIP() << "no corpus at " << corpus_dir();
  const Image img = read_image(path);
  MipOptions o;
  o.alpha_coverage_ref = 0.5f;
  const MipChain c = generate_mips(img.view(), o);
  const float target = alpha_coverage(img.view(), 0.5f);
  for (std::size_t l = 1; l < c.levels.size() && c.levels[l].width() >= 16; ++l) {
    EXPECT_NEAR(alpha_coverage(c.levels[l].view(), 0.5f), target, 0.01f) << "level " << l;
  }
}

TEST(MipNormalMap, LevelsAreUnitLength) {
  // A bumpy normal field from an analytic height, stored as xyz * 0.5 + 0.5.
  Image img(64, 64, 3, PixelType::u8);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const float dx = 1.5f * std::cos(x * 0.4f), dy = 1.5f * std::sin(y * 0.3f);
      const float len = std::sqrt(dx * dx + dy * dy + 1.0f);
      img.set(x, y, 0, -dx / len * 0.5f + 0.5f);
      img.set(x, y, 1, -dy / len * 0.5f + 0.5f);
      img.set(x, y, 2, 1.0f / len * 0.5f + 0.5f);
    }
  MipOptions o;
  o.normal_map = true;
  const MipChain c = generate_mips(img.view(), o);
  MipOptions color;
  color.color_space = "linear";
  const MipChain plain = generate_mips(img.view(), color);
  double plain_min = 1.0;
  for (std::size_t l = 1; l < c.levels.size(); ++l) {
    const Image& lv = c.levels[l];
    for (int y = 0; y < lv.height(); ++y)
      for (int x = 0; x < lv.width(); ++x) {
        auto len = [&](const Image& im) {
          double s = 0;
          for (int i = 0; i < 3; ++i) s += std::pow(im.get(x, y, i) * 255.0 / 127.5 - 1.0, 2);
          return std::sqrt(s);
        };
        // 8-bit quantization moves each component by at most 1/255 of the
        // [-1, 1] range's half-width: the length by at most sqrt(3)/127.5.
        ASSERT_NEAR(len(lv), 1.0, std::sqrt(3.0) / 127.5) << "level " << l;
        plain_min = std::min(plain_min, len(plain.levels[l]));
      }
  }
  EXPECT_LT(plain_min, 0.9) << "plain filtering should shorten the normals";
}

TEST(MipDeterminism, SameBytesForAnyThreadCountAndSimdOrScalar) {
  const Image img = random_image(257, 131, 4, PixelType::u8, 21);
  for (FilterKind k : {FilterKind::box, FilterKind::gaussian, FilterKind::lanczos3}) {
    MipOptions o = options(k, WrapMode::mirror);
    o.alpha_coverage_ref = 0.5f;
    MipChain one, two, scalar;
    {
      ThreadLimit t(1);
      one = generate_mips(img.view(), o);
    }
    {
      ThreadLimit t(2);
      two = generate_mips(img.view(), o);
    }
    {
      ScalarKernels scalar_only;
      scalar = generate_mips(img.view(), o);
    }
    ASSERT_EQ(one.levels.size(), two.levels.size());
    for (std::size_t l = 0; l < one.levels.size(); ++l) {
      EXPECT_TRUE(same_bytes(one.levels[l], two.levels[l])) << to_string(k) << " level " << l;
      EXPECT_TRUE(same_bytes(one.levels[l], scalar.levels[l])) << to_string(k) << " level " << l;
    }
  }
}

TEST(MipErrors, BadOptionsAreRejected) {
  const Image gray = random_image(8, 8, 1, PixelType::u8, 1);
  MipOptions n;
  n.normal_map = true;
  EXPECT_THROW(generate_mips(gray.view(), n), Error);
  MipOptions s;
  s.filter.sigma = 0.0f;
  EXPECT_THROW(generate_mips(gray.view(), s), Error);
  MipOptions a;
  a.alpha_coverage_ref = 1.5f;
  EXPECT_THROW(generate_mips(random_image(8, 8, 4, PixelType::u8, 1).view(), a), Error);
  MipOptions cs;
  cs.color_space = "not-a-space";
  EXPECT_THROW(generate_mips(gray.view(), cs), Error);
}

// Float output from sRGB input is linear: level 0 holds decoded values.
TEST(MipTypes, FloatOutputIsLinear) {
  const Image img = checkerboard(8, 8, 3);
  MipOptions o;
  o.output_type = PixelType::f32;
  o.wrap = WrapMode::repeat;
  const MipChain c = generate_mips(img.view(), o);
  EXPECT_EQ(c.color_space, "linear");
  EXPECT_NEAR(c.levels[1].get(0, 0, 0), 0.5f, 1e-6);
  EXPECT_FLOAT_EQ(c.levels[0].get(1, 0, 0), 1.0f);
}
