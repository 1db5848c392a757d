// BC4 and BC5 benchmark: texproc's encoder at each quality against
// libsquish's BC4 and BC5 (Debian's libsquish-dev 1.15, a scalar build) on
// the corpus heightmaps (BC4) and normal maps' X and Y (BC5), single thread,
// in one run; and BC4 on two threads. PSNR is scored with the
// specification's exact decoding (texproc's decoder; libsquish's own BC4/BC5
// decoding is not used); BC5's over both channels, and each channel's. And
// whole processes, TGA in, DDS out: nvcompress (Debian's NVIDIA Texture
// Tools 2.0) beside `texproc compress --threads 1`.
#include <benchmark/benchmark.h>
#include <squish.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <cstdio>

#include "bench_common.h"
#include "texproc/block_decode.h"
#include "texproc/block_encode.h"
#include "texproc/container.h"
#include "texproc/image_io.h"
#include "texproc/normalmap.h"
#include "texproc/runtime.h"

using namespace texproc;

namespace {

struct Height {
  std::string name;
  Image r8;  // one channel, 8-bit, width and height multiples of 4 (cropped)
};

const std::vector<Height>& heights() {
  static const std::vector<Height> h = [] {
    std::vector<Height> out;
    for (const char* f : {"height/trigger_swiss_h_1024.png", "height/irrlicht_terrain_heightmap_256.bmp",
                          "height/povray_mount1_250.png", "height/scorched3d_denali_256.bmp",
                          "height/stellarium_stein_mauerwerk_height_256.png"}) {
      const Image img = read_image(std::string(TEXPROC_CORPUS_DIR) + "/" + f);
      const std::vector<float> v = extract_height(img.view(), HeightChannel::r, false);
      const int w = img.width() / 4 * 4, hh = img.height() / 4 * 4;
      Image r(w, hh, 1, PixelType::u8);
      for (int y = 0; y < hh; ++y)
        for (int x = 0; x < w; ++x) r.set(x, y, 0, v[std::size_t(y) * img.width() + x]);
      out.push_back({f, std::move(r)});
    }
    return out;
  }();
  return h;
}

double psnr(const Image& src, const std::vector<std::uint8_t>& blocks) {
  const Image d = decompress_image(blocks, src.width(), src.height(), TexelFormat::bc4_unorm, PixelType::f32);
  double se = 0;
  for (int y = 0; y < src.height(); ++y)
    for (int x = 0; x < src.width(); ++x) se += std::pow(d.get(x, y, 0) * 255.0 - src.row<std::uint8_t>(y)[x], 2);
  return 10 * std::log10(255.0 * 255.0 / (se / (double(src.width()) * src.height())));
}

// BC5: RGBA8 crops of corpus tangent-space normal maps (X in red, Y in green).
const std::vector<Image>& normal_maps() {
  static const std::vector<Image> n = [] {
    std::vector<Image> out;
    for (const char* f :
         {"normal_ts/qt3d_copper_brushed_normal.png", "normal_ts/qt3d_water_normal_512.jpg",
          "normal_ts/ufoai_door061_nm_alphaheight_512x602.png", "normal_ts/stellarium_stein_mauerwerk_bump_256.png",
          "normal_ts/qt3d_moonnormal_1638x819.jpg", "normal_ts/ufoai_rock017_nm_alphaheight.png"})
      out.push_back(bench::color_crop(f));
    return out;
  }();
  return n;
}

// PSNR over [0, 255] with the exact decoding: psnr[0] X, psnr[1] Y,
// psnr[2] both (the squared errors of the two channels pooled, as RGB PSNR
// pools three: a channel coded losslessly does not run off to infinity).
void psnr_xy(const Image& src, const std::vector<std::uint8_t>& blocks, double psnr[3]) {
  const Image d = decompress_image(blocks, src.width(), src.height(), TexelFormat::bc5_unorm, PixelType::f32);
  const double n = double(src.width()) * src.height();
  double se[2] = {};
  for (int c = 0; c < 2; ++c)
    for (int y = 0; y < src.height(); ++y)
      for (int x = 0; x < src.width(); ++x)
        se[c] += std::pow(d.get(x, y, c) * 255.0 - src.row<std::uint8_t>(y)[4 * x + c], 2);
  for (int c = 0; c < 2; ++c) psnr[c] = 10 * std::log10(255.0 * 255.0 / (se[c] / n));
  psnr[2] = 10 * std::log10(255.0 * 255.0 / ((se[0] + se[1]) / (2 * n)));
}

void run_bc5(benchmark::State& state, const std::string& who, Quality q) {
  ThreadLimit one(1);
  double pixels = 0, psnr_sum[3] = {};
  for (auto _ : state) {
    psnr_sum[0] = psnr_sum[1] = psnr_sum[2] = 0;
    for (const Image& img : normal_maps()) {
      std::vector<std::uint8_t> blocks;
      if (who == "libsquish") {  // kBc5: red and green
        blocks.resize(squish::GetStorageRequirements(img.width(), img.height(), squish::kBc5));
        squish::CompressImage(img.data(), img.width(), img.height(), blocks.data(), squish::kBc5);
      } else {
        blocks = compress_image(img.view(), TexelFormat::bc5_unorm, q);
      }
      benchmark::DoNotOptimize(blocks.data());
      state.PauseTiming();
      double p[3];
      psnr_xy(img, blocks, p);
      for (int k = 0; k < 3; ++k) psnr_sum[k] += p[k];
      state.ResumeTiming();
    }
  }
  for (const Image& img : normal_maps()) pixels += double(img.width()) * img.height();
  const double n = double(normal_maps().size());
  state.counters["MPix/s"] = benchmark::Counter(pixels / 1e6, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["PSNR"] = psnr_sum[2] / n;
  state.counters["PSNR_X"] = psnr_sum[0] / n;
  state.counters["PSNR_Y"] = psnr_sum[1] / n;
}

void run_threads(benchmark::State& state, const std::string& who, Quality q, int threads) {
  ThreadLimit limit(threads);
  double pixels = 0, psnr_sum = 0;
  for (auto _ : state) {
    psnr_sum = 0;
    for (const Height& h : heights()) {
      std::vector<std::uint8_t> blocks;
      if (who == "libsquish") {
        // libsquish takes RGBA8 and compresses the red channel for kBc4.
        std::vector<squish::u8> rgba(std::size_t(h.r8.width()) * h.r8.height() * 4, 255);
        for (std::size_t i = 0; i < std::size_t(h.r8.width()) * h.r8.height(); ++i) rgba[4 * i] = h.r8.data()[i];
        blocks.resize(squish::GetStorageRequirements(h.r8.width(), h.r8.height(), squish::kBc4));
        squish::CompressImage(rgba.data(), h.r8.width(), h.r8.height(), blocks.data(), squish::kBc4);
      } else {
        blocks = compress_image(h.r8.view(), TexelFormat::bc4_unorm, q);
      }
      benchmark::DoNotOptimize(blocks.data());
      state.PauseTiming();
      psnr_sum += psnr(h.r8, blocks);
      state.ResumeTiming();
    }
  }
  for (const Height& h : heights()) pixels += double(h.r8.width()) * h.r8.height();
  state.counters["MPix/s"] = benchmark::Counter(pixels / 1e6, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["PSNR"] = psnr_sum / double(heights().size());
}

void run(benchmark::State& state, const std::string& who, Quality q) { run_threads(state, who, q, 1); }

// The inputs as RGBA8 TGA files (what nvcompress reads), written once:
// heightmaps in every channel, normal maps as they are.
std::vector<std::string> write_tga_files(bool bc5) {
  const std::string dir = (std::filesystem::temp_directory_path() / "texproc_bench_bc4").string();
  std::filesystem::create_directories(dir);
  std::vector<std::string> out;
  WriteOptions w;
  w.color_space = "linear";
  const std::size_t n = bc5 ? normal_maps().size() : heights().size();
  for (std::size_t i = 0; i < n; ++i) {
    out.push_back(dir + (bc5 ? "/n" : "/h") + std::to_string(i) + ".tga");
    if (bc5) {
      write_image(out.back(), normal_maps()[i].view(), w);
      continue;
    }
    const Image& h = heights()[i].r8;
    Image rgba(h.width(), h.height(), 4, PixelType::u8);
    for (int y = 0; y < h.height(); ++y)
      for (int x = 0; x < h.width(); ++x)
        for (int c = 0; c < 4; ++c) rgba.row<std::uint8_t>(y)[4 * x + c] = h.row<std::uint8_t>(y)[x];
    write_image(out.back(), rgba.view(), w);
  }
  return out;
}

const std::vector<std::string>& tga_files(bool bc5) {
  static const std::vector<std::string> h = write_tga_files(false), n = write_tga_files(true);
  return bc5 ? n : h;
}

// One whole process per texture, TGA in, DDS out: nvcompress (Debian's
// NVIDIA Texture Tools 2.0, -nocuda) or `texproc compress --threads 1`; the
// DDS decoded with texproc for the PSNR (BC5's over both channels).
void process(benchmark::State& state, const std::string& tool, bool bc5) {
  double psnr_sum = 0, pixels = 0;
  const char* f = bc5 ? "bc5" : "bc4";
  for (auto _ : state) {
    double seconds = 0;
    psnr_sum = 0;
    for (std::size_t i = 0; i < tga_files(bc5).size(); ++i) {
      const std::string in = tga_files(bc5)[i], out = in + "." + tool + ".dds";
      const std::string cmd = tool == "nvcompress"
                                  ? "nvcompress -" + std::string(f) + " -nomips -nocuda " + in + " " + out
                                  : std::string(TEXPROC_CLI_PATH) + " compress " + in + " -o " + out + " --format " +
                                        f + " --threads 1 -f -q";
      const double took = bench::timed_command(cmd);
      if (took < 0) {
        state.SkipWithError(("failed: " + cmd).c_str());
        return;
      }
      seconds += took;
      const Texture t = read_texture(out);
      if (bc5) {
        double p[3];
        psnr_xy(normal_maps()[i], t.image(0), p);
        psnr_sum += p[2];
      } else {
        psnr_sum += psnr(heights()[i].r8, t.image(0));
      }
    }
    state.SetIterationTime(seconds);
  }
  const std::size_t n = bc5 ? normal_maps().size() : heights().size();
  for (std::size_t i = 0; i < n; ++i) {
    const Image& img = bc5 ? normal_maps()[i] : heights()[i].r8;
    pixels += double(img.width()) * img.height();
  }
  state.counters["MPix/s"] = benchmark::Counter(pixels / 1e6, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["PSNR"] = psnr_sum / double(n);
}

}  // namespace

BENCHMARK_CAPTURE(process, bc4_nvcompress_process, std::string("nvcompress"), false)
    ->Unit(benchmark::kMillisecond)
    ->UseManualTime()
    ->Iterations(3);
BENCHMARK_CAPTURE(process, bc4_texproc_process, std::string("texproc"), false)
    ->Unit(benchmark::kMillisecond)
    ->UseManualTime()
    ->Iterations(3);
BENCHMARK_CAPTURE(process, bc5_nvcompress_process, std::string("nvcompress"), true)
    ->Unit(benchmark::kMillisecond)
    ->UseManualTime()
    ->Iterations(3);
BENCHMARK_CAPTURE(process, bc5_texproc_process, std::string("texproc"), true)
    ->Unit(benchmark::kMillisecond)
    ->UseManualTime()
    ->Iterations(3);
BENCHMARK_CAPTURE(run, libsquish_bc4, std::string("libsquish"), Quality::normal)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);
BENCHMARK_CAPTURE(run, texproc_fast, std::string("texproc"), Quality::fast)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);
BENCHMARK_CAPTURE(run, texproc_normal, std::string("texproc"), Quality::normal)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);
BENCHMARK_CAPTURE(run, texproc_high, std::string("texproc"), Quality::high)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);
// Thread scaling (wall-clock time): the heightmaps above on two threads.
BENCHMARK_CAPTURE(run_threads, texproc_normal_2_threads, std::string("texproc"), Quality::normal, 2)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0)
    ->UseRealTime();
BENCHMARK_CAPTURE(run_threads, texproc_high_2_threads, std::string("texproc"), Quality::high, 2)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0)
    ->UseRealTime();
// BC5 on normal maps' X and Y.
BENCHMARK_CAPTURE(run_bc5, bc5_libsquish, std::string("libsquish"), Quality::normal)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);
BENCHMARK_CAPTURE(run_bc5, bc5_texproc_fast, std::string("texproc"), Quality::fast)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);
BENCHMARK_CAPTURE(run_bc5, bc5_texproc_normal, std::string("texproc"), Quality::normal)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);
BENCHMARK_CAPTURE(run_bc5, bc5_texproc_high, std::string("texproc"), Quality::high)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);

BENCHMARK_MAIN();
