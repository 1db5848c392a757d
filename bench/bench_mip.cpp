// Mip-chain benchmark: texproc's mip stage in memory, and whole commands
// (TIFF in, TIFF out) for texproc, maketx and nvcompress in the same run.
//
// Input: a 4096x4096 RGBA8 sRGB image tiled from corpus albedo textures, with
// a soft alpha. Run: build/bench/bench_mip [--benchmark_filter=...]
// Ratios against the peers are printed after the table.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>

#include "texproc/image_io.h"
#include "texproc/mip.h"
#include "texproc/runtime.h"

namespace fs = std::filesystem;
using namespace texproc;

namespace {

const std::string kDir = (fs::temp_directory_path() / "texproc_bench").string();

// 4096x4096 RGBA8: a 2x2 tiling of a 2048x2048 corpus albedo, alpha from a
// smooth pattern (so premultiplication does real work).
const Image& input_image() {
  static const Image img = [] {
    const Image src = read_image(std::string(TEXPROC_CORPUS_DIR) + "/albedo_srgb/wz2100_backdrop0_2048.png");
    Image out(4096, 4096, 4, PixelType::u8);
    for (int y = 0; y < 4096; ++y) {
      const std::uint8_t* s = src.row<std::uint8_t>(y % src.height());
      std::uint8_t* d = out.row<std::uint8_t>(y);
      for (int x = 0; x < 4096; ++x) {
        const int sx = x % src.width();
        for (int c = 0; c < 3; ++c) d[x * 4 + c] = s[sx * src.channels() + std::min(c, src.channels() - 1)];
        d[x * 4 + 3] = std::uint8_t(std::lround(127.5 + 127.5 * std::sin(x * 0.01) * std::cos(y * 0.013)));
      }
    }
    return out;
  }();
  return img;
}

const std::string& input_file(const char* ext) {
  static std::map<std::string, std::string> files;
  auto it = files.find(ext);
  if (it != files.end()) return it->second;
  fs::create_directories(kDir);
  const std::string path = kDir + "/in4096" + ext;
  WriteOptions w;
  w.compression = "none";
  write_image(path, input_image().view(), w);
  return files[ext] = path;
}

void mip_stage(benchmark::State& state, FilterKind kind, int threads) {
  const Image& img = input_image();
  ThreadLimit limit(threads);
  MipOptions o;
  o.filter.kind = kind;
  for (auto _ : state) {
    // Level 0 moves into the chain, as the CLI does; the copy is not timed.
    state.PauseTiming();
    Image copy = img;
    state.ResumeTiming();
    MipChain c = generate_mips(std::move(copy), o);
    benchmark::DoNotOptimize(c.levels.back().data());
    state.PauseTiming();
    c = MipChain{};  // freeing is not timed either
    state.ResumeTiming();
  }
  state.counters["MPix/s"] = benchmark::Counter(4096.0 * 4096.0 / 1e6, benchmark::Counter::kIsIterationInvariantRate);
}

void run_command(benchmark::State& state, const std::string& cmd) {
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    if (std::system(cmd.c_str()) != 0) {
      state.SkipWithError(("failed: " + cmd).c_str());
      return;
    }
    state.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
}

void BM_MipStage_Gaussian(benchmark::State& s) { mip_stage(s, FilterKind::gaussian, 0); }
void BM_MipStage_Gaussian_1thread(benchmark::State& s) { mip_stage(s, FilterKind::gaussian, 1); }
void BM_MipStage_Box(benchmark::State& s) { mip_stage(s, FilterKind::box, 0); }
void BM_MipStage_Box_1thread(benchmark::State& s) { mip_stage(s, FilterKind::box, 1); }
void BM_MipStage_Lanczos3(benchmark::State& s) { mip_stage(s, FilterKind::lanczos3, 0); }

void BM_Command_texproc(benchmark::State& s) {
  run_command(
      s, std::string(TEXPROC_CLI_PATH) + " mip " + input_file(".tif") + " -o " + kDir + "/out_texproc.tif --force -q");
}
void BM_Command_maketx(benchmark::State& s) {
  run_command(s, "maketx --filter gaussian " + input_file(".tif") + " -o " + kDir + "/out_maketx.tif >/dev/null");
}
void BM_Command_nvcompress(benchmark::State& s) {
  // nvcompress reads TGA, not TIFF: the same pixels, uncompressed RGBA mips to DDS.
  run_command(s, "nvcompress -rgb -nocuda -alpha " + input_file(".tga") + " " + kDir + "/out_nvtt.dds >/dev/null");
}

BENCHMARK(BM_MipStage_Gaussian)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_MipStage_Gaussian_1thread)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_MipStage_Box)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_MipStage_Box_1thread)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_MipStage_Lanczos3)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_Command_texproc)->Unit(benchmark::kMillisecond)->UseManualTime()->Iterations(5);
BENCHMARK(BM_Command_maketx)->Unit(benchmark::kMillisecond)->UseManualTime()->Iterations(3);
BENCHMARK(BM_Command_nvcompress)->Unit(benchmark::kMillisecond)->UseManualTime()->Iterations(3);

// Remembers each benchmark's time so that ratios can be printed at the end.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& r : runs) {
      if (!r.error_occurred) times_[r.benchmark_name()] = r.GetAdjustedRealTime();
    }
  }
  void Finalize() override {
    ConsoleReporter::Finalize();
    auto ratio = [&](const std::string& a, const std::string& b) {
      if (times_.count(a) && times_.count(b)) {
        std::cout << b << " / " << a << " = " << times_[b] / times_[a] << "x\n";
      }
    };
    std::cout << "\nRatios (peer time / texproc time; > 1 means texproc is faster):\n";
    ratio("BM_Command_texproc/iterations:5/manual_time", "BM_Command_maketx/iterations:3/manual_time");
    ratio("BM_Command_texproc/iterations:5/manual_time", "BM_Command_nvcompress/iterations:3/manual_time");
    ratio("BM_MipStage_Gaussian/min_time:2.000", "BM_MipStage_Gaussian_1thread/min_time:2.000");
    ratio("BM_MipStage_Box/min_time:2.000", "BM_MipStage_Box_1thread/min_time:2.000");
  }

 private:
  std::map<std::string, double> times_;
};

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  std::cout << "SIMD target: " << simd_target_name() << ", hardware threads: " << hardware_threads() << "\n";
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
}
