// Normal maps against analytic heightfields with known normals.
#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <cmath>
#include <cstring>
#include <numbers>

#include "normalmap/kernels.h"
#include "support/images.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/normalmap.h"
#include "texproc/runtime.h"

using namespace texproc;
using namespace texproc::test;

namespace {
const GradientKernel kAllKernels[] = {GradientKernel::gather2x2, GradientKernel::central,   GradientKernel::sobel3,
                                      GradientKernel::sobel5,    GradientKernel::prewitt3,  GradientKernel::prewitt5,
                                      GradientKernel::scharr3,   GradientKernel::multiscale};

// A float heightfield from a function of texel coordinates.
template <typename F>
Image height_field(int w, int h, F f) {
  Image img(w, h, 1, PixelType::f32);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img.row<float>(y)[x] = float(f(double(x), double(y)));
  return img;
}

struct Vec3 {
  double x, y, z;
};
Vec3 decode(const Image& n, int x, int y) {
  return {n.get(x, y, 0) * 2.0 - 1.0, n.get(x, y, 1) * 2.0 - 1.0, n.get(x, y, 2) * 2.0 - 1.0};
}
double angle_deg(Vec3 a, Vec3 b) {
  const double la = std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z), lb = std::sqrt(b.x * b.x + b.y * b.y + b.z * b.z);
  const double c = (a.x * b.x + a.y * b.y + a.z * b.z) / (la * lb);
  return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / std::numbers::pi;
}
// The true normal of z = S * h for gradient (gx, gy) of h per texel (gy along
// rows, which grow downwards), OpenGL convention.
Vec3 true_normal(double S, double gx, double gy) {
  const double a = -S * gx, b = S * gy, len = std::sqrt(a * a + b * b + 1.0);
  return {a / len, b / len, 1.0 / len};
}
}  // namespace

// Every kernel's taps are normalized so that a unit ramp has gradient 1.
TEST(NormalKernels, UnitRampGivesGradientOne) {
  for (GradientKernel k : kAllKernels) {
    const SeparableKernel sk = make_kernel(k, {0.5f, 0.3f, 0.2f});
    double moment = 0.0, smooth = 0.0;
    for (std::size_t i = 0; i < sk.deriv.size(); ++i) {
      moment += sk.deriv[i] * (sk.first + int(i));
      smooth += sk.smooth[i];
    }
    EXPECT_NEAR(moment, 1.0, 1e-6) << to_string(k);
    EXPECT_NEAR(smooth, 1.0, 1e-6) << to_string(k);
  }
}

// Planes: every kernel is exact away from the edges, for several slopes,
// both conventions; a 45 degree ramp gives a 45 degree normal.
TEST(NormalMap, PlanesAreExactForEveryKernel) {
  const double S = 8.0;
  for (auto [a, b] : {std::pair{0.0, 0.0}, {1.0 / 8.0, 0.0}, {0.0, -0.05}, {0.03, 0.07}, {-0.2, 0.1}}) {
    const Image img = height_field(40, 30, [&](double x, double y) { return 0.5 + a * (x - 20) + b * (y - 15); });
    for (GradientKernel k : kAllKernels) {
      NormalMapOptions o;
      o.kernel = k;
      o.height_scale = float(S);
      const Image n = normal_map(img.view(), o, PixelType::f32);
      const Vec3 want = true_normal(S, a, b);
      for (int y = 5; y < 25; ++y)
        for (int x = 5; x < 35; ++x) {
          const Vec3 got = decode(n, x, y);
          ASSERT_NEAR(got.x, want.x, 1e-5) << to_string(k);
          ASSERT_NEAR(got.y, want.y, 1e-5) << to_string(k);
          ASSERT_NEAR(got.z, want.z, 1e-5) << to_string(k);
        }
      if (a == 1.0 / 8.0 && b == 0.0) {
        EXPECT_NEAR(angle_deg(decode(n, 20, 15), {0, 0, 1}), 45.0, 1e-3) << to_string(k);
      }
    }
  }
}

// Edges: a ramp along x repeated down the rows is exact on the top and bottom
// rows with repeat (and with clamp and mirror, which see the same rows).
TEST(NormalMap, EdgesAlongTheConstantAxisAreExact) {
  const Image img = height_field(32, 16, [](double x, double) { return 0.1 + 0.02 * x; });
  for (WrapMode w : {WrapMode::clamp, WrapMode::repeat, WrapMode::mirror}) {
    NormalMapOptions o;
    o.wrap = w;
    const Image n = normal_map(img.view(), o, PixelType::f32);
    const Vec3 want = true_normal(8.0, 0.02, 0.0);
    for (int y : {0, 1, 14, 15})
      for (int x = 3; x < 29; ++x) ASSERT_NEAR(decode(n, x, y).x, want.x, 1e-5) << to_string(w);
  }
}

// A cap of a sphere of radius R texels: the surface normal is (p - c) / R.
TEST(NormalMap, SphereCapNormals) {
  const double R = 40.0, S = 1.0;
  const Image img = height_field(64, 64, [&](double x, double y) {
    const double r2 = (x - 31.5) * (x - 31.5) + (y - 31.5) * (y - 31.5);
    return std::sqrt(std::max(0.0, R * R - r2));  // height in texels, scale 1
  });
  for (GradientKernel k : {GradientKernel::central, GradientKernel::sobel3, GradientKernel::scharr3}) {
    NormalMapOptions o;
    o.kernel = k;
    o.height_scale = float(S);
    const Image n = normal_map(img.view(), o, PixelType::f32);
    double worst = 0.0;
    for (int y = 16; y < 48; ++y)
      for (int x = 16; x < 48; ++x) {
        const double z = std::sqrt(R * R - (x - 31.5) * (x - 31.5) - (y - 31.5) * (y - 31.5));
        // OpenGL: n.y points up the image, i.e. against the row direction.
        const Vec3 want{(x - 31.5) / R, -(y - 31.5) / R, z / R};
        worst = std::max(worst, angle_deg(decode(n, x, y), want));
      }
    EXPECT_LT(worst, 0.5) << to_string(k);
  }
}

// An 8-bit quantized sinusoid at 30 degrees, as real heightmaps are stored:
// the smoothing kernels suppress quantization noise and are more isotropic,
// so their mean angular error is lower; the 2x2 gather, centred half a texel
// off, is worst. Error is measured against the analytic normal.
TEST(NormalMap, SinusoidRanksTheKernels) {
  const double P = 24.0, th = std::numbers::pi / 6, A = 0.04;
  const double kx = 2 * std::numbers::pi / P * std::cos(th), ky = 2 * std::numbers::pi / P * std::sin(th);
  Image img(128, 128, 1, PixelType::u8);
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x) img.set(x, y, 0, float(0.5 + A * std::sin(kx * x + ky * y)));
  auto error = [&](GradientKernel k) {
    NormalMapOptions o;
    o.kernel = k;
    o.height_scale = 16.0f;
    const Image n = normal_map(img.view(), o, PixelType::f32);
    double sum = 0.0;
    int count = 0;
    for (int y = 8; y < 120; ++y)
      for (int x = 8; x < 120; ++x) {
        const double c = A * std::cos(kx * x + ky * y);
        sum += angle_deg(decode(n, x, y), true_normal(16.0, c * kx, c * ky));
        ++count;
      }
    return sum / count;
  };
  const double gather = error(GradientKernel::gather2x2), central = error(GradientKernel::central);
  const double sobel = error(GradientKernel::sobel3), scharr = error(GradientKernel::scharr3);
  EXPECT_LT(sobel, central);
  EXPECT_LT(scharr, central);
  EXPECT_LT(central, gather);
  RecordProperty("mean_error_deg_gather_central_sobel_scharr", std::to_string(gather) + " " + std::to_string(central) +
                                                                   " " + std::to_string(sobel) + " " +
                                                                   std::to_string(scharr));
}

// Tiling: with repeat, a periodic heightfield shifted by k columns gives the
// same normal map shifted by k columns, bytes and all: the edges continue.
TEST(NormalMap, RepeatIsSeamless) {
  const Image a = random_image(48, 20, 1, PixelType::u8, 3);
  Image b(48, 20, 1, PixelType::u8);
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 48; ++x) b.row<std::uint8_t>((y + 7) % 20)[(x + 5) % 48] = a.row<std::uint8_t>(y)[x];
  for (GradientKernel k : kAllKernels) {
    NormalMapOptions o;
    o.kernel = k;
    o.wrap = WrapMode::repeat;
    const Image na = normal_map(a.view(), o, PixelType::u8), nb = normal_map(b.view(), o, PixelType::u8);
    for (int y = 0; y < 20; ++y)
      for (int x = 0; x < 48; ++x)
        ASSERT_EQ(
            0, std::memcmp(na.row<std::uint8_t>(y) + 3 * x, nb.row<std::uint8_t>((y + 7) % 20) + 3 * ((x + 5) % 48), 3))
            << to_string(k) << " at " << x << "," << y;
  }
}

TEST(NormalMap, YDownFlipsOnlyGreen) {
  const Image img = random_image(33, 17, 1, PixelType::u16, 9);
  NormalMapOptions up, down;
  down.y_up = false;
  const Image a = normal_map(img.view(), up, PixelType::u8), b = normal_map(img.view(), down, PixelType::u8);
  for (int y = 0; y < 17; ++y)
    for (int x = 0; x < 33; ++x) {
      EXPECT_EQ(a.get(x, y, 0), b.get(x, y, 0));
      EXPECT_EQ(a.get(x, y, 2), b.get(x, y, 2));
      // Green encodes -y: the decoded values are negatives within one step.
      EXPECT_NEAR(a.get(x, y, 1) * 2 - 1, -(b.get(x, y, 1) * 2 - 1), 2.0 / 255.0 + 1e-6);
    }
}

// xy output with z rebuilt as the shader does equals the xyz output within
// 8-bit quantization; xyzh carries the height in alpha.
TEST(NormalMap, TwoChannelAndHeightOutputs) {
  const Image img = random_image(20, 20, 1, PixelType::u8, 5);
  NormalMapOptions o;
  const Image xyz = normal_map(img.view(), o, PixelType::u8);
  o.channels = NormalChannels::xy;
  const Image xy = normal_map(img.view(), o, PixelType::u8);
  o.channels = NormalChannels::xyzh;
  o.invert = true;
  const Image xyzh = normal_map(img.view(), o, PixelType::u8);
  ASSERT_EQ(xy.channels(), 2);
  ASSERT_EQ(xyzh.channels(), 4);
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 20; ++x) {
      EXPECT_EQ(xy.get(x, y, 0), xyz.get(x, y, 0));
      EXPECT_EQ(xy.get(x, y, 1), xyz.get(x, y, 1));
      const double nx = xy.get(x, y, 0) * 2 - 1, ny = xy.get(x, y, 1) * 2 - 1;
      const double z = std::sqrt(std::max(0.0, 1 - nx * nx - ny * ny));
      EXPECT_NEAR(z, xyz.get(x, y, 2) * 2 - 1, 0.02);  // 8-bit x and y move z by at most ~0.016 here
      EXPECT_EQ(xyzh.row<std::uint8_t>(y)[4 * x + 3], 255 - img.row<std::uint8_t>(y)[x]);
    }
}

// The consuming form gives the heights of the copying form, whatever the
// bands and pages: rows are read before their memory is given back.
TEST(NormalMap, ExtractHeightConsumingMatchesCopy) {
  for (const auto& [channels, type] : {std::pair{4, PixelType::u8}, std::pair{1, PixelType::u16},
                                       std::pair{3, PixelType::f32}, std::pair{2, PixelType::u8}}) {
    Image img = Image::uninitialized(1013, 347, channels, type);
    std::uint32_t state = 12345;
    for (std::size_t i = 0; i < img.byte_size(); ++i) {
      state = state * 1664525u + 1013904223u;
      img.data()[i] = std::uint8_t(state >> 24);
    }
    if (type == PixelType::f32)
      for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width() * channels; ++x) img.row<float>(y)[x] = float((x * 7 + y * 13) % 101) / 100;
    const std::vector<float> copied = extract_height(img.view(), HeightChannel::automatic, true);
    const std::vector<float> consumed = extract_height(std::move(img), HeightChannel::automatic, true);
    EXPECT_TRUE(img.empty());
    ASSERT_EQ(copied.size(), consumed.size());
    EXPECT_EQ(0, std::memcmp(copied.data(), consumed.data(), copied.size() * sizeof(float))) << channels;
  }
}

TEST(NormalMap, HeightChannelsAndErrors) {
  Image rgba(4, 4, 4, PixelType::u8);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      rgba.set(x, y, 0, 0.1f * x);
      rgba.set(x, y, 3, 0.2f * y);
    }
  EXPECT_NEAR(extract_height(rgba.view(), HeightChannel::r, false)[2], 0.2f, 1.0 / 255);
  EXPECT_NEAR(extract_height(rgba.view(), HeightChannel::a, false)[4], 0.2f, 1.0 / 255);
  EXPECT_NEAR(extract_height(rgba.view(), HeightChannel::automatic, false)[1], 0.2126f * 0.1f, 1.0 / 255);
  Image gray(4, 4, 1, PixelType::u8);
  EXPECT_THROW(extract_height(gray.view(), HeightChannel::a, false), Error);
  EXPECT_THROW(extract_height(gray.view(), HeightChannel::g, false), Error);
  NormalMapOptions bad;
  bad.height_scale = 0.0f;
  EXPECT_THROW(normal_map(gray.view(), bad, PixelType::u8), Error);
  bad = NormalMapOptions{};
  bad.kernel = GradientKernel::multiscale;
  bad.multiscale_weights = {};
  EXPECT_THROW(normal_map(gray.view(), bad, PixelType::u8), Error);
  EXPECT_THROW(parse_gradient_kernel("laplace"), Error);
}

TEST(NormalMap, SameBytesForThreadsAndSimdTargets) {
  const Image img = random_image(301, 77, 1, PixelType::u16, 11);
  for (GradientKernel k : kAllKernels) {
    NormalMapOptions o;
    o.kernel = k;
    o.wrap = WrapMode::mirror;
    o.channels = NormalChannels::xyzh;
    Image one, two, scalar;
    {
      ThreadLimit t(1);
      one = normal_map(img.view(), o, PixelType::u16);
    }
    {
      ThreadLimit t(2);
      two = normal_map(img.view(), o, PixelType::u16);
    }
    {
      ScalarKernels scalar_only;
      scalar = normal_map(img.view(), o, PixelType::u16);
    }
    EXPECT_EQ(0, std::memcmp(one.data(), two.data(), one.byte_size())) << to_string(k);
    EXPECT_EQ(0, std::memcmp(one.data(), scalar.data(), one.byte_size())) << to_string(k);
    for (int64_t target : hwy::SupportedAndGeneratedTargets()) {
      hwy::SetSupportedTargetsForTest(target);
      const Image t = normal_map(img.view(), o, PixelType::u16);
      EXPECT_EQ(0, std::memcmp(one.data(), t.data(), one.byte_size()))
          << to_string(k) << " " << hwy::TargetName(target);
    }
    hwy::SetSupportedTargetsForTest(0);
  }
}

// The corpus pair: Stellarium's normal map was derived from its height map
// with DirectX's green (notes: corr x 0.95, y -0.96 against OpenGL). texproc
// with --y down must agree in sign and correlate strongly on both axes.
TEST(NormalMap, CorpusPairAgreesWithShippedNormalMap) {
  if (!have_corpus()) GTEST_SKIP() << "no corpus";
  const Image height = read_image(corpus_dir() + "/height/stellarium_stein_mauerwerk_height_256.png");
  const Image shipped = read_image(corpus_dir() + "/normal_ts/stellarium_stein_mauerwerk_bump_256.png");
  NormalMapOptions o;
  o.y_up = false;
  o.height_channel = HeightChannel::r;
  const Image ours = normal_map(height.view(), o, PixelType::u8);
  for (int c = 0; c < 2; ++c) {
    double sa = 0, sb = 0, sab = 0, saa = 0, sbb = 0;
    const int n = 256 * 256;
    for (int y = 0; y < 256; ++y)
      for (int x = 0; x < 256; ++x) {
        const double a = ours.get(x, y, c), b = shipped.get(x, y, c);
        sa += a;
        sb += b;
        sab += a * b;
        saa += a * a;
        sbb += b * b;
      }
    const double corr = (sab - sa * sb / n) / std::sqrt((saa - sa * sa / n) * (sbb - sb * sb / n));
    EXPECT_GT(corr, 0.8) << "channel " << c;
  }
}
