// Cone-map benchmark: exact conservative cones for corpus and hard-case
// heightmaps at several sizes, on 1 and 2 threads, against the brute-force
// definition where it finishes in reasonable time, in the same run.
#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <random>

#include "texproc/conemap.h"
#include "texproc/image_io.h"
#include "texproc/normalmap.h"
#include "texproc/runtime.h"

using namespace texproc;

namespace {

std::vector<float> resample_terrain(int n) {
  static const Image src = read_image(std::string(TEXPROC_CORPUS_DIR) + "/height/trigger_swiss_h_1024.png");
  static const std::vector<float> h = extract_height(src.view(), HeightChannel::automatic, false);
  std::vector<float> out(std::size_t(n) * n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) out[std::size_t(y) * n + x] = h[std::size_t(y * 1024 / n) * 1024 + x * 1024 / n];
  return out;
}

std::vector<float> hard_case(const std::string& kind, int n) {
  std::vector<float> f(std::size_t(n) * n);
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  if (kind == "hemisphere") {
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const float r2 = (std::pow(x - n / 2.0f, 2.0f) + std::pow(y - n / 2.0f, 2.0f)) / std::pow(n * 0.45f, 2.0f);
        f[std::size_t(y) * n + x] = r2 < 1 ? std::sqrt(1 - r2) : 0.0f;
      }
  } else if (kind == "spikes") {
    for (auto& v : f) v = u(rng) < 0.001f ? 1.0f : 0.0f;
  } else if (kind == "white") {  // white noise: neighbours unrelated
    for (auto& v : f) v = u(rng);
  } else if (kind == "ramp") {  // two planes (a sawtooth): every uphill texel of a row gives the same ratio, 0.5
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) f[std::size_t(y) * n + x] = float(2 * x % n) / float(n);
  } else {  // fractal: octaves of value noise
    std::vector<float> acc(f.size(), 0.0f);
    float amp = 0.5f;
    for (int cell = n / 4; cell >= 1; cell /= 2, amp *= 0.55f) {
      const int g = n / cell + 2;
      std::vector<float> grid(std::size_t(g) * g);
      for (auto& v : grid) v = u(rng);
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const float fx = float(x) / cell, fy = float(y) / cell;
          const int ix = int(fx), iy = int(fy);
          const float tx = fx - ix, ty = fy - iy;
          const float a = grid[iy * g + ix], b = grid[iy * g + ix + 1], c = grid[(iy + 1) * g + ix],
                      d = grid[(iy + 1) * g + ix + 1];
          acc[std::size_t(y) * n + x] += amp * ((a * (1 - tx) + b * tx) * (1 - ty) + (c * (1 - tx) + d * tx) * ty);
        }
    }
    const float mx = *std::max_element(acc.begin(), acc.end());
    for (std::size_t i = 0; i < f.size(); ++i) f[i] = acc[i] / mx;
  }
  return f;
}

const std::vector<float>& field(const std::string& kind, int n) {
  static std::map<std::pair<std::string, int>, std::vector<float>> cache;
  auto key = std::make_pair(kind, n);
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  return cache[key] = kind == "terrain" ? resample_terrain(n) : hard_case(kind, n);
}

void cones(benchmark::State& state, const std::string& kind, int n, int threads, bool brute) {
  const std::vector<float>& f = field(kind, n);
  ThreadLimit limit(threads);
  for (auto _ : state) {
    auto r = brute ? cone_ratios_brute_force(f, n, n, ConeMapOptions{}) : cone_ratios(f, n, n, ConeMapOptions{});
    benchmark::DoNotOptimize(r.data());
  }
}

// A variant of the classic cones (relaxed, bilinear-safe): time, and the
// mean over the texels of its ratio over the classic one (`counter`).
void variant_cones(benchmark::State& state, const std::string& kind, int n, int threads, const ConeMapOptions& o,
                   const char* counter) {
  const std::vector<float>& f = field(kind, n);
  ThreadLimit limit(threads);
  std::vector<float> r;
  for (auto _ : state) {
    r = cone_ratios(f, n, n, o);
    benchmark::DoNotOptimize(r.data());
  }
  const std::vector<float> c = cone_ratios(f, n, n, ConeMapOptions{});
  double sum = 0;
  for (std::size_t i = 0; i < r.size(); ++i) sum += c[i] > 0 ? double(r[i]) / c[i] : 1.0;
  state.counters[counter] = sum / double(r.size());
}

// --fast: time, and the mean of fast / exact ratio over the texels (the
// exact map computed once per field, outside the timing).
void fast_cones(benchmark::State& state, const std::string& kind, int n, int threads, int reach) {
  const std::vector<float>& f = field(kind, n);
  ThreadLimit limit(threads);
  ConeMapOptions o;
  o.fast_reach = reach;
  std::vector<float> r;
  for (auto _ : state) {
    r = cone_ratios(f, n, n, o);
    benchmark::DoNotOptimize(r.data());
  }
  static std::map<std::pair<std::string, int>, std::vector<float>> exact_cache;
  auto& exact = exact_cache[{kind, n}];
  if (exact.empty()) {
    ThreadLimit all(0);
    exact = cone_ratios(f, n, n, ConeMapOptions{});
  }
  double sum = 0, worst = 1;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const double q = exact[i] > 0 ? double(r[i]) / exact[i] : 1.0;
    if (q > 1.0 + 1e-6) state.SkipWithError("fast cone wider than exact");
    sum += q;
    worst = std::min(worst, q);
  }
  state.counters["mean_fast_over_exact"] = sum / double(r.size());
  state.counters["min_fast_over_exact"] = worst;
}

void register_all() {
  for (const char* kind : {"terrain", "hemisphere", "fractal", "spikes", "white", "ramp"}) {
    for (int n : {1024, 4096}) {
      if (n == 4096 && (std::string(kind) == "white" || std::string(kind) == "ramp")) continue;
      for (int reach : {1, 2, 4}) {
        if (n == 4096 && reach == 4) continue;
        benchmark::RegisterBenchmark(
            (std::string("fast/") + kind + "/" + std::to_string(n) + "/reach:" + std::to_string(reach) + "/threads:2")
                .c_str(),
            [kind, n, reach](benchmark::State& s) { fast_cones(s, kind, n, 2, reach); })
            ->Unit(benchmark::kMillisecond)
            ->Iterations(1)
            ->UseRealTime();
      }
    }
  }
  for (int n : {256, 512, 1024, 2048, 4096}) {
    for (int t : {1, 2}) {
      if (n == 4096 && t == 1) continue;
      benchmark::RegisterBenchmark(("conemap/terrain/" + std::to_string(n) + "/threads:" + std::to_string(t)).c_str(),
                                   [n, t](benchmark::State& s) { cones(s, "terrain", n, t, false); })
          ->Unit(benchmark::kMillisecond)
          ->Iterations(n >= 2048 ? 1 : 3)
          ->UseRealTime();
    }
  }
  for (const char* kind : {"hemisphere", "fractal", "spikes", "white", "ramp"}) {
    for (int t : {1, 2}) {
      benchmark::RegisterBenchmark((std::string("conemap/") + kind + "/1024/threads:" + std::to_string(t)).c_str(),
                                   [kind, t](benchmark::State& s) { cones(s, kind, 1024, t, false); })
          ->Unit(benchmark::kMillisecond)
          ->Iterations(2)
          ->UseRealTime();
    }
    if (std::string(kind) == "white" || std::string(kind) == "ramp") continue;
    benchmark::RegisterBenchmark((std::string("conemap/") + kind + "/4096/threads:2").c_str(),
                                 [kind](benchmark::State& s) { cones(s, kind, 4096, 2, false); })
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1)
        ->UseRealTime();
  }
  for (const char* kind : {"terrain", "hemisphere", "fractal", "spikes"}) {
    benchmark::RegisterBenchmark((std::string("bilinear/") + kind + "/1024/threads:2").c_str(),
                                 [kind](benchmark::State& s) {
                                   ConeMapOptions o;
                                   o.bilinear_safe = true;
                                   variant_cones(s, kind, 1024, 2, o, "mean_safe_over_classic");
                                 })
        ->Unit(benchmark::kMillisecond)
        ->Iterations(2)
        ->UseRealTime();
  }
  for (const char* kind : {"terrain", "hemisphere", "fractal", "spikes"}) {
    benchmark::RegisterBenchmark((std::string("relaxed/") + kind + "/1024/threads:2").c_str(),
                                 [kind](benchmark::State& s) {
                                   ConeMapOptions o;
                                   o.mode = ConeMode::relaxed;
                                   variant_cones(s, kind, 1024, 2, o, "mean_relaxed_over_conservative");
                                 })
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1)
        ->UseRealTime();
  }
  for (int n : {128, 256}) {
    benchmark::RegisterBenchmark(("brute_force/terrain/" + std::to_string(n) + "/threads:2").c_str(),
                                 [n](benchmark::State& s) { cones(s, "terrain", n, 2, true); })
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1)
        ->UseRealTime();
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
}
