// Image-based lighting: the GGX-prefiltered specular chain, diffuse
// irradiance and its spherical harmonics (docs/cubemap.md).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "cubemap/convolve.h"
#include "cubemap/cube_internal.h"
#include "texproc/error.h"
#include "texproc/runtime.h"

namespace texproc {
namespace {

// A source in the kernel's layout, padded to a multiple of 16 texels.
struct PaddedSource {
  cube::TexelSet set;
  explicit PaddedSource(const CubeLevel& level) : set(cube::texel_set(level)) {
    const std::size_t n = (set.size() + 15) / 16 * 16;
    for (auto* v : {&set.x, &set.y, &set.z, &set.w, &set.r, &set.g, &set.b}) v->resize(n, 0.0f);
  }
  cube::ConvolveSource view() const {
    return {set.x.data(), set.y.data(), set.z.data(), set.w.data(),
            set.r.data(), set.g.data(), set.b.data(), set.size()};
  }
};

// Every texel of `out` convolved exactly with the lobe over `src`.
void convolve_level(const CubeLevel& src, float ggx_alpha, CubeLevel& out) {
  const PaddedSource ps(src);
  const cube::ConvolveSource s = ps.view();
  const int n = out.size;
  for_each_row_block(6 * n, 1, [&](int r0, int r1) {
    std::vector<float> x(n), y(n), z(n), rgb(3 * std::size_t(n));
    for (int r = r0; r < r1; ++r) {
      const int f = r / n, j = r % n;
      for (int i = 0; i < n; ++i) {
        double d[3];
        cube::texel_direction(f, n, i, j, d);
        x[i] = float(d[0]), y[i] = float(d[1]), z[i] = float(d[2]);
      }
      cube::convolve_lobe(s, x.data(), y.data(), z.data(), n, ggx_alpha, rgb.data());
      float* row = out.faces[f].row<float>(j);
      for (int i = 0; i < n; ++i) {
        row[4 * i + 0] = rgb[3 * i + 0];
        row[4 * i + 1] = rgb[3 * i + 1];
        row[4 * i + 2] = rgb[3 * i + 2];
        row[4 * i + 3] = 1.0f;
      }
    }
  });
}

double radical_inverse(unsigned k) {
  unsigned b = k;
  b = (b << 16) | (b >> 16);
  b = ((b & 0x55555555u) << 1) | ((b & 0xAAAAAAAAu) >> 1);
  b = ((b & 0x33333333u) << 2) | ((b & 0xCCCCCCCCu) >> 2);
  b = ((b & 0x0F0F0F0Fu) << 4) | ((b & 0xF0F0F0F0u) >> 4);
  b = ((b & 0x00FF00FFu) << 8) | ((b & 0xFF00FF00u) >> 8);
  return b * (1.0 / 4294967296.0);
}

// Filtered importance sampling (Colbert and Krivanek, GPU Gems 3, 20.4):
// GGX half vectors from a Hammersley set; each tap reads the level of the
// source chain whose texels cover the solid angle the sample stands for,
// biased half a level finer than their +1 (measured against brute force on
// the corpus in bench_cubemap: +1 blurs, 0 leaves noise at 256 samples).
constexpr double kLodBias = 0.5;
void sample_level(const CubeSampler& chain, float alpha, int samples, CubeLevel& out) {
  struct Tap {
    double l[3];
    float weight, lod;
  };
  std::vector<Tap> taps;
  const double a2 = double(alpha) * alpha;
  const double texel_solid = 4.0 * std::numbers::pi / (6.0 * chain.size() * chain.size());
  for (int k = 0; k < samples; ++k) {
    const double e1 = (k + 0.5) / samples, e2 = radical_inverse(unsigned(k));
    const double cos_h = std::sqrt((1.0 - e2) / (1.0 + (a2 - 1.0) * e2));
    const double sin_h = std::sqrt(std::max(0.0, 1.0 - cos_h * cos_h));
    const double phi = 2.0 * std::numbers::pi * e1;
    const double hx = sin_h * std::cos(phi), hy = sin_h * std::sin(phi), hz = cos_h;
    Tap t;
    t.l[0] = 2.0 * hz * hx;
    t.l[1] = 2.0 * hz * hy;
    t.l[2] = 2.0 * hz * hz - 1.0;
    if (t.l[2] <= 0.0) continue;
    const double q = cos_h * cos_h * (a2 - 1.0) + 1.0;
    const double D = a2 / (std::numbers::pi * q * q);
    const double pdf = D / 4.0;  // of l, with n = v
    const double sample_solid = 1.0 / (samples * pdf);
    t.lod = float(std::max(0.0, 0.5 * std::log2(sample_solid / texel_solid) + kLodBias));
    t.weight = float(t.l[2]);
    taps.push_back(t);
  }
  const int n = out.size;
  for_each_row_block(6 * n, 1, [&](int r0, int r1) {
    for (int r = r0; r < r1; ++r) {
      const int f = r / n, j = r % n;
      float* row = out.faces[f].row<float>(j);
      for (int i = 0; i < n; ++i) {
        double N[3], T[3], B[3];
        cube::texel_direction(f, n, i, j, N);
        const double up[3] = {std::fabs(N[2]) < 0.999 ? 0.0 : 1.0, 0.0, std::fabs(N[2]) < 0.999 ? 1.0 : 0.0};
        T[0] = up[1] * N[2] - up[2] * N[1];
        T[1] = up[2] * N[0] - up[0] * N[2];
        T[2] = up[0] * N[1] - up[1] * N[0];
        const double tl = std::sqrt(T[0] * T[0] + T[1] * T[1] + T[2] * T[2]);
        for (double& c : T) c /= tl;
        B[0] = N[1] * T[2] - N[2] * T[1];
        B[1] = N[2] * T[0] - N[0] * T[2];
        B[2] = N[0] * T[1] - N[1] * T[0];
        float acc[4] = {0, 0, 0, 0}, wsum = 0;
        for (const Tap& t : taps) {
          double L[3];
          for (int c = 0; c < 3; ++c) L[c] = T[c] * t.l[0] + B[c] * t.l[1] + N[c] * t.l[2];
          float s[4];
          chain.sample(L, t.lod, s);
          for (int c = 0; c < 3; ++c) acc[c] += t.weight * s[c];
          wsum += t.weight;
        }
        for (int c = 0; c < 3; ++c) row[4 * i + c] = acc[c] / wsum;
        row[4 * i + 3] = 1.0f;
      }
    }
  });
}

}  // namespace

float specular_roughness(int level, int levels) { return levels > 1 ? float(level) / float(levels - 1) : 0.0f; }

Cubemap prefilter_specular(const Cubemap& source, const SpecularOptions& o) {
  if (source.levels.empty()) throw Error(ErrorCode::bad_arguments, "prefilter_specular: the source has no level 0");
  if (o.samples < 1) throw Error(ErrorCode::bad_arguments, "prefilter_specular: samples must be at least 1");
  const int size = o.size > 0 ? o.size : std::min(source.size(), 256);
  Cubemap resized, scratch;
  if (size != source.size()) resized = resize_cubemap(source, size);
  const Cubemap& chain = cube::full_chain(size != source.size() ? resized : source, scratch);
  const int all = int(chain.levels.size());
  int levels = 1;
  while (levels < all && chain.levels[levels].size >= std::max(1, o.min_size)) ++levels;
  if (o.levels > 0) levels = std::min(o.levels, all);
  const CubeSampler sampler(chain);
  Cubemap out;
  out.levels.push_back(chain.levels[0]);
  for (int m = 1; m < levels; ++m) {
    const int n = std::max(1, size >> m);
    const float r = specular_roughness(m, levels), alpha = std::max(r * r, 1e-4f);
    CubeLevel level = cube::make_level(n);
    // The coarsest source level whose texels are a sixth of the lobe's
    // width (about 2 alpha radians) or finer, 90 degrees / N <= alpha / 3.8,
    // and no coarser than 32 a face: a coarser source left 1-5% error at
    // roughness 0.8-1 against brute force (bench_cubemap).
    int s = 0;
    const int floor_size = std::min(size, 32);
    while (s + 1 < all && chain.levels[s + 1].size >= 6.0 / alpha && chain.levels[s + 1].size >= floor_size) ++s;
    const double cost = 36.0 * double(n) * n * double(chain.levels[s].size) * chain.levels[s].size;
    if (cost <= o.exact_budget) {
      convolve_level(chain.levels[s], alpha, level);
    } else {
      sample_level(sampler, alpha, o.samples, level);
    }
    out.levels.push_back(std::move(level));
  }
  return out;
}

Cubemap irradiance_cubemap(const Cubemap& source, int size) {
  if (source.levels.empty()) throw Error(ErrorCode::bad_arguments, "irradiance_cubemap: the source has no level 0");
  if (size < 1) throw Error(ErrorCode::bad_arguments, "irradiance map face size must be at least 1");
  Cubemap scratch;
  const Cubemap& chain = cube::full_chain(source, scratch);
  std::size_t s = 0;
  while (s + 1 < chain.levels.size() && chain.levels[s].size > 32) ++s;
  Cubemap out;
  out.levels.push_back(cube::make_level(size));
  convolve_level(chain.levels[s], -1.0f, out.levels[0]);
  return out;
}

void sh9_basis(const double n[3], double y[9]) {
  const double x = n[0], yy = n[1], z = n[2];
  y[0] = 0.282095;
  y[1] = 0.488603 * yy;
  y[2] = 0.488603 * z;
  y[3] = 0.488603 * x;
  y[4] = 1.092548 * x * yy;
  y[5] = 1.092548 * yy * z;
  y[6] = 0.315392 * (3.0 * z * z - 1.0);
  y[7] = 1.092548 * x * z;
  y[8] = 0.546274 * (x * x - yy * yy);
}

void SphericalHarmonics9::irradiance(const double n[3], double rgb[3]) const {
  static constexpr double kBand[9] = {1.0, 2.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0, 0.25, 0.25, 0.25, 0.25, 0.25};
  double y[9];
  sh9_basis(n, y);
  for (int c = 0; c < 3; ++c) {
    double e = 0;
    for (int k = 0; k < 9; ++k) e += kBand[k] * radiance[k][c] * y[k];
    rgb[c] = e;  // (A_l / pi) L_lm Y_lm: A0 = pi, A1 = 2 pi / 3, A2 = pi / 4
  }
}

SphericalHarmonics9 project_sh9(const Cubemap& cube) {
  if (cube.levels.empty()) throw Error(ErrorCode::bad_arguments, "project_sh9: the cube map has no level 0");
  const CubeLevel* level = &cube.levels[0];
  Cubemap scratch;
  if (level->size > 128) {
    const Cubemap& chain = cube::full_chain(cube, scratch);
    std::size_t s = 0;
    while (chain.levels[s].size > 128) ++s;
    level = &chain.levels[s];
  }
  const int n = level->size;
  SphericalHarmonics9 sh;
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j) {
      const float* row = level->faces[f].row<float>(j);
      for (int i = 0; i < n; ++i) {
        double d[3], y[9];
        cube::texel_direction(f, n, i, j, d);
        sh9_basis(d, y);
        const double w = cube_texel_solid_angle(n, i, j);
        for (int k = 0; k < 9; ++k)
          for (int c = 0; c < 3; ++c) sh.radiance[k][c] += y[k] * w * row[4 * i + c];
      }
    }
  return sh;
}

}  // namespace texproc
