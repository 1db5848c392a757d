// Block decoding speed: texproc's decompress_image (8-bit output; BC6H to
// floats) for every block format on one thread, and, where CMake is given
// its header (-DTEXPROC_BCDEC_DIR=, a checkout of iOrange/bcdec outside this
// tree; skipped when absent), bcdec's BC1-BC7 block decoders writing the
// same image, and with -DTEXPROC_RG_ETC1_DIR= rg_etc1's ETC1 unpacker, in one run. The blocks: bench_common.h's six colour crops
// (1.4 MPix), encoded once at `fast`.
#include <benchmark/benchmark.h>

#include <map>
#include <string>
#include <vector>

#include "bench_common.h"
#include "texproc/block_decode.h"
#include "texproc/block_encode.h"
#include "texproc/runtime.h"

#ifdef TEXPROC_HAVE_BCDEC
#define BCDEC_IMPLEMENTATION
#include "bcdec.h"
#endif
#ifdef TEXPROC_HAVE_RG_ETC1
#include <cstring>

#include "rg_etc1.h"
#endif

using namespace texproc;

namespace {

struct Encoded {
  int width, height;
  std::vector<std::uint8_t> blocks;
};

const std::vector<Encoded>& encoded(TexelFormat f) {
  static std::map<TexelFormat, std::vector<Encoded>> cache;
  auto it = cache.find(f);
  if (it != cache.end()) return it->second;
  std::vector<Encoded> out;
  for (const Image& img : bench::color_textures()) {
    out.push_back({img.width(), img.height(), compress_image(img.view(), f, Quality::fast)});  // BC6H: the 8-bit colour as [0, 1]
  }
  return cache.emplace(f, std::move(out)).first->second;
}

void run_texproc(benchmark::State& state, TexelFormat f) {
  const auto& e = encoded(f);  // before timing: the first call encodes
  ThreadLimit one(1);
  const PixelType type = format_info(f).is_float ? PixelType::f32 : PixelType::u8;
  double pixels = 0;
  for (const Encoded& x : e) pixels += double(x.width) * x.height;
  for (auto _ : state)
    for (const Encoded& x : e) {
      Image img = decompress_image(x.blocks, x.width, x.height, f, type);
      benchmark::DoNotOptimize(img.data());
    }
  state.counters["MPix/s"] = benchmark::Counter(pixels / 1e6, benchmark::Counter::kIsIterationInvariantRate);
}

#ifdef TEXPROC_HAVE_BCDEC
void run_bcdec(benchmark::State& state, TexelFormat f) {
  const auto& e = encoded(f);
  using F = TexelFormat;
  const int bytes = f == F::bc4_unorm ? 1 : f == F::bc5_unorm ? 2 : f == F::bc6h_ufloat ? 6 : 4;
  const int block = format_info(f).block_bytes;
  double pixels = 0;
  for (const Encoded& x : e) pixels += double(x.width) * x.height;
  for (auto _ : state)
    for (const Encoded& x : e) {
      std::vector<std::uint8_t> img(std::size_t(x.width) * x.height * bytes);
      const int pitch = x.width * bytes, bw = x.width / 4;
      for (int by = 0; by < x.height / 4; ++by)
        for (int bx = 0; bx < bw; ++bx) {
          const std::uint8_t* src = x.blocks.data() + (std::size_t(by) * bw + bx) * block;
          std::uint8_t* dst = img.data() + std::size_t(4 * by) * pitch + std::size_t(4 * bx) * bytes;
          switch (f) {
            case F::bc1_rgb_unorm: bcdec_bc1(src, dst, pitch); break;
            case F::bc3_unorm: bcdec_bc3(src, dst, pitch); break;
            case F::bc4_unorm: bcdec_bc4(src, dst, pitch); break;
            case F::bc5_unorm: bcdec_bc5(src, dst, pitch); break;
            case F::bc6h_ufloat: bcdec_bc6h_half(src, dst, pitch / 2, 0); break;
            default: bcdec_bc7(src, dst, pitch); break;
          }
        }
      benchmark::DoNotOptimize(img.data());
    }
  state.counters["MPix/s"] = benchmark::Counter(pixels / 1e6, benchmark::Counter::kIsIterationInvariantRate);
}
#endif

#ifdef TEXPROC_HAVE_RG_ETC1
// rg_etc1's block unpacker (RGBA, 16 texels in a row), each block copied into an RGBA image.
void run_rg_etc1(benchmark::State& state) {
  const auto& e = encoded(TexelFormat::etc1_rgb);
  double pixels = 0;
  for (const Encoded& x : e) pixels += double(x.width) * x.height;
  for (auto _ : state)
    for (const Encoded& x : e) {
      std::vector<std::uint8_t> img(std::size_t(x.width) * x.height * 4);
      const int pitch = x.width * 4, bw = x.width / 4;
      unsigned int px[16];
      for (int by = 0; by < x.height / 4; ++by)
        for (int bx = 0; bx < bw; ++bx) {
          rg_etc1::unpack_etc1_block(x.blocks.data() + (std::size_t(by) * bw + bx) * 8, px);
          for (int r = 0; r < 4; ++r) std::memcpy(img.data() + std::size_t(4 * by + r) * pitch + std::size_t(16 * bx), px + 4 * r, 16);
        }
      benchmark::DoNotOptimize(img.data());
    }
  state.counters["MPix/s"] = benchmark::Counter(pixels / 1e6, benchmark::Counter::kIsIterationInvariantRate);
}
#endif

void register_all() {
  using F = TexelFormat;
  for (F f : {F::bc1_rgb_unorm, F::bc3_unorm, F::bc4_unorm, F::bc5_unorm, F::bc6h_ufloat, F::bc7_unorm, F::etc1_rgb, F::etc2_rgb_unorm,
              F::etc2_rgba8_unorm, F::eac_r11_unorm, F::eac_rg11_unorm}) {
    benchmark::RegisterBenchmark((std::string("decode/texproc/") + format_info(f).name).c_str(), run_texproc, f)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
#ifdef TEXPROC_HAVE_RG_ETC1
    if (f == F::etc1_rgb)
      benchmark::RegisterBenchmark("decode/rg_etc1/etc1_rgb", run_rg_etc1)->Unit(benchmark::kMillisecond)->UseRealTime();
#endif
#ifdef TEXPROC_HAVE_BCDEC
    if (f <= F::bc7_unorm && f != F::etc1_rgb)
      benchmark::RegisterBenchmark((std::string("decode/bcdec/") + format_info(f).name).c_str(), run_bcdec, f)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
#endif
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
