// BC1 benchmark: texproc's colour encoder at each quality against libsquish
// (Debian's libsquish-dev 1.15, a scalar build: range fit, cluster fit,
// iterative cluster fit) on corpus textures, single thread, in one run. PSNR
// over RGB, decoded with texproc's decoder (the Khronos rounding). And whole
// processes, TGA in, DDS out: NVIDIA Texture Tools' nvcompress (Debian's
// libnvtt-bin 2.0, -nocuda) beside `texproc compress --threads 1`.
#include <benchmark/benchmark.h>
#include <squish.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>

#include "bench_common.h"
#include "texproc/block_decode.h"
#include "texproc/block_encode.h"
#include "texproc/container.h"
#include "texproc/image_io.h"
#include "texproc/runtime.h"

using namespace texproc;

namespace {

void run_threads(benchmark::State& state, int squish_flags, Quality q, int threads) {
  ThreadLimit limit(threads);
  double psnr_sum = 0, pixels = 0;
  for (auto _ : state) {
    psnr_sum = 0;
    for (const Image& img : bench::color_textures()) {
      std::vector<std::uint8_t> blocks;
      if (squish_flags) {
        blocks.resize(squish::GetStorageRequirements(img.width(), img.height(), squish::kDxt1));
        squish::CompressImage(img.data(), img.width(), img.height(), blocks.data(),
                              squish::kDxt1 | squish_flags);  // metric 0: uniform weights
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

void run(benchmark::State& state, int squish_flags, Quality q) { run_threads(state, squish_flags, q, 1); }

// The textures tiled into one 2048x2048 image.
const Image& mosaic_image() {
  static const Image img = [] {
    Image m(2048, 2048, 4, PixelType::u8);
    const auto& t = bench::color_textures();
    for (int y = 0; y < 2048; ++y)
      for (int x = 0; x < 2048; ++x) {
        const Image& src = t[std::size_t((y / 512) * 4 + x / 512) % t.size()];
        std::memcpy(m.row<std::uint8_t>(y) + 4 * x, src.row<std::uint8_t>(y % src.height()) + 4 * (x % src.width()), 4);
      }
    return m;
  }();
  return img;
}

void mosaic(benchmark::State& state, Quality q, int threads) {
  ThreadLimit limit(threads);
  for (auto _ : state) benchmark::DoNotOptimize(compress_image(mosaic_image().view(), TexelFormat::bc1_rgb_unorm, q));
  state.counters["MPix/s"] = benchmark::Counter(2048.0 * 2048.0 / 1e6, benchmark::Counter::kIsIterationInvariantRate);
}

// The textures as TGA files (what nvcompress reads), written once.
const std::vector<std::string>& tga_files() {
  static const std::vector<std::string> files = [] {
    const std::string dir = (std::filesystem::temp_directory_path() / "texproc_bench_bc1").string();
    std::filesystem::create_directories(dir);
    std::vector<std::string> out;
    for (std::size_t i = 0; i < bench::color_textures().size(); ++i) {
      out.push_back(dir + "/t" + std::to_string(i) + ".tga");
      WriteOptions w;
      w.color_space = "linear";
      write_image(out.back(), bench::color_textures()[i].view(), w);
    }
    return out;
  }();
  return files;
}

// One whole process per texture (`command` gets the input and output
// names); its DDS is decoded with texproc for the PSNR.
void process(benchmark::State& state, const std::string& tool) {
  double psnr_sum = 0, pixels = 0;
  for (auto _ : state) {
    double seconds = 0;
    psnr_sum = 0;
    for (std::size_t i = 0; i < tga_files().size(); ++i) {
      const std::string in = tga_files()[i], out = in + "." + tool + ".dds";
      const std::string cmd = tool == "nvcompress" ? "nvcompress -bc1 -nomips -nocuda -color " + in + " " + out
                                                   : std::string(TEXPROC_CLI_PATH) + " compress " + in + " -o " + out +
                                                         " --format bc1 --linear --threads 1 -f -q";
      const double took = bench::timed_command(cmd);
      if (took < 0) {
        state.SkipWithError(("failed: " + cmd).c_str());
        return;
      }
      seconds += took;
      const Texture t = read_texture(out);
      psnr_sum += bench::psnr_rgb(bench::color_textures()[i], TexelFormat::bc1_rgb_unorm, t.image(0));
    }
    state.SetIterationTime(seconds);
  }
  for (const Image& img : bench::color_textures()) pixels += double(img.width()) * img.height();
  state.counters["MPix/s"] = benchmark::Counter(pixels / 1e6, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["PSNR"] = psnr_sum / double(bench::color_textures().size());
}

}  // namespace

BENCHMARK_CAPTURE(process, nvcompress_process, std::string("nvcompress"))
    ->Unit(benchmark::kMillisecond)
    ->UseManualTime()
    ->Iterations(3);
BENCHMARK_CAPTURE(process, texproc_process, std::string("texproc"))
    ->Unit(benchmark::kMillisecond)
    ->UseManualTime()
    ->Iterations(3);
BENCHMARK_CAPTURE(run, libsquish_range_fit, squish::kColourRangeFit, Quality::fast)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);
BENCHMARK_CAPTURE(run, libsquish_cluster_fit, squish::kColourClusterFit, Quality::fast)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(run, libsquish_iterative_cluster_fit, squish::kColourIterativeClusterFit, Quality::fast)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(run, texproc_fast, 0, Quality::fast)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK_CAPTURE(run, texproc_normal, 0, Quality::normal)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK_CAPTURE(run, texproc_high, 0, Quality::high)->Unit(benchmark::kMillisecond)->Iterations(1);
// Thread scaling (wall-clock time): the textures above on two threads (each
// image is small: a fast encode takes well under a millisecond, so waking
// the second thread shows), and a 2048x2048 mosaic of them on one and two.
BENCHMARK_CAPTURE(run_threads, texproc_fast_2_threads, 0, Quality::fast, 2)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0)
    ->UseRealTime();
BENCHMARK_CAPTURE(run_threads, texproc_normal_2_threads, 0, Quality::normal, 2)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0)
    ->UseRealTime();
BENCHMARK_CAPTURE(run_threads, texproc_high_2_threads, 0, Quality::high, 2)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->UseRealTime();
BENCHMARK_CAPTURE(mosaic, fast_1_thread, Quality::fast, 1)->Unit(benchmark::kMillisecond)->MinTime(1.0)->UseRealTime();
BENCHMARK_CAPTURE(mosaic, fast_2_threads, Quality::fast, 2)->Unit(benchmark::kMillisecond)->MinTime(1.0)->UseRealTime();
BENCHMARK_CAPTURE(mosaic, normal_1_thread, Quality::normal, 1)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0)
    ->UseRealTime();
BENCHMARK_CAPTURE(mosaic, normal_2_threads, Quality::normal, 2)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0)
    ->UseRealTime();

BENCHMARK_MAIN();
