// BC3 and BC2 benchmark: texproc at each quality against libsquish (Debian's
// libsquish-dev 1.15, a scalar build: DXT5 and DXT3 with range fit, cluster
// fit and iterative cluster fit colour) on the corpus textures with alpha,
// single thread, in one run. PSNR over RGBA (colour under transparent
// texels counted: texproc's default `--transparent-color keep`), decoded
// with texproc's decoder.
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

// RGBA8 crops (multiples of 4) of the corpus textures with alpha; gray and
// gray-alpha images spread to RGB.
const std::vector<Image>& alpha_textures() {
  static const std::vector<Image> t = [] {
    std::vector<Image> out;
    for (const char* f : {"alpha/trigger_palm_tree2_1000.png", "alpha/ufoai_fence_512x256.png",
                          "alpha/wz2100_page113_atlas_614x614.png", "alpha/qt3d_earth_clouds_1229x615.png",
                          "alpha/openarena_gargoyle_wings_stone.tga", "alpha/openarena_player_models_ports_504.tga",
                          "alpha/trigger_tree_shape1_gray_alpha.png", "alpha/openarena_frame1_l_ui.tga"}) {
      const Image src = read_image(std::string(TEXPROC_CORPUS_DIR) + "/" + f);
      const int w = src.width() / 4 * 4, h = src.height() / 4 * 4, n = src.channels();
      Image img(w, h, 4, PixelType::u8);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          for (int c = 0; c < 4; ++c) {
            const int sc = c == 3 ? (n == 2 || n == 4 ? n - 1 : -1) : (n <= 2 ? 0 : c);
            img.set(x, y, c, sc < 0 ? 1.0f : src.get(x, y, sc));
          }
      out.push_back(std::move(img));
    }
    return out;
  }();
  return t;
}

double psnr_rgba(const Image& src, TexelFormat f, const std::vector<std::uint8_t>& blocks) {
  const Image d = decompress_image(blocks, src.width(), src.height(), f, PixelType::u8);
  double se = 0;
  for (int y = 0; y < src.height(); ++y)
    for (int x = 0; x < 4 * src.width(); ++x) {
      const double e = double(d.row<std::uint8_t>(y)[x]) - src.row<std::uint8_t>(y)[x];
      se += e * e;
    }
  return 10 * std::log10(255.0 * 255.0 / (se / (4.0 * src.width() * src.height())));
}

// bc2: DXT3 / BC2, else DXT5 / BC3; squish_fit 0: texproc at `q`.
void run(benchmark::State& state, bool bc2, int squish_fit, Quality q) {
  ThreadLimit one(1);
  const TexelFormat f = bc2 ? TexelFormat::bc2_unorm : TexelFormat::bc3_unorm;
  double psnr_sum = 0, pixels = 0;
  for (auto _ : state) {
    psnr_sum = 0;
    for (const Image& img : alpha_textures()) {
      std::vector<std::uint8_t> blocks;
      if (squish_fit) {
        const int flags = (bc2 ? squish::kDxt3 : squish::kDxt5) | squish_fit;  // metric 0: uniform weights
        blocks.resize(squish::GetStorageRequirements(img.width(), img.height(), flags));
        squish::CompressImage(img.data(), img.width(), img.height(), blocks.data(), flags);
      } else {
        blocks = compress_image(img.view(), f, q);
      }
      state.PauseTiming();
      psnr_sum += psnr_rgba(img, f, blocks);
      state.ResumeTiming();
    }
  }
  for (const Image& img : alpha_textures()) pixels += double(img.width()) * img.height();
  state.counters["MPix/s"] = benchmark::Counter(pixels / 1e6, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["PSNR"] = psnr_sum / double(alpha_textures().size());
}

}  // namespace

BENCHMARK_CAPTURE(run, bc3_libsquish_range_fit, false, squish::kColourRangeFit, Quality::fast)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);
BENCHMARK_CAPTURE(run, bc3_libsquish_cluster_fit, false, squish::kColourClusterFit, Quality::fast)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(run, bc3_libsquish_iterative_cluster_fit, false, squish::kColourIterativeClusterFit, Quality::fast)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(run, bc3_texproc_fast, false, 0, Quality::fast)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK_CAPTURE(run, bc3_texproc_normal, false, 0, Quality::normal)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK_CAPTURE(run, bc3_texproc_high, false, 0, Quality::high)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK_CAPTURE(run, bc2_libsquish_cluster_fit, true, squish::kColourClusterFit, Quality::fast)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(run, bc2_texproc_normal, true, 0, Quality::normal)->Unit(benchmark::kMillisecond)->MinTime(1.0);

BENCHMARK_MAIN();
