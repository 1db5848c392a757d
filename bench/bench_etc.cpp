// ETC benchmark: texproc's ETC1 and ETC2 RGB encoders at each quality
// against Android's libetc1 (Debian's android-libetc1-dev, the encoder
// behind etc1tool; scalar, single thread) and beside texproc's BC1 of the
// same class, on the corpus colour textures of bench_bc1, single thread, in
// one run. PSNR over RGB, decoded with texproc's decoders (which match
// libetc1's decoder bit for bit: test EtcDecode.Etc1MatchesLibEtc1).
// EAC R11 against BC4 on the corpus heightmaps: PSNR on the [0, 1] scale.
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "bench_common.h"
#include "libetc1_encode.h"
#include "texproc/block_decode.h"
#include "texproc/block_encode.h"
#include "texproc/image_io.h"
#include "texproc/metrics.h"
#include "texproc/runtime.h"

using namespace texproc;

namespace {

void color(benchmark::State& state, bool use_libetc1, TexelFormat f, Quality q) {
  ThreadLimit one(1);
  double psnr_sum = 0, pixels = 0;
  for (auto _ : state) {
    psnr_sum = 0;
    for (const Image& img : bench::color_textures()) {
      const std::vector<std::uint8_t> blocks =
          use_libetc1 ? bench::libetc1_encode(img) : compress_image(img.view(), f, q);
      state.PauseTiming();
      psnr_sum += bench::psnr_rgb(img, f, blocks);
      state.ResumeTiming();
    }
  }
  for (const Image& img : bench::color_textures()) pixels += double(img.width()) * img.height();
  state.counters["MPix/s"] = benchmark::Counter(pixels / 1e6, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["PSNR"] = psnr_sum / double(bench::color_textures().size());
}

const std::vector<Image>& heightmaps() {
  static const std::vector<Image> t = [] {
    std::vector<Image> out;
    for (const char* f : {"height/povray_mount1_250.png", "height/stellarium_stein_mauerwerk_height_256.png",
                          "height/mpl_jacksboro_fault_dem_403x344_u16.png", "height/trigger_swiss_h_1024.png"}) {
      const Image src = read_image(std::string(TEXPROC_CORPUS_DIR) + "/" + f);
      Image one(src.width() / 4 * 4, src.height() / 4 * 4, 1, PixelType::u16);
      for (int y = 0; y < one.height(); ++y)
        for (int x = 0; x < one.width(); ++x) one.set(x, y, 0, src.get(x, y, 0));
      out.push_back(std::move(one));
    }
    return out;
  }();
  return t;
}

void height(benchmark::State& state, TexelFormat f, Quality q) {
  ThreadLimit one(1);
  double psnr_sum = 0, pixels = 0;
  for (auto _ : state) {
    psnr_sum = 0;
    for (const Image& img : heightmaps()) {
      std::vector<std::uint8_t> blocks = compress_image(img.view(), f, q);
      state.PauseTiming();
      const Image d = decompress_image(std::move(blocks), img.width(), img.height(), f, PixelType::f32);
      Image src(img.width(), img.height(), 1, PixelType::f32);
      for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x) src.set(x, y, 0, img.get(x, y, 0));
      psnr_sum += compare_images(src.view(), d.view()).psnr();
      state.ResumeTiming();
    }
  }
  for (const Image& img : heightmaps()) pixels += double(img.width()) * img.height();
  state.counters["MPix/s"] = benchmark::Counter(pixels / 1e6, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["PSNR"] = psnr_sum / double(heightmaps().size());
}

}  // namespace

BENCHMARK_CAPTURE(color, libetc1, true, TexelFormat::etc1_rgb, Quality::fast)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(color, etc1_fast, false, TexelFormat::etc1_rgb, Quality::fast)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(0.5);
BENCHMARK_CAPTURE(color, etc1_normal, false, TexelFormat::etc1_rgb, Quality::normal)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(color, etc1_high, false, TexelFormat::etc1_rgb, Quality::high)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(color, etc2_fast, false, TexelFormat::etc2_rgb_unorm, Quality::fast)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(0.5);
BENCHMARK_CAPTURE(color, etc2_normal, false, TexelFormat::etc2_rgb_unorm, Quality::normal)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(color, etc2_high, false, TexelFormat::etc2_rgb_unorm, Quality::high)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(color, bc1_normal, false, TexelFormat::bc1_rgb_unorm, Quality::normal)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(color, bc1_high, false, TexelFormat::bc1_rgb_unorm, Quality::high)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(height, eac_r11_normal, TexelFormat::eac_r11_unorm, Quality::normal)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(height, eac_r11_high, TexelFormat::eac_r11_unorm, Quality::high)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(height, bc4_normal, TexelFormat::bc4_unorm, Quality::normal)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(height, bc4_high, TexelFormat::bc4_unorm, Quality::high)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

BENCHMARK_MAIN();
