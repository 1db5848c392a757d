// BC1 benchmark: texproc's colour encoder at each quality against libsquish
// (Debian's libsquish-dev 1.15, a scalar build: range fit, cluster fit,
// iterative cluster fit) on corpus textures, single thread, in one run. PSNR
// over RGB, decoded with texproc's decoder (the Khronos rounding).
#include <benchmark/benchmark.h>
#include <squish.h>

#include <cmath>
#include <string>

#include "texproc/block_decode.h"
#include "texproc/block_encode.h"
#include "texproc/image_io.h"
#include "texproc/runtime.h"

using namespace texproc;

namespace {

// RGBA8 crops (multiples of 4) of corpus colour textures.
const std::vector<Image>& textures() {
  static const std::vector<Image> t = [] {
    std::vector<Image> out;
    for (const char* f : {"albedo_srgb/colobot_desert4.png", "albedo_srgb/ufoai_rock017.png", "photo/skimage_astronaut_512.png",
                          "albedo_srgb/wz2100_terrain_tile10_128_palette.png", "photo/skimage_coffee_600x400.png",
                          "albedo_srgb/stellarium_stein_mauerwerk_512_rgba_opaque.png"}) {
      const Image src = read_image(std::string(TEXPROC_CORPUS_DIR) + "/" + f);
      const int w = src.width() / 4 * 4, h = src.height() / 4 * 4;
      Image img(w, h, 4, PixelType::u8);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          for (int c = 0; c < 4; ++c) img.set(x, y, c, c == 3 ? 1.0f : src.get(x, y, std::min(c, src.channels() - 1)));
      out.push_back(std::move(img));
    }
    return out;
  }();
  return t;
}

double psnr_rgb(const Image& src, const std::vector<std::uint8_t>& blocks) {
  Texture t;
  t.format = TexelFormat::bc1_rgb_unorm;
  t.width = std::uint32_t(src.width());
  t.height = std::uint32_t(src.height());
  t.images.push_back(blocks);
  const Image d = decode_texture_image(t, 0, 0, 0, PixelType::u8);
  double se = 0;
  for (int y = 0; y < src.height(); ++y)
    for (int x = 0; x < src.width(); ++x)
      for (int c = 0; c < 3; ++c) {
        const double e = double(d.row<std::uint8_t>(y)[3 * x + c]) - src.row<std::uint8_t>(y)[4 * x + c];
        se += e * e;
      }
  return 10 * std::log10(255.0 * 255.0 / (se / (3.0 * src.width() * src.height())));
}

void run(benchmark::State& state, int squish_flags, Quality q) {
  ThreadLimit one(1);
  double psnr_sum = 0, pixels = 0;
  for (auto _ : state) {
    psnr_sum = 0;
    for (const Image& img : textures()) {
      std::vector<std::uint8_t> blocks;
      if (squish_flags) {
        blocks.resize(squish::GetStorageRequirements(img.width(), img.height(), squish::kDxt1));
        squish::CompressImage(img.data(), img.width(), img.height(), blocks.data(), squish::kDxt1 | squish_flags);  // metric 0: uniform weights
      } else {
        blocks = compress_image(img.view(), TexelFormat::bc1_rgb_unorm, q);
      }
      state.PauseTiming();
      psnr_sum += psnr_rgb(img, blocks);
      state.ResumeTiming();
    }
  }
  for (const Image& img : textures()) pixels += double(img.width()) * img.height();
  state.counters["MPix/s"] = benchmark::Counter(pixels / 1e6, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["PSNR"] = psnr_sum / double(textures().size());
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
