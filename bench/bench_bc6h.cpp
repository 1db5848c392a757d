// BC6H benchmark: texproc's encoder at each quality and, where CMake is
// given its source (-DTEXPROC_CMP_DIR=, a checkout of
// GPUOpen-Tools/compressonator outside this tree; skipped when absent),
// Compressonator's CMP_Core (CompressBlockBC6 at quality 0.1 and 1.0) and,
// with -DTEXPROC_CVTT_DIR=, cvtt (ConvectionKernels' EncodeBC6HU, default
// and with its fast indexing), in one run. Inputs: two 256x256 crops (the centre, and a quarter in from the
// top left) of each of the corpus's six HDR EXR images, UF16, one thread
// (and texproc on two). The error: log2 RMSE over RGB pooled over every
// crop, the RMSE of sign(v) log2(1 + |v|) between each texel's input half
// and its decoding (texproc's decoder, which matches Pillow's) -- about
// stops for bright values, linear near 0 (docs/compression.md says why);
// and beside it the PSNR after a fixed tone map (Reinhard, gamma 1/2.2).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <Imath/half.h>

#include "bench_common.h"
#include "texproc/block_decode.h"
#include "texproc/block_encode.h"
#include "texproc/image_io.h"
#include "texproc/runtime.h"

#ifdef TEXPROC_HAVE_CMP_CORE
#include "cmp_core.h"
#endif
#ifdef TEXPROC_HAVE_CVTT
#include "ConvectionKernels.h"
#endif

using namespace texproc;

namespace {

const char* const kHdrFiles[] = {
    "hdr/blender_world_forest.exr",          "hdr/blender_world_city.exr",
    "hdr/blender_world_courtyard.exr",       "hdr/blender_world_night.exr",
    "hdr/blender_matcap_check_normal+y.exr", "hdr/blender_matcap_metal_carpaint.exr",
};

// Each crop as f32 RGB with its values rounded to halves (what every
// encoder here is given), and the same halves' bits.
struct Crop {
  Image img;
  std::vector<std::uint16_t> half;  // RGB, row by row
};

const std::vector<Crop>& crops() {
  static const std::vector<Crop> c = [] {
    std::vector<Crop> out;
    for (const char* f : kHdrFiles) {
      const Image src = read_image(std::string(TEXPROC_CORPUS_DIR) + "/" + f);
      const int w = std::min(256, src.width() / 4 * 4), h = std::min(256, src.height() / 4 * 4);
      const int origins[2][2] = {{(src.width() - w) / 2, (src.height() - h) / 2},
                                 {src.width() / 4 - w / 2 > 0 ? src.width() / 4 - w / 2 : 0,
                                  src.height() / 4 - h / 2 > 0 ? src.height() / 4 - h / 2 : 0}};
      for (const auto& o : origins) {
        Crop cr{Image(w, h, 3, PixelType::f32), {}};
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x)
            for (int ch = 0; ch < 3; ++ch) {
              const float v = std::clamp(src.get(o[0] + x, o[1] + y, std::min(ch, src.channels() - 1)), 0.0f, 65504.0f);
              const Imath::half hv(v);
              cr.img.row<float>(y)[3 * x + ch] = float(hv);
              cr.half.push_back(hv.bits());
            }
        out.push_back(std::move(cr));
      }
    }
    return out;
  }();
  return c;
}

double log_value(double v) { return std::copysign(std::log2(1.0 + std::fabs(v)), v); }
// A second view: a fixed tone map (Reinhard's v / (1 + v), then a 1/2.2
// gamma) into [0, 1], where a PSNR means what it means for LDR images.
double tone_mapped(double v) { return std::pow(std::max(v, 0.0) / (1.0 + std::max(v, 0.0)), 1.0 / 2.2); }

struct Errors {
  double log_se = 0, tm_se = 0;
};

// The squared log and tone-mapped differences over RGB of `blocks` against the crop.
Errors squared_errors(const Crop& c, const std::vector<std::uint8_t>& blocks) {
  const int bw = c.img.width() / 4;
  Errors e;
  for (int by = 0; by < c.img.height() / 4; ++by)
    for (int bx = 0; bx < bw; ++bx) {
      float t[16][4];
      decode_block(TexelFormat::bc6h_ufloat, &blocks[(std::size_t(by) * bw + bx) * 16], t);
      for (int i = 0; i < 16; ++i)
        for (int ch = 0; ch < 3; ++ch) {
          const double v = c.img.row<const float>(4 * by + i / 4)[3 * (4 * bx + i % 4) + ch];
          const double d = log_value(t[i][ch]) - log_value(v), dt = tone_mapped(t[i][ch]) - tone_mapped(v);
          e.log_se += d * d;
          e.tm_se += dt * dt;
        }
    }
  return e;
}

#ifdef TEXPROC_HAVE_CMP_CORE
std::vector<std::uint8_t> cmp_image(const Crop& c, float quality) {
  void* options = nullptr;
  CreateOptionsBC6(&options);
  SetQualityBC6(options, quality);
  SetSignedBC6(options, false);
  const int w = c.img.width(), bw = w / 4, bh = c.img.height() / 4;
  std::vector<std::uint8_t> out(std::size_t(bw) * bh * 16);
  for (int by = 0; by < bh; ++by)
    for (int bx = 0; bx < bw; ++bx)
      CompressBlockBC6(&c.half[(std::size_t(4 * by) * w + 4 * bx) * 3], unsigned(3 * w),
                       out.data() + (std::size_t(by) * bw + bx) * 16, options);
  DestroyOptionsBC6(options);
  return out;
}
#endif

#ifdef TEXPROC_HAVE_CVTT
// cvtt's EncodeBC6HU, eight blocks a call; `fast`: its BC6H_FastIndexing flag.
std::vector<std::uint8_t> cvtt_image(const Crop& c, bool fast) {
  cvtt::Options options;
  options.flags = cvtt::Flags::Default | (fast ? cvtt::Flags::BC6H_FastIndexing : 0u);
  // Every channel weighted alike, as the metric here weighs them (cvtt's
  // default weights red and blue by luminance).
  options.redWeight = options.greenWeight = options.blueWeight = 1.0f;
  const int w = c.img.width(), bw = w / 4, n = bw * (c.img.height() / 4);
  std::vector<std::uint8_t> out(std::size_t(n) * 16);
  cvtt::PixelBlockF16 blocks[cvtt::NumParallelBlocks];
  std::uint8_t packed[cvtt::NumParallelBlocks * 16];
  for (int b0 = 0; b0 < n; b0 += int(cvtt::NumParallelBlocks)) {
    for (int k = 0; k < int(cvtt::NumParallelBlocks); ++k) {
      const int b = std::min(b0 + k, n - 1), bx = b % bw, by = b / bw;
      for (int i = 0; i < 16; ++i) {
        for (int ch = 0; ch < 3; ++ch)
          blocks[k].m_pixels[i][ch] =
              std::int16_t(c.half[(std::size_t(4 * by + i / 4) * w + 4 * bx + i % 4) * 3 + std::size_t(ch)]);
        blocks[k].m_pixels[i][3] = 0x3C00;  // 1.0
      }
    }
    cvtt::Kernels::EncodeBC6HU(packed, blocks, options);
    for (int k = 0; k < int(cvtt::NumParallelBlocks) && b0 + k < n; ++k)
      std::memcpy(&out[std::size_t(b0 + k) * 16], packed + 16 * k, 16);
  }
  return out;
}
#endif

// who: "texproc" (quality, threads), "cmp" (its quality) or "cvtt" (quality > 0: not fast).
void run(benchmark::State& state, const std::string& who, Quality q, int threads, float cmp_quality) {
  ThreadLimit limit(threads);
  double se = 0, tm = 0, samples = 0;
  for (auto _ : state) {
    se = tm = samples = 0;
    for (const Crop& c : crops()) {
      std::vector<std::uint8_t> blocks;
#ifdef TEXPROC_HAVE_CMP_CORE
      if (who == "cmp") blocks = cmp_image(c, cmp_quality);
#endif
#ifdef TEXPROC_HAVE_CVTT
      if (who == "cvtt") blocks = cvtt_image(c, cmp_quality == 0.0f);
#endif
      (void)cmp_quality;
      if (who == "texproc") blocks = compress_image(c.img.view(), TexelFormat::bc6h_ufloat, q);
      benchmark::DoNotOptimize(blocks.data());
      state.PauseTiming();
      const Errors e = squared_errors(c, blocks);
      se += e.log_se;
      tm += e.tm_se;
      samples += 3.0 * c.img.width() * c.img.height();
      state.ResumeTiming();
    }
  }
  double pixels = 0;
  for (const Crop& c : crops()) pixels += double(c.img.width()) * c.img.height();
  state.counters["MPix/s"] = benchmark::Counter(pixels / 1e6, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["logRMSE"] = std::sqrt(se / samples);
  state.counters["tmPSNR"] = 10 * std::log10(samples / tm);
}

void register_all() {
  for (Quality q : {Quality::fast, Quality::normal, Quality::high, Quality::max})
    benchmark::RegisterBenchmark((std::string("bc6h/texproc/") + to_string(q)).c_str(), run, "texproc", q, 1, 0.0f)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->MinTime(q == Quality::max ? 0.1 : 1.0);
  for (Quality q : {Quality::fast, Quality::normal})
    benchmark::RegisterBenchmark((std::string("bc6h/texproc/") + to_string(q) + "/threads:2").c_str(), run, "texproc",
                                 q, 2, 0.0f)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
#ifdef TEXPROC_HAVE_CMP_CORE
  for (float cq : {0.1f, 1.0f})
    benchmark::RegisterBenchmark((std::string("bc6h/cmp_core/q") + (cq < 1.0f ? "0.1" : "1.0")).c_str(), run, "cmp",
                                 Quality::normal, 1, cq)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->MinTime(0.1);
#endif
#ifdef TEXPROC_HAVE_CVTT
  benchmark::RegisterBenchmark("bc6h/cvtt/fast_indexing", run, "cvtt", Quality::normal, 1, 0.0f)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime()
      ->MinTime(0.1);
  benchmark::RegisterBenchmark("bc6h/cvtt/default", run, "cvtt", Quality::normal, 1, 1.0f)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime()
      ->MinTime(0.1);
#endif
}

}  // namespace

int main(int argc, char** argv) {
  crops();  // read and cut before any timing (the first benchmark would pay for it)
  register_all();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
