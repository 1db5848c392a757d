// BC7 benchmark: texproc's encoder at each quality beside texproc's BC1
// `high` and, where CMake is given its source (-DTEXPROC_BC7ENC_DIR=, a
// checkout of richgel999/bc7enc_rdo outside this tree; skipped when absent),
// bc7enc (bc7enc_rdo's C++ block encoder: uber 0 with 16 partitions, uber 4
// with 64, linear RGB weights) and, with -DTEXPROC_CVTT_DIR=, cvtt
// (ConvectionKernels at qualities 1, 10 and 50, uniform weights), in one run. The setting: 256x256
// centred crops of the corpus's 15 albedo and photo images, opaque, single
// thread (and texproc on two), PSNR over RGB pooled over every crop's
// squared errors, scored with texproc's exact decoder (which matches
// Pillow's on random blocks).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "bench_common.h"
#include "texproc/block_decode.h"
#include "texproc/block_encode.h"
#include "texproc/image_io.h"
#include "texproc/runtime.h"

#ifdef TEXPROC_HAVE_BC7ENC
#include "bc7enc.h"
#endif
#ifdef TEXPROC_HAVE_CVTT
#include "ConvectionKernels.h"
#endif

using namespace texproc;

namespace {

#ifdef TEXPROC_HAVE_BC7ENC
std::vector<std::uint8_t> bc7enc_image(const Image& img, int uber, int partitions) {
  static const bool ready = [] {
    bc7enc_compress_block_init();
    return true;
  }();
  (void)ready;
  bc7enc_compress_block_params p;
  bc7enc_compress_block_params_init(&p);
  bc7enc_compress_block_params_init_linear_weights(&p);
  p.m_uber_level = std::uint32_t(uber);
  p.m_max_partitions = std::uint32_t(partitions);
  const int bw = img.width() / 4, bh = img.height() / 4;
  std::vector<std::uint8_t> out(std::size_t(bw) * bh * 16);
  std::uint8_t px[16][4];
  for (int by = 0; by < bh; ++by)
    for (int bx = 0; bx < bw; ++bx) {
      for (int i = 0; i < 16; ++i)
        for (int c = 0; c < 4; ++c) px[i][c] = img.row<const std::uint8_t>(4 * by + i / 4)[4 * (4 * bx + i % 4) + c];
      bc7enc_compress_block(out.data() + (std::size_t(by) * bw + bx) * 16, px, &p);
    }
  return out;
}
#endif

#ifdef TEXPROC_HAVE_CVTT
// cvtt at a quality 1-100 (its plan from ConfigureBC7EncodingPlanFromQuality),
// uniform channel weights (the PSNR here is plain RGB), eight blocks a call.
std::vector<std::uint8_t> cvtt_image(const Image& img, int quality) {
  // The plan once a quality (set up before the first timed call), not once an image.
  static std::map<int, cvtt::BC7EncodingPlan> plans;
  auto it = plans.find(quality);
  if (it == plans.end()) {
    it = plans.emplace(quality, cvtt::BC7EncodingPlan{}).first;
    cvtt::Kernels::ConfigureBC7EncodingPlanFromQuality(it->second, quality);
  }
  const cvtt::BC7EncodingPlan& plan = it->second;
  cvtt::Options options;
  options.flags = cvtt::Flags::Default | cvtt::Flags::Uniform;
  const int bw = img.width() / 4, bh = img.height() / 4, n = bw * bh;
  std::vector<std::uint8_t> out(std::size_t(n) * 16);
  cvtt::PixelBlockU8 blocks[cvtt::NumParallelBlocks];
  std::uint8_t packed[cvtt::NumParallelBlocks * 16];
  for (int b0 = 0; b0 < n; b0 += int(cvtt::NumParallelBlocks)) {
    for (int k = 0; k < int(cvtt::NumParallelBlocks); ++k) {
      const int b = std::min(b0 + k, n - 1), bx = b % bw, by = b / bw;
      for (int i = 0; i < 16; ++i)
        for (int c = 0; c < 4; ++c)
          blocks[k].m_pixels[i][c] = img.row<const std::uint8_t>(4 * by + i / 4)[4 * (4 * bx + i % 4) + c];
    }
    cvtt::Kernels::EncodeBC7(packed, blocks, options, plan);
    for (int k = 0; k < int(cvtt::NumParallelBlocks) && b0 + k < n; ++k)
      std::memcpy(&out[std::size_t(b0 + k) * 16], packed + 16 * k, 16);
  }
  return out;
}
#endif

// who: "texproc" (format, quality, threads), "bc7enc" (uber, partitions) or "cvtt" (quality in `uber`).
void run(benchmark::State& state, const std::string& who, TexelFormat format, Quality q, int threads, int uber,
         int partitions) {
  ThreadLimit limit(threads);
  // Each crop's blocks kept and scored after the timed loop: pausing the
  // clock around every crop's scoring (as an earlier version did) timed
  // the pause's own cost and the worker threads' wake-up from the
  // scoring's idle, not the encoding (texproc fast's two threads read
  // 1.79x one this way, 1.97x unpaused).
  const auto& crops = bench::centred_crops();
  std::vector<std::vector<std::uint8_t>> out(crops.size());
  for (auto _ : state) {
    for (std::size_t c = 0; c < crops.size(); ++c) {
      const Image& img = crops[c];
      std::vector<std::uint8_t>& blocks = out[c];
#ifdef TEXPROC_HAVE_BC7ENC
      if (who == "bc7enc") blocks = bc7enc_image(img, uber, partitions);
#else
      (void)partitions;
#endif
#ifdef TEXPROC_HAVE_CVTT
      if (who == "cvtt") blocks = cvtt_image(img, uber);
#endif
      (void)uber;
      if (who == "texproc") blocks = compress_image(img.view(), format, q);
      benchmark::DoNotOptimize(blocks.data());
    }
  }
  double se = 0, samples = 0;
  for (std::size_t c = 0; c < crops.size(); ++c) {
    se += bench::squared_error_rgb(crops[c], format, out[c]);
    samples += 3.0 * crops[c].width() * crops[c].height();
  }
  double pixels = 0;
  for (const Image& img : bench::centred_crops()) pixels += double(img.width()) * img.height();
  state.counters["MPix/s"] = benchmark::Counter(pixels / 1e6, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["PSNR"] = 10 * std::log10(255.0 * 255.0 / (se / samples));
}

void register_all() {
  using F = TexelFormat;
  for (Quality q : {Quality::fast, Quality::normal, Quality::high, Quality::max})
    benchmark::RegisterBenchmark((std::string("bc7/texproc/") + to_string(q)).c_str(), run, "texproc", F::bc7_unorm, q,
                                 1, 0, 0)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->MinTime(q == Quality::max ? 0.1 : 1.0);
  for (Quality q : {Quality::fast, Quality::normal})
    benchmark::RegisterBenchmark((std::string("bc7/texproc/") + to_string(q) + "/threads:2").c_str(), run, "texproc",
                                 F::bc7_unorm, q, 2, 0, 0)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  benchmark::RegisterBenchmark("bc1/texproc/high", run, "texproc", F::bc1_rgb_unorm, Quality::high, 1, 0, 0)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
#ifdef TEXPROC_HAVE_BC7ENC
  benchmark::RegisterBenchmark("bc7/bc7enc/uber0_16", run, "bc7enc", F::bc7_unorm, Quality::normal, 1, 0, 16)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  benchmark::RegisterBenchmark("bc7/bc7enc/uber4_64", run, "bc7enc", F::bc7_unorm, Quality::normal, 1, 4, 64)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime()
      ->MinTime(0.1);
#endif
#ifdef TEXPROC_HAVE_CVTT
  for (int q : {1, 10, 50})
    benchmark::RegisterBenchmark(("bc7/cvtt/quality" + std::to_string(q)).c_str(), run, "cvtt", F::bc7_unorm,
                                 Quality::normal, 1, q, 0)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->MinTime(0.1);
#endif
}

}  // namespace

int main(int argc, char** argv) {
  bench::centred_crops();  // read and cut before any timing (the first benchmark would pay for it)
#ifdef TEXPROC_HAVE_CVTT
  for (int q : {1, 10, 50}) cvtt_image(bench::centred_crops()[0], q);  // cvtt's plans, before any timing
#endif
  register_all();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
