// Summed-area table benchmark: building tables of a 4096x4096 RGBA8 image
// (u32 and f32) and of a 16384x16384 8-bit image (u32), into reused memory,
// beside a plain pass that reads the same input and writes the same number
// of table bytes (the bandwidth floor) in the same run.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstring>

#include "texproc/image_io.h"
#include "texproc/runtime.h"
#include "texproc/sat.h"

using namespace texproc;

namespace {

const Image& rgba4096() {
  static const Image img = [] {
    const Image src = read_image(std::string(TEXPROC_CORPUS_DIR) + "/albedo_srgb/wz2100_backdrop0_2048.png");
    Image out = Image::uninitialized(4096, 4096, 4, PixelType::u8);
    for (int y = 0; y < 4096; ++y)
      for (int x = 0; x < 4096; ++x) {
        const std::uint8_t* s = src.row<std::uint8_t>(y % 2048) + (x % 2048) * 3;
        std::uint8_t* d = out.row<std::uint8_t>(y) + x * 4;
        d[0] = s[0];
        d[1] = s[1];
        d[2] = s[2];
        d[3] = std::uint8_t((x ^ y) & 255);
      }
    return out;
  }();
  return img;
}

const Image& gray16k() {
  static const Image img = [] {
    const Image src = read_image(std::string(TEXPROC_CORPUS_DIR) + "/height/trigger_swiss_h_1024.png");
    Image out = Image::uninitialized(16384, 16384, 1, PixelType::u8);
    for (int y = 0; y < 16384; ++y)
      for (int x = 0; x < 16384; ++x) out.row<std::uint8_t>(y)[x] = src.row<std::uint8_t>(y % 1024)[x % 1024];
    return out;
  }();
  return img;
}

void table(benchmark::State& state, const Image& img, SatPrecision p) {
  SummedAreaTable t;
  build_sat(img.view(), p, t);  // first touch outside the timing
  for (auto _ : state) {
    build_sat(img.view(), p, t);
    benchmark::DoNotOptimize(t.data.data());
  }
  state.counters["MPix/s"] =
      benchmark::Counter(double(img.width()) * img.height() / 1e6, benchmark::Counter::kIsIterationInvariantRate);
}

// Reads every input byte and writes a 4-byte element for it, on the same
// threads and row blocks: what building a u32 table must at least cost.
void floor_pass(benchmark::State& state, const Image& img) {
  const std::size_t n = std::size_t(img.width()) * img.channels();
  PixelBytes bytes(n * img.height() * 4);      // pixel memory, as the tables'
  std::memset(bytes.data(), 0, bytes.size());  // first touch outside the timing, as for the tables
  auto* const out = reinterpret_cast<std::uint32_t*>(bytes.data());
  for (auto _ : state) {
    for_each_row_block(img.height(), 64, [&](int y0, int y1) {
      for (int y = y0; y < y1; ++y) {
        const std::uint8_t* s = img.row<std::uint8_t>(y);
        std::uint32_t* d = out + std::size_t(y) * n;
        for (std::size_t i = 0; i < n; ++i) d[i] = s[i];
      }
    });
    benchmark::DoNotOptimize(out);
  }
}

void BM_Floor_rgba8_4096(benchmark::State& s) { floor_pass(s, rgba4096()); }
void BM_Sat_u32_rgba8_4096(benchmark::State& s) { table(s, rgba4096(), SatPrecision::u32); }
void BM_Sat_f32_rgba8_4096(benchmark::State& s) { table(s, rgba4096(), SatPrecision::f32); }
void BM_Sat_u64_rgba8_4096(benchmark::State& s) { table(s, rgba4096(), SatPrecision::u64); }
void BM_Floor_gray8_16384(benchmark::State& s) { floor_pass(s, gray16k()); }
void BM_Sat_u32_gray8_16384(benchmark::State& s) { table(s, gray16k(), SatPrecision::u32); }

}  // namespace

BENCHMARK(BM_Floor_rgba8_4096)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Sat_u32_rgba8_4096)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Sat_f32_rgba8_4096)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Sat_u64_rgba8_4096)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Floor_gray8_16384)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Sat_u32_gray8_16384)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
