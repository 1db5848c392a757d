// resize_image against analytic answers, and apply_size_rule's arithmetic.
#include <gtest/gtest.h>

#include <cmath>

#include "support/images.h"
#include "texproc/error.h"
#include "texproc/mip.h"

using namespace texproc;

namespace {

ResizeOptions with_filter(FilterKind k) {
  ResizeOptions o;
  o.filter = Filter{k};
  return o;
}

SizeRule rule(int w, int h, int max_size, const char* pow2, int multiple_of) {
  SizeRule r;
  r.resize_width = w;
  r.resize_height = h;
  r.max_size = max_size;
  r.pow2 = pow2;
  r.multiple_of = multiple_of;
  return r;
}

}  // namespace

TEST(Resize, SameSizeIsTheImage) {
  for (PixelType type : {PixelType::u8, PixelType::u16, PixelType::f32}) {
    const Image in = test::random_image(17, 9, 3, type, 4);
    const Image out = resize_image(in.view(), 17, 9, [] {
      ResizeOptions o;
      o.color_space = "linear";
      return o;
    }());
    for (int y = 0; y < 9; ++y)
      for (int x = 0; x < 17 * 3; ++x)
        ASSERT_NEAR(out.get(x / 3, y, x % 3), in.get(x / 3, y, x % 3), 1e-6) << to_string(type);
  }
}

TEST(Resize, ConstantStaysConstantAtAnySize) {
  Image in(37, 23, 4, PixelType::u8);
  for (int y = 0; y < in.height(); ++y)
    for (int x = 0; x < in.width(); ++x) {
      in.set(x, y, 0, 0.8f);
      in.set(x, y, 1, 0.3f);
      in.set(x, y, 2, 0.1f);
      in.set(x, y, 3, 0.6f);
    }
  for (auto [w, h] : {std::pair{10, 7}, std::pair{64, 64}, std::pair{1, 1}, std::pair{100, 3}})
    for (FilterKind k : {FilterKind::mitchell, FilterKind::lanczos3, FilterKind::box, FilterKind::gaussian}) {
      const Image out = resize_image(in.view(), w, h, with_filter(k));
      ASSERT_EQ(out.width(), w);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          for (int c = 0; c < 4; ++c)
            ASSERT_EQ(out.row<std::uint8_t>(y)[4 * x + c], in.row<std::uint8_t>(0)[c]) << w << "x" << h;
    }
}

// Halving with the box filter is the mean of each 2x2 block (linear floats).
TEST(Resize, BoxHalvingIsTheBlockMean) {
  const Image in = test::random_image(8, 6, 1, PixelType::f32, 9);
  const Image out = resize_image(in.view(), 4, 3, with_filter(FilterKind::box));
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) {
      const double mean = (in.get(2 * x, 2 * y, 0) + in.get(2 * x + 1, 2 * y, 0) + in.get(2 * x, 2 * y + 1, 0) +
                           in.get(2 * x + 1, 2 * y + 1, 0)) /
                          4;
      EXPECT_NEAR(out.get(x, y, 0), mean, 1e-6);
    }
}

// Doubling a ramp with the tent filter interpolates it: the ramp again,
// away from the clamped edges.
TEST(Resize, TentDoublingKeepsARamp) {
  Image in(16, 1, 1, PixelType::f32);
  for (int x = 0; x < 16; ++x) in.set(x, 0, 0, 0.05f * x);
  const Image out = resize_image(in.view(), 32, 1, with_filter(FilterKind::triangle));
  for (int x = 2; x < 30; ++x) {
    const double source_x = (x + 0.5) / 2 - 0.5;  // where the output texel's centre falls
    EXPECT_NEAR(out.get(x, 0, 0), 0.05 * source_x, 1e-6) << x;
  }
}

// Colour under alpha 0 does not bleed into visible texels.
TEST(Resize, TransparentColourDoesNotBleed) {
  Image in(8, 8, 4, PixelType::u8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const bool left = x < 4;
      in.set(x, y, 0, left ? 1.0f : 0.0f);
      in.set(x, y, 1, left ? 0.0f : 1.0f);
      in.set(x, y, 3, left ? 0.0f : 1.0f);
    }
  const Image out = resize_image(in.view(), 3, 3, with_filter(FilterKind::box));
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x)
      if (out.get(x, y, 3) > 0) {
        EXPECT_EQ(out.row<std::uint8_t>(y)[4 * x], 0) << x << "," << y;
      }
}

TEST(Resize, SizeRules) {
  auto sized = [](SizeRule r, int w, int h) {
    apply_size_rule(r, w, h);
    return std::pair{w, h};
  };
  EXPECT_EQ(sized(rule(1024, 0, 0, "", 0), 2048, 1024), (std::pair{1024, 512}));
  EXPECT_EQ(sized(rule(0, 300, 0, "", 0), 2048, 1024), (std::pair{600, 300}));
  EXPECT_EQ(sized(rule(100, 50, 0, "", 0), 7, 9), (std::pair{100, 50}));
  EXPECT_EQ(sized(rule(0, 0, 1000, "", 0), 3000, 1500), (std::pair{1000, 500}));
  EXPECT_EQ(sized(rule(0, 0, 1000, "", 0), 800, 600), (std::pair{800, 600}));
  EXPECT_EQ(sized(rule(0, 0, 0, "nearest", 0), 600, 800), (std::pair{512, 1024}));
  EXPECT_EQ(sized(rule(0, 0, 0, "nearest", 0), 768, 1), (std::pair{1024, 1}));  // a tie goes up
  EXPECT_EQ(sized(rule(0, 0, 0, "down", 0), 1000, 1025), (std::pair{512, 1024}));
  EXPECT_EQ(sized(rule(0, 0, 0, "up", 0), 1000, 1024), (std::pair{1024, 1024}));
  EXPECT_EQ(sized(rule(0, 0, 0, "", 4), 30, 33), (std::pair{32, 36}));
  EXPECT_EQ(sized(rule(0, 0, 100, "down", 4), 300, 30), (std::pair{64, 8}));
  EXPECT_THROW(sized(rule(0, 0, 0, "sideways", 0), 4, 4), Error);
  EXPECT_THROW(resize_image(Image(4, 4, 1, PixelType::u8).view(), 0, 4), Error);
}
