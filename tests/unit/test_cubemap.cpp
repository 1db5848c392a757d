// Cube maps: known answers (directions, constants, bright spots, analytic
// spherical harmonics), seams measured, IBL against brute force, SIMD
// against scalar, thread counts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <random>

#include "cubemap/convolve.h"
#include "cubemap/pano_map.h"
#include "support/images.h"
#include "support/targets.h"
#include "support/threads.h"
#include "texproc/cubemap.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/mip.h"

namespace texproc {
namespace {

using test::corpus_dir;
using test::have_corpus;

constexpr double kPi = std::numbers::pi;

// A panorama whose colour is a function of its own direction.
template <typename F>
Image panorama_of(int w, F f) {
  Image p(w, w / 2, 4, PixelType::f32);
  for (int y = 0; y < w / 2; ++y)
    for (int x = 0; x < w; ++x) {
      double d[3];
      equirect_direction(x + 0.5, y + 0.5, w, w / 2, d);
      float rgb[3];
      f(d, rgb);
      float* t = p.row<float>(y) + 4 * x;
      t[0] = rgb[0];
      t[1] = rgb[1];
      t[2] = rgb[2];
      t[3] = 1.0f;
    }
  return p;
}

void unit_dir(int face, int n, int i, int j, double d[3]) {
  cube_direction(face, 2.0 * (i + 0.5) / n - 1.0, 2.0 * (j + 0.5) / n - 1.0, d);
  const double l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  for (int k = 0; k < 3; ++k) d[k] /= l;
}

std::vector<std::uint8_t> bytes_of(const Cubemap& c) {
  std::vector<std::uint8_t> b;
  for (const CubeLevel& l : c.levels)
    for (const Image& f : l.faces) b.insert(b.end(), f.data(), f.data() + f.byte_size());
  return b;
}

Cubemap smooth_cube(int n) {
  const Image p = panorama_of(4 * n, [](const double* d, float* rgb) {
    rgb[0] = float(0.5 + 0.3 * d[0] + 0.1 * d[1] * d[2]);
    rgb[1] = float(0.4 + 0.2 * d[1] * d[1]);
    rgb[2] = float(0.6 - 0.25 * d[2] + 0.1 * d[0] * d[1]);
  });
  return cubemap_from_equirect(p.view(), n);
}

Cubemap corpus_cube(int n) {
  const Image hdr = read_image(corpus_dir() + "/hdr/blender_world_forest.exr");
  const Image rgba = to_linear_rgba(hdr.view(), ColorSpace::linear());
  return cubemap_from_equirect(rgba.view(), n);
}

TEST(CubeGeometry, FacesFollowTheVulkanTable) {
  const double centres[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int f = 0; f < 6; ++f) {
    double d[3];
    cube_direction(f, 0, 0, d);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(d[k], centres[f][k]) << f;
  }
  // +Z: u runs along +x, v down along -y (the table of the Vulkan spec).
  double d[3];
  cube_direction(4, 1, 1, d);
  EXPECT_EQ(d[0], 1);
  EXPECT_EQ(d[1], -1);
  // +Y: v runs towards +z.
  cube_direction(2, 0, 1, d);
  EXPECT_EQ(d[2], 1);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uv(-0.999, 0.999);
  for (int f = 0; f < 6; ++f)
    for (int k = 0; k < 100; ++k) {
      const double u = uv(rng), v = uv(rng);
      cube_direction(f, u, v, d);
      double u2, v2;
      ASSERT_EQ(cube_face_uv(d, u2, v2), f);
      EXPECT_NEAR(u2, u, 1e-12);
      EXPECT_NEAR(v2, v, 1e-12);
    }
}

TEST(CubeGeometry, SolidAnglesSumToTheSphere) {
  for (int n : {1, 2, 7, 32}) {
    double s = 0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) s += cube_texel_solid_angle(n, i, j);
    EXPECT_NEAR(6 * s, 4 * kPi, 1e-12) << n;
  }
  // A corner texel of a large face is smaller than a centre one by (1 + u^2 + v^2)^1.5 = 3^1.5.
  const double u = 1.0 / 512 - 1.0;
  EXPECT_NEAR(cube_texel_solid_angle(512, 256, 256) / cube_texel_solid_angle(512, 0, 0), std::pow(1.0 + 2 * u * u, 1.5),
              1e-3);
}

TEST(CubeGeometry, PanoramaMappingRoundTrips) {
  double d[3];
  equirect_direction(512, 256, 1024, 512, d);  // the centre looks along -Z
  EXPECT_NEAR(d[2], -1, 1e-12);
  equirect_direction(768, 256, 1024, 512, d);  // three quarters across: +X
  EXPECT_NEAR(d[0], 1, 1e-12);
  equirect_direction(100, 0, 1024, 512, d);  // the top row: +Y
  EXPECT_NEAR(d[1], 1, 1e-12);
  for (double x : {0.5, 100.25, 900.0})
    for (double y : {3.5, 256.0, 500.0}) {
      equirect_direction(x, y, 1024, 512, d);
      double x2, y2;
      direction_to_equirect(d, 1024, 512, x2, y2);
      EXPECT_NEAR(x2, x, 1e-9);
      EXPECT_NEAR(y2, y, 1e-9);
    }
}

TEST(CubeLayouts, DetectedFromTheAspectRatio) {
  EXPECT_EQ(detect_cube_layout(1024, 512), CubeLayout::equirect);
  EXPECT_EQ(detect_cube_layout(1024, 768), CubeLayout::cross_horizontal);
  EXPECT_EQ(detect_cube_layout(768, 1024), CubeLayout::cross_vertical);
  EXPECT_EQ(detect_cube_layout(1536, 256), CubeLayout::strip_horizontal);
  EXPECT_EQ(detect_cube_layout(256, 1536), CubeLayout::strip_vertical);
  try {
    detect_cube_layout(1000, 600);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::bad_arguments);
    EXPECT_NE(std::string(e.what()).find("1000x600"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("2:1"), std::string::npos) << e.what();
  }
  EXPECT_EQ(parse_cube_layout("cross"), CubeLayout::cross_horizontal);
  EXPECT_THROW(parse_cube_layout("diagonal"), Error);
}

TEST(CubeLayouts, EveryLayoutRoundTripsTheFacesExactly) {
  const Cubemap c = smooth_cube(8);
  for (CubeLayout l : {CubeLayout::cross_horizontal, CubeLayout::cross_vertical, CubeLayout::strip_horizontal,
                       CubeLayout::strip_vertical}) {
    const Image img = cubemap_to_layout(c, l);
    EXPECT_EQ(detect_cube_layout(img.width(), img.height()), l);
    EXPECT_EQ(bytes_of(cubemap_from_layout(img.view(), l)), bytes_of(c)) << to_string(l);
  }
  // The vertical cross's -Z sits below -Y turned 180 degrees: its top-left
  // texel is the face's bottom-right one.
  const Image v = cubemap_to_layout(c, CubeLayout::cross_vertical);
  EXPECT_EQ(std::memcmp(v.row<float>(24) + 4 * 8, c.levels[0].faces[5].row<float>(7) + 4 * 7, 16), 0);
}

TEST(CubeFaces, MismatchedFacesAreNamed) {
  Image a(8, 8, 4, PixelType::f32), b(4, 4, 4, PixelType::f32);
  std::array<ConstImageView, 6> faces = {a.view(), a.view(), a.view(), b.view(), a.view(), a.view()};
  try {
    cubemap_from_faces(faces);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("-Y is 4x4"), std::string::npos) << e.what();
  }
  Image wide(8, 4, 4, PixelType::f32);
  faces = {wide.view(), wide.view(), wide.view(), wide.view(), wide.view(), wide.view()};
  EXPECT_THROW(cubemap_from_faces(faces), Error);
}

TEST(CubeFromPanorama, EveryTexelSeesItsOwnDirection) {
  const Image p = panorama_of(256, [](const double* d, float* rgb) {
    for (int k = 0; k < 3; ++k) rgb[k] = float(d[k]);
  });
  const int n = 16;
  const Cubemap c = cubemap_from_equirect(p.view(), n);
  double worst = 0;
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        double d[3];
        unit_dir(f, n, i, j, d);
        const float* t = c.levels[0].faces[f].row<float>(j) + 4 * i;
        for (int k = 0; k < 3; ++k) worst = std::max(worst, std::fabs(t[k] - d[k]));
      }
  // Averaging a unit vector over a texel's footprint shortens it by at most
  // the footprint's angular variance (here about 1e-3).
  EXPECT_LT(worst, 0.01);
}

TEST(CubeFromPanorama, FlipMirrorsTheWorldAxis) {
  const Image p = panorama_of(128, [](const double* d, float* rgb) {
    for (int k = 0; k < 3; ++k) rgb[k] = float(d[k]);
  });
  const int n = 8;
  const Cubemap c = cubemap_from_equirect(p.view(), n, CubeFlip::z);
  for (int f = 0; f < 6; ++f) {
    double d[3];
    unit_dir(f, n, 3, 4, d);
    const float* t = c.levels[0].faces[f].row<float>(4) + 12;
    EXPECT_NEAR(t[0], d[0], 0.02);
    EXPECT_NEAR(t[2], -d[2], 0.02);
  }
  // Mirroring a cube map twice gives it back; mirroring z once equals
  // sampling the panorama mirrored.
  const Cubemap plain = cubemap_from_equirect(p.view(), n);
  EXPECT_EQ(bytes_of(flip_cubemap(flip_cubemap(plain, CubeFlip::x), CubeFlip::x)), bytes_of(plain));
  const Cubemap mirrored = flip_cubemap(plain, CubeFlip::z);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k)
          EXPECT_NEAR(mirrored.levels[0].faces[f].row<float>(j)[4 * i + k],
                      c.levels[0].faces[f].row<float>(j)[4 * i + k], 1e-5);
}

TEST(CubeFromPanorama, ABrightDirectionLandsOnItsTexel) {
  // One bright panorama texel in the direction of texel (20, 9) of +X.
  const int w = 512, h = 256, n = 32;
  Image p(w, h, 4, PixelType::f32);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) p.row<float>(y)[4 * x + 3] = 1.0f;
  double target[3], px, py;
  unit_dir(0, n, 20, 9, target);
  direction_to_equirect(target, w, h, px, py);
  const int bx = int(px), by = int(py);
  for (int c = 0; c < 3; ++c) p.row<float>(by)[4 * bx + c] = 1000.0f;
  const Cubemap cube = cubemap_from_equirect(p.view(), n);
  double d[3];
  equirect_direction(bx + 0.5, by + 0.5, w, h, d);
  double u, v;
  const int face = cube_face_uv(d, u, v);
  EXPECT_EQ(face, 0);
  const int ei = int((u + 1) * 0.5 * n), ej = int((v + 1) * 0.5 * n);
  EXPECT_EQ(ei, 20);
  EXPECT_EQ(ej, 9);
  int best_f = -1, best_i = -1, best_j = -1;
  float best = -1;
  double total = 0;
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const float t = cube.levels[0].faces[f].row<float>(j)[4 * i];
        total += t * cube_texel_solid_angle(n, i, j);
        if (t > best) {
          best = t;
          best_f = f;
          best_i = i;
          best_j = j;
        }
      }
  EXPECT_EQ(best_f, face);
  EXPECT_EQ(best_i, ei);
  EXPECT_EQ(best_j, ej);
  // The spot's energy (value x solid angle) is kept within 10%.
  const double energy = 1000.0 * (2 * kPi / w) * (kPi / h) * std::sqrt(target[0] * target[0] + target[2] * target[2]);
  EXPECT_NEAR(total, energy, 0.1 * energy);
}

TEST(CubeFromPanorama, ALargePanoramaDoesNotAlias) {
  // Stripes one panorama texel wide average to their mean on small faces.
  Image p(1024, 512, 4, PixelType::f32);
  for (int y = 0; y < 512; ++y)
    for (int x = 0; x < 1024; ++x) {
      float* t = p.row<float>(y) + 4 * x;
      t[0] = t[1] = t[2] = float(((x + y) & 1) ? 1.0 : 0.0);
      t[3] = 1.0f;
    }
  const Cubemap c = cubemap_from_equirect(p.view(), 16);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < 16; ++j)
      for (int i = 0; i < 16; ++i) EXPECT_NEAR(c.levels[0].faces[f].row<float>(j)[4 * i], 0.5, 0.05) << f;
}

TEST(CubeMips, AConstantStaysConstantAtEveryLevelAndThroughIbl) {
  const Image p = panorama_of(128, [](const double*, float* rgb) { rgb[0] = 0.25f, rgb[1] = 2.0f, rgb[2] = 7.0f; });
  Cubemap c = cubemap_from_equirect(p.view(), 32);
  generate_cube_mips(c);
  ASSERT_EQ(c.levels.size(), 6u);
  SpecularOptions so;
  so.min_size = 1;
  const Cubemap spec = prefilter_specular(c, so);
  so.exact_budget = 0;  // every level importance-sampled
  const Cubemap sampled = prefilter_specular(c, so);
  const Cubemap irr = irradiance_cubemap(c, 8);
  for (const Cubemap* m : std::initializer_list<const Cubemap*>{&c, &spec, &sampled, &irr})
    for (const CubeLevel& l : m->levels)
      for (const Image& f : l.faces)
        for (int y = 0; y < l.size; ++y)
          for (int x = 0; x < l.size; ++x) {
            const float* t = f.row<float>(y) + 4 * x;
            EXPECT_NEAR(t[0], 0.25f, 1e-5f);
            EXPECT_NEAR(t[1], 2.0f, 1e-5f);
            EXPECT_NEAR(t[2], 7.0f, 2e-5f);
          }
}

TEST(CubeMips, ASmoothSkyShowsNoStepAcrossTheEdges) {
  // Colour = direction: the step across an edge is no larger than the step
  // beside it or anywhere inside, at every level with neighbours inside.
  const Image p = panorama_of(512, [](const double* d, float* rgb) {
    for (int k = 0; k < 3; ++k) rgb[k] = float(d[k]);
  });
  Cubemap c = cubemap_from_equirect(p.view(), 64);
  generate_cube_mips(c);
  for (std::size_t k = 0; k < c.levels.size() && c.levels[k].size >= 4; ++k) {
    const SeamStats s = measure_seams(c.levels[k]);
    EXPECT_LE(s.edge_step, s.near_edge_step) << "level " << k;
    EXPECT_LE(s.edge_step, s.interior_step) << "level " << k;
  }
}

TEST(CubeMips, NoLevelShowsASeamOnARealPanorama) {
  if (!have_corpus()) GTEST_SKIP() << "no corpus at " << corpus_dir();
  // On real content the step across the edges depends on what lies there
  // (a horizon along an edge); the level sampled straight from the panorama
  // has no seam by construction, and the chain must not step more than it.
  const Image hdr = read_image(corpus_dir() + "/hdr/blender_world_forest.exr");
  const Image rgba = to_linear_rgba(hdr.view(), ColorSpace::linear());
  Cubemap c = cubemap_from_equirect(rgba.view(), 128);
  generate_cube_mips(c);
  for (std::size_t k = 1; k < c.levels.size() && c.levels[k].size >= 2; ++k) {
    const SeamStats s = measure_seams(c.levels[k]);
    const SeamStats direct = measure_seams(cubemap_from_equirect(rgba.view(), c.levels[k].size).levels[0]);
    EXPECT_LE(s.edge_step, 1.05 * direct.edge_step) << "level " << k << " (" << c.levels[k].size << ")";
  }
  // Per-face filtering (texproc mip's Gaussian on each face, clamped at the
  // edges) steps more than that at most levels.
  std::array<MipChain, 6> per_face;
  MipOptions mo;
  mo.color_space = "linear";
  for (int f = 0; f < 6; ++f) per_face[f] = generate_mips(c.levels[0].faces[f].view(), mo);
  int seams = 0, levels = 0;
  for (std::size_t k = 1; k < c.levels.size() && c.levels[k].size >= 2; ++k, ++levels) {
    CubeLevel l;
    l.size = c.levels[k].size;
    for (int f = 0; f < 6; ++f) l.faces[f] = per_face[f].levels[k];
    if (measure_seams(l).edge_step > 1.05 * measure_seams(c.levels[k]).edge_step) ++seams;
  }
  EXPECT_GT(2 * seams, levels);
}

TEST(CubeSampling, CubeToPanoramaToCubeKeepsASmoothImage) {
  Cubemap c = smooth_cube(32);
  const Image pano = cubemap_to_equirect(c, 256);
  ASSERT_EQ(pano.height(), 128);
  const Cubemap back = cubemap_from_equirect(pano.view(), 32);
  double worst = 0;
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < 32; ++j)
      for (int i = 0; i < 32; ++i)
        for (int k = 0; k < 3; ++k)
          worst = std::max(worst, double(std::fabs(back.levels[0].faces[f].row<float>(j)[4 * i + k] -
                                                   c.levels[0].faces[f].row<float>(j)[4 * i + k])));
  EXPECT_LT(worst, 0.004);  // docs/cubemap.md states this bound
  // Resizing keeps it too.
  const Cubemap small = resize_cubemap(c, 16), large = resize_cubemap(small, 32);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(large.levels[0].faces[2].row<float>(5)[4 * 7 + k], c.levels[0].faces[2].row<float>(5)[4 * 7 + k], 0.01);
}

TEST(CubeSh, ConstantAndCosineLobeAreExact) {
  const Image constant = panorama_of(256, [](const double*, float* rgb) { rgb[0] = rgb[1] = rgb[2] = 1.5f; });
  const SphericalHarmonics9 a = project_sh9(cubemap_from_equirect(constant.view(), 32));
  EXPECT_NEAR(a.radiance[0][0], 1.5 * 0.282095 * 4 * kPi, 1e-4);
  for (int k = 1; k < 9; ++k) EXPECT_NEAR(a.radiance[k][1], 0.0, 1e-5) << k;
  // L = max(z, 0): L00 = 0.282095 pi, L10 = 0.488603 (2 pi / 3), L20 = 0.315392 pi / 4 ... (pi / 2) * 0.25 * 2.
  const Image lobe =
      panorama_of(1024, [](const double* d, float* rgb) { rgb[0] = rgb[1] = rgb[2] = float(std::max(d[2], 0.0)); });
  const SphericalHarmonics9 b = project_sh9(cubemap_from_equirect(lobe.view(), 128));
  EXPECT_NEAR(b.radiance[0][0], 0.282095 * kPi, 2e-3 * 0.886);
  EXPECT_NEAR(b.radiance[2][0], 0.488603 * 2 * kPi / 3, 2e-3 * 1.023);
  EXPECT_NEAR(b.radiance[6][0], 0.315392 * kPi / 2, 2e-3 * 0.495);
  for (int k : {1, 3, 4, 5, 7, 8}) EXPECT_NEAR(b.radiance[k][0], 0.0, 1e-3) << k;
  // The irradiance of a constant: the constant (over pi, times pi).
  double n[3] = {0.3, -0.8, 0.52}, e[3];
  a.irradiance(n, e);
  EXPECT_NEAR(e[0], 1.5, 1e-4);
}

TEST(CubeSh, IrradianceMapMatchesTheHarmonicsOfABandLimitedSky) {
  // A sky of bands 0-2 only: its SH irradiance is exact, so the direct
  // cosine convolution must agree with it.
  const Image p = panorama_of(512, [](const double* d, float* rgb) {
    rgb[0] = float(1.0 + 0.5 * d[2] + 0.3 * d[0] * d[1]);
    rgb[1] = float(0.8 + 0.4 * d[1]);
    rgb[2] = float(0.6 + 0.2 * (3 * d[2] * d[2] - 1));
  });
  const Cubemap c = cubemap_from_equirect(p.view(), 64);
  const SphericalHarmonics9 sh = project_sh9(c);
  const Cubemap irr = irradiance_cubemap(c, 16);
  double worst = 0;
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < 16; ++j)
      for (int i = 0; i < 16; ++i) {
        double d[3], e[3];
        unit_dir(f, 16, i, j, d);
        sh.irradiance(d, e);
        for (int k = 0; k < 3; ++k)
          worst = std::max(worst, std::fabs(irr.levels[0].faces[f].row<float>(j)[4 * i + k] - e[k]) / e[k]);
      }
  EXPECT_LT(worst, 0.01);
}

// GGX D(h) (n.l), every texel of the source, in double.
Cubemap brute_ggx(const CubeLevel& src, int n, double alpha) {
  Cubemap out;
  out.levels.resize(1);
  out.levels[0].size = n;
  for (Image& f : out.levels[0].faces) f = Image(n, n, 4, PixelType::f32);
  const double a2 = alpha * alpha;
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        double N[3], acc[3] = {0, 0, 0}, ws = 0;
        unit_dir(f, n, i, j, N);
        for (int sf = 0; sf < 6; ++sf)
          for (int sj = 0; sj < src.size; ++sj)
            for (int si = 0; si < src.size; ++si) {
              double L[3];
              unit_dir(sf, src.size, si, sj, L);
              const double c = N[0] * L[0] + N[1] * L[1] + N[2] * L[2];
              if (c <= 0) continue;
              double H[3] = {N[0] + L[0], N[1] + L[1], N[2] + L[2]};
              const double hl = std::sqrt(H[0] * H[0] + H[1] * H[1] + H[2] * H[2]);
              const double nh = (N[0] * H[0] + N[1] * H[1] + N[2] * H[2]) / hl;
              const double q = nh * nh * (a2 - 1) + 1;
              const double w = a2 / (kPi * q * q) * c * cube_texel_solid_angle(src.size, si, sj);
              const float* t = src.faces[sf].row<float>(sj) + 4 * si;
              for (int k = 0; k < 3; ++k) acc[k] += w * t[k];
              ws += w;
            }
        for (int k = 0; k < 3; ++k) out.levels[0].faces[f].row<float>(j)[4 * i + k] = float(acc[k] / ws);
      }
  return out;
}

double relative_rms(const CubeLevel& a, const CubeLevel& b) {
  double e = 0, s = 0;
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < a.size; ++y)
      for (int x = 0; x < a.size * 4; ++x) {
        if (x % 4 == 3) continue;
        const double d = a.faces[f].row<float>(y)[x] - b.faces[f].row<float>(y)[x];
        e += d * d;
        s += double(b.faces[f].row<float>(y)[x]) * b.faces[f].row<float>(y)[x];
      }
  return std::sqrt(e / s);
}

TEST(CubeIbl, SpecularMatchesBruteForceConvolution) {
  if (!have_corpus()) GTEST_SKIP() << "no corpus at " << corpus_dir();
  const Cubemap src = corpus_cube(32);
  EXPECT_EQ(prefilter_specular(src).levels.size(), 3u);  // 32, 16, 8: roughness 1 on 8x8 faces
  SpecularOptions all;
  all.min_size = 1;
  const Cubemap spec = prefilter_specular(src, all);
  ASSERT_EQ(spec.levels.size(), 6u);
  EXPECT_EQ(bytes_of(Cubemap{{spec.levels[0]}}), bytes_of(src));  // level 0: the mirror
  SpecularOptions so = all;
  so.exact_budget = 0;
  so.samples = 512;
  const Cubemap sampled = prefilter_specular(src, so);
  for (int m = 1; m < 6; ++m) {
    const double alpha = std::pow(specular_roughness(m, 6), 2.0);
    const Cubemap ref = brute_ggx(src.levels[0], spec.levels[m].size, alpha);
    EXPECT_LT(relative_rms(spec.levels[m], ref.levels[0]), 0.01) << "level " << m;
    EXPECT_LT(relative_rms(sampled.levels[m], ref.levels[0]), 0.05) << "level " << m << " sampled";
  }
}

TEST(CubeIbl, ConvolutionSimdEqualsScalarOnEveryTarget) {
  if (!have_corpus()) GTEST_SKIP() << "no corpus at " << corpus_dir();
  const Cubemap src = corpus_cube(16);
  for (float alpha : {-1.0f, 0.05f, 0.5f}) {
    test::expect_same_on_every_target(
        [&] {
          if (alpha < 0) return bytes_of(irradiance_cubemap(src, 8));
          SpecularOptions so;
          so.levels = 3;
          return bytes_of(prefilter_specular(src, so));
        },
        "cube convolution alpha " + std::to_string(alpha));
  }
}

TEST(CubeFromPanorama, Atan2PolynomialIsWithinTwoTenthsOfAMicroradian) {
  double worst = 0;
  for (int a = 0; a < 100000; ++a) {
    const double t = 2 * kPi * a / 100000.0;
    for (double r : {1e-3, 1.0, 7.5}) {
      const float y = float(r * std::sin(t)), x = float(r * std::cos(t));
      worst = std::max(worst, std::fabs(cube::atan2_poly(y, x) - std::atan2(double(y), double(x))));
    }
  }
  EXPECT_LT(worst, 4e-7);  // float rounding of the result included (pi is 3.1e-7 apart in float)
  EXPECT_EQ(cube::atan2_poly(0.0f, 0.0f), 0.0f);
}

TEST(CubeFromPanorama, SimdEqualsScalarOnEveryTarget) {
  if (!have_corpus()) GTEST_SKIP() << "no corpus at " << corpus_dir();
  const Image hdr = read_image(corpus_dir() + "/hdr/blender_world_courtyard.exr");
  const Image rgba = to_linear_rgba(hdr.view(), ColorSpace::linear());
  for (CubeFlip flip : {CubeFlip::none, CubeFlip::z}) {
    test::expect_same_on_every_target([&] { return bytes_of(cubemap_from_equirect(rgba.view(), 37, flip)); },
                                      "cubemap_from_equirect");
  }
}

TEST(CubeMaps, BytesDoNotDependOnTheThreadCount) {
  if (!have_corpus()) GTEST_SKIP() << "no corpus at " << corpus_dir();
  const Image hdr = read_image(corpus_dir() + "/hdr/blender_world_city.exr");
  const Image rgba = to_linear_rgba(hdr.view(), ColorSpace::linear());
  auto run = [&] {
    Cubemap c = cubemap_from_equirect(rgba.view(), 64);
    generate_cube_mips(c);
    auto b = bytes_of(c);
    SpecularOptions so;
    so.size = 32;
    auto s = bytes_of(prefilter_specular(c, so));
    b.insert(b.end(), s.begin(), s.end());
    return b;
  };
  EXPECT_EQ(test::with_threads(1, run), test::with_threads(2, run));
}

TEST(CubeColor, LinearRgbaRoundTripsSrgbBytes) {
  Image img(5, 3, 3, PixelType::u8);
  for (std::size_t k = 0; k < img.byte_size(); ++k) img.data()[k] = std::uint8_t(k * 17);
  const Image lin = to_linear_rgba(img.view(), ColorSpace::srgb());
  const Image back = from_linear_rgba(lin.view(), ColorSpace::srgb(), 3, PixelType::u8);
  ASSERT_EQ(back.byte_size(), img.byte_size());
  EXPECT_EQ(std::memcmp(back.data(), img.data(), img.byte_size()), 0);
}

TEST(CubePreview, ShowsTheCrossesAndTheSpheres) {
  Cubemap c = smooth_cube(16);
  generate_cube_mips(c);
  const Image p = render_cube_preview(c, nullptr);
  EXPECT_EQ(p.width(), 8 * 16 + 16);
  EXPECT_EQ(p.height(), 5 * 16);
  EXPECT_EQ(p.type(), PixelType::u8);
  // The centre of the first sphere (the mirror) sees +Z straight back.
  const std::uint8_t* s = p.row<std::uint8_t>(3 * 16 + 16) + 4 * 16;
  EXPECT_GT(s[0], 0);
  EXPECT_EQ(s[3], 255);
}

}  // namespace
}  // namespace texproc
