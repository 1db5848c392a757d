// BC1 benchmark: texproc's colour encoder at each quality against libsquish
// (Debian's libsquish-dev 1.15, a scalar build: range fit, cluster fit,
// iterative cluster fit) on corpus textures, single thread, in one run. PSNR
// over RGB, decoded with texproc's decoder (the Khronos rounding).
#include <benchmark/benchmark.h>
#include <squish.h>

#include <cmath>
#include <string>

#include "bench_common.h"
#include "texproc/block_decode.h"
#include "texproc/block_encode.h"
#include "texproc/image_io.h"
#include "texproc/runtime.h"

using namespace texproc;

namespace {

// RGBA8 crops (multiples of 4) of corpus colour textures.


void run(benchmark::State& state, int squish_flags, Quality q) {
  ThreadLimit one(1);
  double psnr_sum = 0, pixels = 0;
  for (auto _ : state) {
    psnr_sum = 0;
    for (const Image& img : bench::color_textures()) {
      std::vector<std::uint8_t> blocks;
      if (squish_flags) {
        blocks.resize(squish::GetStorageRequirements(img.width(), img.height(), squish::kDxt1));
        squish::CompressImage(img.data(), img.width(), img.height(), blocks.data(), squish::kDxt1 | squish_flags);  // metric 0: uniform weights
      } else {
        blocks = compress_image(img.view(), TexelFormat::bc1_rgb_unorm, q);
      }
      state.PauseTiming();
      psnr_sum += bench::psnr_rgb(img, TexelFormat::bc1_rgb_unorm, blocks);
      state.ResumeTiming();
    }
  }
  for (const Image& img : bench::color_textures()) pixels += double(img.width()) * img.height();
  state.counters["MPix/s"] = benchmark::Counter(pixels / 1e6, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["PSNR"] = psnr_sum / double(bench::color_textures().size());
}

}  // namespace

BENCHMARK_CAPTURE(run, libsquish_range_fit, squish::kColourRangeFit, Quality::fast)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK_CAPTURE(run, libsquish_cluster_fit, squish::kColourClusterFit, Quality::fast)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(run, libsquish_iterative_cluster_fit, squish::kColourIterativeClusterFit, Quality::fast)
    ->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(run, texproc_fast, 0, Quality::fast)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK_CAPTURE(run, texproc_normal, 0, Quality::normal)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK_CAPTURE(run, texproc_high, 0, Quality::high)->Unit(benchmark::kMillisecond)->Iterations(1);

BENCHMARK_MAIN();
