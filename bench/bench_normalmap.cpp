// Normal-map benchmark: each kernel on a 4096x4096 16-bit heightmap, into a
// preallocated RGB8 image, against a plain read-and-write pass over the same
// memory (the bandwidth floor) in the same run.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstring>

#include "texproc/image_io.h"
#include "texproc/normalmap.h"
#include "texproc/runtime.h"

using namespace texproc;

namespace {

// 4096x4096 u16: the corpus terrain heightmap tiled 4x4, plus fine detail so
// that no region is flat.
const Image& heights() {
  static const Image img = [] {
    const Image src = read_image(std::string(TEXPROC_CORPUS_DIR) + "/height/trigger_swiss_h_1024.png");
    Image out = Image::uninitialized(4096, 4096, 1, PixelType::u16);
    for (int y = 0; y < 4096; ++y)
      for (int x = 0; x < 4096; ++x) {
        const float h = src.get(x % src.width(), y % src.height(), 0) * 0.95f +
                        0.025f * (1.0f + std::sin(x * 0.37f) * std::cos(y * 0.23f));
        out.row<std::uint16_t>(y)[x] = std::uint16_t(std::lround(h * 65535.0f));
      }
    return out;
  }();
  return img;
}

void normals(benchmark::State& state, GradientKernel k) {
  const Image& h = heights();
  Image out = Image::uninitialized(4096, 4096, 3, PixelType::u8);
  NormalMapOptions o;
  o.kernel = k;
  for (auto _ : state) {
    compute_normal_map(h.view(), out.view(), o);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["MPix/s"] = benchmark::Counter(4096.0 * 4096.0 / 1e6, benchmark::Counter::kIsIterationInvariantRate);
}

// Reads every u16 and writes three bytes, on the same threads: what any
// kernel must at least pay.
void BM_BandwidthFloor(benchmark::State& state) {
  const Image& h = heights();
  Image out = Image::uninitialized(4096, 4096, 3, PixelType::u8);
  for (auto _ : state) {
    for_each_row_block(4096, 16, [&](int y0, int y1) {
      for (int y = y0; y < y1; ++y) {
        const std::uint16_t* s = h.row<std::uint16_t>(y);
        std::uint8_t* d = out.row<std::uint8_t>(y);
        for (int x = 0; x < 4096; ++x) {
          const std::uint8_t v = std::uint8_t(s[x] >> 8);
          d[3 * x] = v;
          d[3 * x + 1] = v;
          d[3 * x + 2] = v;
        }
      }
    });
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["MPix/s"] = benchmark::Counter(4096.0 * 4096.0 / 1e6, benchmark::Counter::kIsIterationInvariantRate);
}

}  // namespace

BENCHMARK(BM_BandwidthFloor)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(normals, gather2x2, GradientKernel::gather2x2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(normals, central, GradientKernel::central)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(normals, sobel3, GradientKernel::sobel3)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(normals, prewitt3, GradientKernel::prewitt3)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(normals, scharr3, GradientKernel::scharr3)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(normals, sobel5, GradientKernel::sobel5)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(normals, prewitt5, GradientKernel::prewitt5)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(normals, multiscale, GradientKernel::multiscale)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
