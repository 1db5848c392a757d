// Cone maps: the fast generator against the brute-force definition, and
// cone stepping against a dense linear search.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

#include "support/images.h"
#include "support/targets.h"
#include "support/threads.h"
#include "texproc/conemap.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/normalmap.h"
#include "texproc/runtime.h"

using namespace texproc;
using namespace texproc::test;

namespace {
std::vector<float> field(int w, int h, const char* kind, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<float> f(std::size_t(w) * h, 0.0f);
  const std::string k = kind;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float& v = f[std::size_t(y) * w + x];
      if (k == "random") v = u(rng);
      if (k == "steps") v = float((x / 8 + y / 5) % 4) / 3.0f;
      if (k == "spikes") v = u(rng) < 0.02f ? 1.0f : 0.1f * u(rng);
      if (k == "peak") v = std::max(0.0f, 1.0f - std::hypot(x - w / 2.0f, y - h / 3.0f) / 10.0f);
      if (k == "flat") v = 0.5f;
      if (k == "quantized") v = std::round(u(rng) * 255.0f) / 255.0f;  // ties in height
      if (k == "ramp") v = float(x) / float(w);                        // every uphill texel of a row ties
      if (k == "planes") {  // tilted sawtooth planes: the slope bound's case, across the wrap
        const float t = 0.37f * float(x) / float(w) + 1.3f * float(y) / float(h);
        v = t - std::floor(t);
      }
    }
  return f;
}
// How many texels apart two texture coordinates are along an axis of n
// texels, on the torus: hits within one texel count as the same hit (a hit
// on a wall between two texels may land on either side).
int texel_gap(float a_uv, float b_uv, int n) {
  const int ia = wrap_index(int(std::floor(a_uv * n)), n, WrapMode::repeat);
  const int ib = wrap_index(int(std::floor(b_uv * n)), n, WrapMode::repeat);
  const int d = std::abs(ia - ib);
  return std::min(d, n - d);
}
}  // namespace

// The branch and bound visits far fewer texels but must find the same
// minimum: equal floats, for every kind of field, both wraps, odd and
// non-square sizes, other depths and caps; conservative and relaxed (which
// is never narrower).
TEST(ConeMap, FastEqualsBruteForceExactly) {
  for (auto [w, h] : {std::pair{32, 32}, {64, 64}, {24, 40}, {1, 7}}) {
    for (const char* kind : {"random", "steps", "spikes", "peak", "flat", "quantized", "ramp", "planes"}) {
      for (WrapMode wrap : {WrapMode::repeat, WrapMode::clamp}) {
        for (auto [depth, cap] : {std::pair{1.0f, 1.0f}, {0.2f, 4.0f}}) {
          ConeMapOptions o;
          o.wrap = wrap;
          o.depth = depth;
          o.max_ratio = cap;
          const std::vector<float> f = field(w, h, kind, unsigned(w + h));
          const std::vector<float> fast = cone_ratios(f, w, h, o), slow = cone_ratios_brute_force(f, w, h, o);
          ASSERT_EQ(fast, slow) << kind << " " << w << "x" << h << " " << to_string(wrap) << " depth " << depth;
          // Relaxed cones: the same equality, and never narrower than these.
          o.mode = ConeMode::relaxed;
          const std::vector<float> rfast = cone_ratios(f, w, h, o), rslow = cone_ratios_brute_force(f, w, h, o);
          ASSERT_EQ(rfast, rslow) << "relaxed " << kind << " " << w << "x" << h << " " << to_string(wrap);
          for (std::size_t i = 0; i < f.size(); ++i) ASSERT_GE(rfast[i], fast[i]) << kind << " texel " << i;
          // Bilinear-safe cones: the same equality with their own definition.
          o.mode = ConeMode::conservative;
          o.bilinear_safe = true;
          const std::vector<float> bfast = cone_ratios(f, w, h, o), bslow = cone_ratios_brute_force(f, w, h, o);
          ASSERT_EQ(bfast, bslow) << "bilinear-safe " << kind << " " << w << "x" << h << " " << to_string(wrap);
        }
      }
    }
  }
}

// ConeMapOptions::progress: one call at a time, rising to exactly 1, for the
// pyramid search and brute force alike, on two threads; the cones are the
// same as without it.
TEST(ConeMap, ProgressRisesToOne) {
  ThreadLimit two(2);
  const std::vector<float> f = field(64, 48, "random", 5u);
  for (bool brute : {false, true}) {
    ConeMapOptions o;
    std::vector<double> seen;
    o.progress = [&](double done) { seen.push_back(done); };
    const std::vector<float> with = brute ? cone_ratios_brute_force(f, 64, 48, o) : cone_ratios(f, 64, 48, o);
    o.progress = nullptr;
    EXPECT_EQ(with, brute ? cone_ratios_brute_force(f, 64, 48, o) : cone_ratios(f, 64, 48, o));
    ASSERT_FALSE(seen.empty());
    EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
    EXPECT_EQ(seen.back(), 1.0);
    EXPECT_EQ(seen.size(), brute ? 48u : 6u);  // texel rows; rows of 8x8 cells
  }
}

// The slope bound across the wrap: a ramp half the texture away is seen by
// some texels of a cell on one side and by the others on the other, where
// it climbs towards them. The search must not prune it for those.
TEST(ConeMap, SlopeBoundHoldsAcrossTheWrap) {
  const int W = 64, H = 8;
  std::vector<float> f(std::size_t(W) * H, 0.0f);
  for (int y = 0; y < H; ++y)
    for (int x = 32; x < 40; ++x) f[std::size_t(y) * W + x] = float(x - 32) / 7.0f;
  ConeMapOptions o;
  o.max_ratio = 0.45f;
  EXPECT_EQ(cone_ratios(f, W, H, o), cone_ratios_brute_force(f, W, H, o));
}

// --fast: every cone at most the exact one (texel for texel, against the
// brute force), for every reach, field kind and wrap; the same bytes for any
// thread count.
TEST(ConeMap, FastModeNeverWiderThanExact) {
  for (auto [w, h] : {std::pair{64, 64}, {24, 40}}) {
    for (const char* kind : {"random", "steps", "spikes", "peak", "flat", "quantized"}) {
      for (WrapMode wrap : {WrapMode::repeat, WrapMode::clamp}) {
        ConeMapOptions o;
        o.wrap = wrap;
        const std::vector<float> f = field(w, h, kind, unsigned(3 * w + h));
        for (int variant = 0; variant < 3; ++variant) {  // classic, bilinear-safe, relaxed
          const bool bilinear = variant == 1;
          o.bilinear_safe = bilinear;
          o.mode = variant == 2 ? ConeMode::relaxed : ConeMode::conservative;
          o.fast_reach = 0;
          const std::vector<float> exact = cone_ratios_brute_force(f, w, h, o);
          for (int reach : {1, 2, 4}) {
            o.fast_reach = reach;
            const std::vector<float> fast = cone_ratios(f, w, h, o);
            for (std::size_t i = 0; i < f.size(); ++i) {
              ASSERT_LE(fast[i], exact[i]) << kind << " reach " << reach << " variant " << variant << " texel " << i;
              ASSERT_GE(fast[i], 0.0f);
            }
          }
        }
      }
    }
  }
  ConeMapOptions o;
  o.fast_reach = 2;
  const std::vector<float> f = field(97, 61, "spikes", 4);
  std::vector<float> one, two;
  {
    ThreadLimit t(1);
    one = cone_ratios(f, 97, 61, o);
  }
  {
    ThreadLimit t(2);
    two = cone_ratios(f, 97, 61, o);
  }
  EXPECT_EQ(one, two);
}

// The SIMD twin of the cell scans gives the scalar reference's floats on
// every target, for exact, --fast and bilinear-safe cones.
TEST(ConeMap, SimdEqualsScalarOnEveryTarget) {
  for (auto [w, h] : {std::pair{64, 64}, {37, 21}}) {
    for (const char* kind : {"random", "spikes", "quantized"}) {
      for (WrapMode wrap : {WrapMode::repeat, WrapMode::clamp}) {
        for (int variant = 0; variant < 5; ++variant) {  // exact, fast, bilinear-safe, relaxed, relaxed fast
          ConeMapOptions o;
          o.wrap = wrap;
          o.fast_reach = variant == 1 || variant == 4 ? 1 : 0;
          o.bilinear_safe = variant == 2;
          o.mode = variant >= 3 ? ConeMode::relaxed : ConeMode::conservative;
          const std::vector<float> f = field(w, h, kind, unsigned(w * h));
          expect_same_on_every_target([&] { return cone_ratios(f, w, h, o); },
                                      std::string(kind) + " variant " + std::to_string(variant));
        }
      }
    }
  }
}

namespace {
// A per-texel field sampled bilinearly at (x, y) in texel units (centres on
// integers), as a GPU sampler does with the wrap mode's addressing.
double bilinear(const std::vector<float>& f, int W, int H, WrapMode wrap, double x, double y) {
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const double tx = x - x0, ty = y - y0;
  auto at = [&](int i, int j) { return double(f[std::size_t(wrap_index(j, H, wrap)) * W + wrap_index(i, W, wrap)]); };
  return (1 - ty) * ((1 - tx) * at(x0, y0) + tx * at(x0 + 1, y0)) +
         ty * ((1 - tx) * at(x0, y0 + 1) + tx * at(x0 + 1, y0 + 1));
}

// Points of the bilinear surface (a quarter-texel grid) strictly inside the
// cone whose apex and ratio are sampled bilinearly at 400 random points.
int bilinear_violations(const std::vector<float>& f, const std::vector<float>& ratios, int W, int H,
                        const ConeMapOptions& o) {
  std::mt19937 rng(7);
  const double span_x = o.wrap == WrapMode::repeat ? W : W - 1, span_y = o.wrap == WrapMode::repeat ? H : H - 1;
  std::uniform_real_distribution<double> ux(0.0, span_x), uy(0.0, span_y);
  int bad = 0;
  for (int s = 0; s < 400; ++s) {
    const double ax = ux(rng), ay = uy(rng);
    const double ha = bilinear(f, W, H, o.wrap, ax, ay), r = bilinear(ratios, W, H, o.wrap, ax, ay);
    for (int j = 0; j <= 4 * int(span_y); ++j)
      for (int i = 0; i <= 4 * int(span_x); ++i) {
        const double x = i / 4.0, y = j / 4.0;
        const double hy = bilinear(f, W, H, o.wrap, x, y);
        if (hy <= ha) continue;
        double dx = std::abs(x - ax), dy = std::abs(y - ay);
        if (o.wrap == WrapMode::repeat) {
          dx = std::min(dx, W - dx);
          dy = std::min(dy, H - dy);
        }
        const double dist = std::hypot(dx / W, dy / H);
        if (dist < o.depth * r * (hy - ha) * (1 - 1e-5)) ++bad;
      }
  }
  return bad;
}
}  // namespace

// --bilinear-safe: no point of the bilinear surface enters a cone whose apex
// and ratio are interpolated bilinearly, where the classic (texel-centre)
// cones are entered; and the safe cones are never wider than the classic.
TEST(ConeMap, BilinearSafeConesHoldBetweenTexels) {
  int classic_bad = 0;
  for (const char* kind : {"random", "steps", "spikes", "peak"}) {
    for (WrapMode wrap : {WrapMode::repeat, WrapMode::clamp}) {
      for (auto [depth, cap] : {std::pair{1.0f, 1.0f}, {0.1f, 4.0f}}) {
        ConeMapOptions o;
        o.wrap = wrap;
        o.depth = depth;
        o.max_ratio = cap;
        const int W = 24, H = 20;
        const std::vector<float> f = field(W, H, kind, 11);
        const std::vector<float> classic = cone_ratios(f, W, H, o);
        o.bilinear_safe = true;
        const std::vector<float> safe = cone_ratios(f, W, H, o);
        EXPECT_EQ(bilinear_violations(f, safe, W, H, o), 0) << kind << " " << to_string(wrap) << " depth " << depth;
        classic_bad += bilinear_violations(f, classic, W, H, o);
        for (std::size_t i = 0; i < f.size(); ++i) ASSERT_LE(safe[i], classic[i] * (1 + 1e-6f)) << kind << " " << i;
      }
    }
  }
  EXPECT_GT(classic_bad, 0) << "the classic cones should be entered between texels somewhere";
}

// --fast keeps most of the cone on a smooth relief (the mean fast / exact
// ratio over texels; the benchmark reports it on corpus and hard cases).
TEST(ConeMap, FastModeKeepsMostOfTheCone) {
  const int n = 128;
  std::vector<float> f(std::size_t(n) * n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const double a = 2 * M_PI * x / n, b = 2 * M_PI * y / n;
      f[std::size_t(y) * n + x] = float(0.5 + 0.25 * std::sin(3 * a) * std::cos(2 * b) + 0.2 * std::sin(a + 5 * b));
    }
  ConeMapOptions o;
  const std::vector<float> exact = cone_ratios(f, n, n, o);
  double previous = 0;
  for (int reach : {1, 2, 4}) {
    o.fast_reach = reach;
    const std::vector<float> fast = cone_ratios(f, n, n, o);
    double sum = 0;
    for (std::size_t i = 0; i < f.size(); ++i) sum += exact[i] > 0 ? fast[i] / exact[i] : 1.0;
    const double mean = sum / double(f.size());
    std::printf("reach %d: mean fast / exact %.4f\n", reach, mean);
    EXPECT_GE(mean, reach == 1 ? 0.6 : 0.75) << "reach " << reach;
    EXPECT_GE(mean, previous) << "a longer reach must not give narrower cones";
    if (reach == 1) {
      EXPECT_LT(mean, 1.0) << "reach 1 should be approximate here";
    }
    previous = mean;
  }
}

// What the cone means: no texel centre higher than p lies strictly inside
// p's cone, and the cone touches one unless it is capped.
TEST(ConeMap, ConesAreConservativeAndTight) {
  const int W = 40, H = 40;
  const std::vector<float> f = field(W, H, "random", 9);
  ConeMapOptions o;
  const std::vector<float> r = cone_ratios(f, W, H, o);
  for (int p = 0; p < W * H; p += 7) {
    const int px = p % W, py = p / W;
    double tightest = 1e30;
    for (int q = 0; q < W * H; ++q) {
      const float dh = f[q] - f[p];
      if (dh <= 0) continue;
      int dx = std::abs(q % W - px), dy = std::abs(q / W - py);
      dx = std::min(dx, W - dx);
      dy = std::min(dy, H - dy);
      const double ratio = std::hypot(dx / double(W), dy / double(H)) / (o.depth * dh);
      ASSERT_GE(ratio, double(r[p]) * (1 - 1e-6)) << "texel " << q << " is inside the cone of " << p;
      tightest = std::min(tightest, ratio);
    }
    EXPECT_NEAR(r[p], std::min(tightest, double(o.max_ratio)), 1e-6);
  }
}

// Quantization rounds down: the stored cone is never wider than the exact one.
TEST(ConeMap, QuantizedConesRoundDown) {
  const int W = 48, H = 32;
  const std::vector<float> f = field(W, H, "random", 3);
  ConeMapOptions o;
  o.max_ratio = 2.0f;
  const std::vector<float> r = cone_ratios(f, W, H, o);
  for (PixelType t : {PixelType::u8, PixelType::u16}) {
    const Image img = cone_map_image(f, r, W, H, o, t);
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        const double g = img.get(x, y, 1);
        const double stored = g * g * o.max_ratio;
        EXPECT_LE(stored, r[std::size_t(y) * W + x] * (1 + 1e-6));
        const double step = t == PixelType::u8 ? 1.0 / 255 : 1.0 / 65535;
        EXPECT_GT(std::sqrt(std::min(1.0, r[std::size_t(y) * W + x] / 2.0)), g - 1e-9);
        EXPECT_LT(std::sqrt(std::min(1.0, r[std::size_t(y) * W + x] / 2.0)), g + step + 1e-9);
      }
  }
}

TEST(ConeMap, SameForAnyThreadCount) {
  const std::vector<float> f = field(97, 61, "spikes", 4);
  std::vector<float> one, two;
  {
    ThreadLimit t(1);
    one = cone_ratios(f, 97, 61, ConeMapOptions{});
  }
  {
    ThreadLimit t(2);
    two = cone_ratios(f, 97, 61, ConeMapOptions{});
  }
  EXPECT_EQ(one, two);
}

// Safety: thousands of random rays on real heightmaps; cone stepping with
// the map never passes through the surface: its hit is the exact first hit,
// within one texel. (A dense linear search is not a safe reference: it can
// clip past a texel corner; the grid traversal cannot.)
TEST(ConeMap, ConeSteppingFindsTheFirstHitOnCorpusHeightmaps) {
  if (!have_corpus()) GTEST_SKIP() << "no corpus";
  for (const char* file : {"height/povray_mount1_250.png", "height/stellarium_stein_mauerwerk_height_256.png"}) {
    const Image img = read_image(corpus_dir() + "/" + file);
    const int W = img.width(), H = img.height();
    const std::vector<float> h = extract_height(img.view(), HeightChannel::r, false);
    for (float depth : {0.05f, 0.3f}) {
      ConeMapOptions o;
      o.depth = depth;
      const std::vector<float> r = cone_ratios(h, W, H, o);
      ConeMapOptions fast_o = o;
      fast_o.fast_reach = 1;
      const std::vector<float> fast = cone_ratios(h, W, H, fast_o);
      int fast_steps = 0;
      std::mt19937 rng(17);
      std::uniform_real_distribution<float> u(0.0f, 1.0f);
      int rays = 0, cone_steps = 0, linear_steps = 0;
      for (int i = 0; i < 1500; ++i) {
        const float angle = u(rng) * 6.2831853f, tilt = 0.2f + 1.2f * u(rng);  // up to ~80 degrees
        const float du = depth * std::tan(tilt) * std::cos(angle), dv = depth * std::tan(tilt) * std::sin(angle);
        const float u0 = u(rng), v0 = u(rng);
        // The exact first hit (a grid traversal of every texel the ray
        // crosses) against cone stepping refined by 16 binary steps.
        const ReliefHit a = trace_exact(h, W, H, o, u0, v0, du, dv);
        const ReliefHit b = trace_cones(h, r, W, H, o, u0, v0, du, dv, 16);
        ASSERT_EQ(a.hit, b.hit);
        if (!a.hit) continue;
        // Within one texel: the hit texels are the same or neighbours (on the
        // torus); a hit on a wall between two texels may land on either side.
        ASSERT_LE(texel_gap(a.u, b.u, W), 1) << file << " ray " << i;
        ASSERT_LE(texel_gap(a.v, b.v, H), 1) << file << " ray " << i;
        // The --fast map is as safe (its cones are never wider).
        const ReliefHit c = trace_cones(h, fast, W, H, o, u0, v0, du, dv, 16);
        ASSERT_TRUE(c.hit);
        ASSERT_LE(texel_gap(a.u, c.u, W), 1) << file << " ray " << i << " (fast)";
        ASSERT_LE(texel_gap(a.v, c.v, H), 1) << file << " ray " << i << " (fast)";
        fast_steps += c.steps;
        ++rays;
        cone_steps += b.steps;
        linear_steps += a.steps;
      }
      EXPECT_GT(rays, 1000);
      EXPECT_GE(fast_steps, cone_steps) << "narrower cones should take more steps in total";
      (void)linear_steps;  // the grid traversal visits every crossed texel: no cost reference
    }
  }
}

// Relaxed cones open up around a dome.
TEST(ConeMap, RelaxedConesOpenAroundADome) {
  // A dome (convex: its near side rises steeply from the ground): cones
  // around it are no longer limited by the near side, only by where a ray
  // could come out again. On the nearest-texel surface a ray also comes out
  // through the side steps of a slope, so the gain is modest: 7% on average
  // here (on a straight-sided cone both are limited by the slope alike).
  ConeMapOptions o;
  o.wrap = WrapMode::clamp;
  std::vector<float> f(64 * 64);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const float d2 = float((x - 32) * (x - 32) + (y - 30) * (y - 30)) / (20.0f * 20.0f);
      f[std::size_t(y) * 64 + x] = d2 < 1.0f ? 0.5f * std::sqrt(1.0f - d2) : 0.0f;
    }
  const std::vector<float> c = cone_ratios(f, 64, 64, o);
  o.mode = ConeMode::relaxed;
  const std::vector<float> r = cone_ratios(f, 64, 64, o);
  double sc = 0, sr = 0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    sc += c[i];
    sr += r[i];
  }
  EXPECT_GT(sr, 1.05 * sc);
}

// Relaxed cone stepping then binary search finds the exact first hit (within
// one texel) on corpus heightmaps, with fewer lookups than conservative
// stepping.
TEST(ConeMap, RelaxedSteppingFindsTheFirstHitOnCorpusHeightmaps) {
  if (!have_corpus()) GTEST_SKIP() << "no corpus";
  for (const char* file : {"height/povray_mount1_250.png", "height/stellarium_stein_mauerwerk_height_256.png"}) {
    const Image img = read_image(corpus_dir() + "/" + file);
    const int W = img.width(), H = img.height();
    const std::vector<float> h = extract_height(img.view(), HeightChannel::r, false);
    for (float depth : {0.05f, 0.3f}) {
      ConeMapOptions o;
      o.depth = depth;
      const std::vector<float> conservative = cone_ratios(h, W, H, o);
      o.mode = ConeMode::relaxed;
      const std::vector<float> relaxed = cone_ratios(h, W, H, o);
      std::mt19937 rng(23);
      std::uniform_real_distribution<float> u(0.0f, 1.0f);
      int rays = 0, relaxed_steps = 0, cone_steps = 0;
      for (int i = 0; i < 1500; ++i) {
        const float angle = u(rng) * 6.2831853f, tilt = 0.2f + 1.2f * u(rng);
        const float du = depth * std::tan(tilt) * std::cos(angle), dv = depth * std::tan(tilt) * std::sin(angle);
        const float u0 = u(rng), v0 = u(rng);
        const ReliefHit a = trace_exact(h, W, H, o, u0, v0, du, dv);
        const ReliefHit b = trace_relaxed(h, relaxed, W, H, o, u0, v0, du, dv, 16);
        ASSERT_EQ(a.hit, b.hit) << file << " ray " << i;
        if (!a.hit) continue;
        ASSERT_LE(texel_gap(a.u, b.u, W), 1) << file << " depth " << depth << " ray " << i;
        ASSERT_LE(texel_gap(a.v, b.v, H), 1) << file << " depth " << depth << " ray " << i;
        relaxed_steps += b.steps;
        cone_steps += trace_cones(h, conservative, W, H, o, u0, v0, du, dv, 16).steps;
        ++rays;
      }
      EXPECT_GT(rays, 1000);
      // For the record (the binary search's 16 lookups are counted too).
      RecordProperty(std::string(file) + " depth " + std::to_string(depth) + " lookups relaxed/conservative",
                     std::to_string(relaxed_steps) + "/" + std::to_string(cone_steps));
    }
  }
}

TEST(ConeMap, OptionsAreChecked) {
  const std::vector<float> f(16, 0.5f);
  ConeMapOptions o;
  o.depth = 0;
  EXPECT_THROW(cone_ratios(f, 4, 4, o), Error);
  o = ConeMapOptions{};
  o.wrap = WrapMode::mirror;
  EXPECT_THROW(cone_ratios(f, 4, 4, o), Error);
  EXPECT_THROW(cone_ratios(f, 5, 4, ConeMapOptions{}), Error);
}

// The banded search gives each row exactly as the whole map does, for every
// kind of cone, bands on and off the 8-row cells, and its map rows are
// cone_map_image's rows.
TEST(ConeMap, BandsEqualTheWholeMap) {
  const int w = 45, h = 37;
  const std::vector<float> f = field(w, h, "random", 11);
  for (int kind = 0; kind < 4; ++kind) {
    ConeMapOptions o;
    o.depth = 0.3f;
    o.fast_reach = kind == 1 ? 2 : 0;
    o.mode = kind == 2 ? ConeMode::relaxed : ConeMode::conservative;
    o.bilinear_safe = kind == 3;
    SCOPED_TRACE(kind);
    const std::vector<float> whole = cone_ratios(f, w, h, o);
    const ConeRatioSearch search(f, w, h, o);
    for (const auto& [y0, y1] : {std::pair{0, h}, std::pair{0, 8}, std::pair{3, 21}, std::pair{16, 24},
                                 std::pair{30, 37}, std::pair{36, 37}}) {
      std::vector<float> band(std::size_t(y1 - y0) * w);
      search.rows(y0, y1, band.data());
      EXPECT_TRUE(std::equal(band.begin(), band.end(), whole.begin() + std::ptrdiff_t(y0) * w)) << y0 << ".." << y1;
    }
    const Image map = cone_map_image(f, whole, w, h, o, PixelType::u16, 4);
    Image banded = Image::uninitialized(w, h, 4, PixelType::u16);
    double sum = 0;
    search.map_rows(PixelType::u16, 4, 0, 20, banded.data(), banded.row_stride(), &sum);
    search.map_rows(PixelType::u16, 4, 20, h, banded.row<std::uint8_t>(20), banded.row_stride(), &sum);
    EXPECT_EQ(0, std::memcmp(map.data(), banded.data(), map.byte_size()));
    double expected = 0;
    for (float v : whole) expected += v;
    EXPECT_EQ(expected, sum);
  }
  ConeMapOptions o;
  std::vector<double> seen;
  o.progress = [&](double done) { seen.push_back(done); };
  const ConeRatioSearch search(f, w, h, o);
  Image map = Image::uninitialized(w, h, 2, PixelType::u8);
  search.map_rows(PixelType::u8, 2, 0, h, map.data(), map.row_stride());
  ASSERT_FALSE(seen.empty());
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_EQ(seen.back(), 1.0);
  float one[45];
  EXPECT_THROW(search.rows(36, 38, one), Error);
}
