// PSNR, errors and SSIM against answers worked out by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "support/images.h"
#include "support/threads.h"

#include <tuple>
#include "texproc/error.h"
#include "texproc/metrics.h"
#include "texproc/runtime.h"

using namespace texproc;
using namespace texproc::test;

namespace {
Image constant_f32(int w, int h, int channels, float v) {
  Image img = Image::uninitialized(w, h, channels, PixelType::f32);
  for (int y = 0; y < h; ++y)
    for (int i = 0; i < w * channels; ++i) img.row<float>(y)[i] = v;
  return img;
}
}  // namespace

TEST(Metrics, IdenticalImages) {
  const Image a = random_image(37, 19, 4, PixelType::u8, 7);
  const ImageDifference d = compare_images(a.view(), a.view());
  EXPECT_EQ(d.mse, 0.0);
  EXPECT_TRUE(std::isinf(d.psnr()));
  EXPECT_EQ(d.differing_texels, 0u);
  for (double s : ssim_per_channel(a.view(), a.view())) EXPECT_NEAR(s, 1.0, 1e-12);
}

// A constant offset d: MSE d^2, PSNR -20 log10(d), max error d; SSIM of two
// constants is its luminance term (2 mx my + C1) / (mx^2 + my^2 + C1).
TEST(Metrics, ConstantOffsetHasKnownFigures) {
  const double off = 0.125;
  const Image a = constant_f32(16, 9, 3, 0.5f), b = constant_f32(16, 9, 3, float(0.5 + off));
  const ImageDifference d = compare_images(a.view(), b.view());
  EXPECT_NEAR(d.mse, off * off, 1e-12);
  EXPECT_NEAR(d.psnr(), -20.0 * std::log10(off), 1e-9);
  EXPECT_NEAR(d.psnr_rgb(), d.psnr(), 1e-9);
  EXPECT_NEAR(d.max_abs, off, 1e-12);
  EXPECT_EQ(d.differing_texels, 16u * 9u);
  const double c1 = 1e-4, mx = 0.5, my = 0.5 + off;
  for (double s : ssim_per_channel(a.view(), b.view())) {
    EXPECT_NEAR(s, (2 * mx * my + c1) / (mx * mx + my * my + c1), 1e-9);
  }
}

// One wrong channel of one texel out of N: MSE e^2 / (N * channels) overall.
TEST(Metrics, PerChannelFiguresAndTypes) {
  Image a = random_image(10, 10, 3, PixelType::u8, 3);
  Image b = a;
  b.row<std::uint8_t>(4)[5 * 3 + 1] = std::uint8_t(a.row<std::uint8_t>(4)[5 * 3 + 1] ^ 0x40);
  const double e = 64.0 / 255.0;
  const ImageDifference d = compare_images(a.view(), b.view());
  EXPECT_NEAR(d.channel[1].mse, e * e / 100.0, 1e-12);
  EXPECT_EQ(d.channel[0].mse, 0.0);
  EXPECT_NEAR(d.mse, e * e / 300.0, 1e-12);
  EXPECT_EQ(d.differing_texels, 1u);
  // The same image as 8-bit and as float: no difference.
  Image f = Image::uninitialized(10, 10, 3, PixelType::f32);
  for (int y = 0; y < 10; ++y)
    for (int i = 0; i < 30; ++i) f.row<float>(y)[i] = a.row<std::uint8_t>(y)[i] / 255.0f;
  EXPECT_EQ(compare_images(a.view(), f.view()).differing_texels, 0u);
  EXPECT_THROW(compare_images(a.view(), random_image(10, 11, 3, PixelType::u8, 1).view()), Error);
  EXPECT_THROW(compare_images(a.view(), random_image(10, 10, 4, PixelType::u8, 1).view()), Error);
}

TEST(Metrics, SameFiguresForAnyThreadCount) {
  const Image a = random_image(300, 211, 4, PixelType::u16, 1), b = random_image(300, 211, 4, PixelType::u16, 2);
  auto figures = [&] {
    const ImageDifference d = compare_images(a.view(), b.view());
    return std::make_tuple(d.mse, d.max_abs, ssim_per_channel(a.view(), b.view()));
  };
  EXPECT_EQ(with_threads(1, figures), with_threads(2, figures));
}
