// Block decoding speed: texproc's decompress_image (8-bit output; BC6H to
// floats) for every block format on one thread, and, where CMake is given
// its header (-DTEXPROC_BCDEC_DIR=, a checkout of iOrange/bcdec outside this
// tree; skipped when absent), bcdec's BC1-BC7 block decoders writing the
// same image (BC6H as floats, as decompress_image writes it, and as bcdec's
// own halves), with -DTEXPROC_RG_ETC1_DIR= rg_etc1's ETC1 unpacker, and with
// -DTEXPROC_ETCPAK_DIR= etcpak's image decoders (BC1-BC5, BC7 through its copy
// of bcdec, ETC1/ETC2 RGB and RGBA, EAC R11/RG11; every one writes 32-bit RGBA
// texels), in one run. The blocks: bench_common.h's six colour crops (1.4
// MPix), encoded once at `fast`.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
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
#include "rg_etc1.h"
#endif
#ifdef TEXPROC_HAVE_ETCPAK
#include "Decode.hpp"
#endif

using namespace texproc;

namespace {

// An IEEE half's bits as a float (BC6H's texels, as bcdec writes them).
float half_bits_to_float(std::uint16_t h) {
  const int sign = h >> 15, exponent = h >> 10 & 31, mantissa = h & 1023;
  float v;
  if (exponent == 0) {
    v = std::ldexp(float(mantissa), -24);
  } else if (exponent == 31) {
    v = mantissa ? std::numeric_limits<float>::quiet_NaN() : std::numeric_limits<float>::infinity();
  } else {
    v = std::ldexp(float(mantissa | 1024), exponent - 25);
  }
  return sign ? -v : v;
}

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
    out.push_back(
        {img.width(), img.height(), compress_image(img.view(), f, Quality::fast)});  // BC6H: the 8-bit colour as [0, 1]
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

// A peer's decoder: one image's blocks into `img`, `bytes` a texel.
using PeerDecode = void (*)(TexelFormat f, const Encoded& x, std::vector<std::uint8_t>& img);

// The share of channel values where a peer's image equals texproc's
// decompress_image (the channels both write; BC6H's halves as floats): 1
// where the peer decodes the same texels, less where it rounds otherwise or
// leaves texels out.
double agreement(TexelFormat f, PeerDecode decode, int bytes) {
  const bool hdr = format_info(f).is_float;
  std::size_t equal = 0, total = 0;
  for (const Encoded& x : encoded(f)) {
    const Image ours = decompress_image(x.blocks, x.width, x.height, f, hdr ? PixelType::f32 : PixelType::u8);
    std::vector<std::uint8_t> img(std::size_t(x.width) * x.height * bytes);
    decode(f, x, img);
    const int c = hdr ? 3 : std::min(ours.channels(), bytes);
    for (int y = 0; y < x.height; ++y)
      for (int i = 0; i < x.width; ++i)
        for (int k = 0; k < c; ++k) {
          const std::size_t at = std::size_t(y) * x.width + i;
          bool same;
          if (hdr) {  // 6 bytes a texel: halves; 12: floats
            float theirs;
            if (bytes == 6) {
              std::uint16_t h;
              std::memcpy(&h, img.data() + at * bytes + 2 * k, 2);
              theirs = half_bits_to_float(h);
            } else {
              std::memcpy(&theirs, img.data() + at * bytes + 4 * k, 4);
            }
            same = ours.row<float>(y)[std::size_t(i) * ours.channels() + k] == theirs;
          } else {
            same = ours.row<std::uint8_t>(y)[std::size_t(i) * ours.channels() + k] == img[at * bytes + k];
          }
          equal += same;
          ++total;
        }
  }
  return total ? double(equal) / double(total) : 0.0;
}

[[maybe_unused]] void run_peer(benchmark::State& state, TexelFormat f, PeerDecode decode, int bytes) {
  const auto& e = encoded(f);
  double pixels = 0;
  for (const Encoded& x : e) pixels += double(x.width) * x.height;
  for (auto _ : state)
    for (const Encoded& x : e) {
      std::vector<std::uint8_t> img(std::size_t(x.width) * x.height * bytes);
      decode(f, x, img);
      benchmark::DoNotOptimize(img.data());
    }
  state.counters["MPix/s"] = benchmark::Counter(pixels / 1e6, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["equal"] = agreement(f, decode, bytes);
}

#ifdef TEXPROC_HAVE_BCDEC
int bcdec_bytes(TexelFormat f) {
  using F = TexelFormat;
  return f == F::bc4_unorm ? 1 : f == F::bc5_unorm ? 2 : f == F::bc6h_ufloat ? 12 : 4;
}

// BC6H as halves (6 bytes a texel), bcdec's own output; the floats above
// (bcdec_bc6h_float, its halves converted) are what decompress_image gives.
void bcdec_bc6h_halves(TexelFormat, const Encoded& x, std::vector<std::uint8_t>& img) {
  const int pitch = x.width * 6, bw = x.width / 4;
  for (int by = 0; by < x.height / 4; ++by)
    for (int bx = 0; bx < bw; ++bx)
      bcdec_bc6h_half(x.blocks.data() + (std::size_t(by) * bw + bx) * 16,
                      img.data() + std::size_t(4 * by) * pitch + std::size_t(24 * bx), pitch / 2, 0);
}

void bcdec_image(TexelFormat f, const Encoded& x, std::vector<std::uint8_t>& img) {
  using F = TexelFormat;
  const int bytes = bcdec_bytes(f), block = format_info(f).block_bytes;
  const int pitch = x.width * bytes, bw = x.width / 4;
  for (int by = 0; by < x.height / 4; ++by)
    for (int bx = 0; bx < bw; ++bx) {
      const std::uint8_t* src = x.blocks.data() + (std::size_t(by) * bw + bx) * block;
      std::uint8_t* dst = img.data() + std::size_t(4 * by) * pitch + std::size_t(4 * bx) * bytes;
      switch (f) {
        case F::bc1_rgb_unorm:
          bcdec_bc1(src, dst, pitch);
          break;
        case F::bc2_unorm:
          bcdec_bc2(src, dst, pitch);
          break;
        case F::bc3_unorm:
          bcdec_bc3(src, dst, pitch);
          break;
        case F::bc4_unorm:
          bcdec_bc4(src, dst, pitch);
          break;
        case F::bc5_unorm:
          bcdec_bc5(src, dst, pitch);
          break;
        case F::bc6h_ufloat:
          bcdec_bc6h_float(src, dst, pitch / 4, 0);
          break;
        default:
          bcdec_bc7(src, dst, pitch);
          break;
      }
    }
}
#endif

#ifdef TEXPROC_HAVE_RG_ETC1
// rg_etc1's block unpacker (RGBA, 16 texels in a row), each block copied into an RGBA image.
void rg_etc1_image(TexelFormat, const Encoded& x, std::vector<std::uint8_t>& img) {
  const int pitch = x.width * 4, bw = x.width / 4;
  unsigned int px[16];
  for (int by = 0; by < x.height / 4; ++by)
    for (int bx = 0; bx < bw; ++bx) {
      rg_etc1::unpack_etc1_block(x.blocks.data() + (std::size_t(by) * bw + bx) * 8, px);
      for (int r = 0; r < 4; ++r)
        std::memcpy(img.data() + std::size_t(4 * by + r) * pitch + std::size_t(16 * bx), px + 4 * r, 16);
    }
}
#endif

#ifdef TEXPROC_HAVE_ETCPAK
// etcpak's whole-image decoders (blocks read as 64-bit words, RGBA out).
bool etcpak_decodes(TexelFormat f) { return f != TexelFormat::bc6h_ufloat && f != TexelFormat::bc2_unorm; }

void etcpak_image(TexelFormat f, const Encoded& x, std::vector<std::uint8_t>& bytes) {
  using F = TexelFormat;
  const auto* src = reinterpret_cast<const std::uint64_t*>(x.blocks.data());
  auto* img = reinterpret_cast<std::uint32_t*>(bytes.data());
  switch (f) {
    case F::bc1_rgb_unorm:
      DecodeBc1(src, img, x.width, x.height);
      break;
    case F::bc3_unorm:
      DecodeBc3(src, img, x.width, x.height);
      break;
    case F::bc4_unorm:
      DecodeBc4(src, img, x.width, x.height);
      break;
    case F::bc5_unorm:
      DecodeBc5(src, img, x.width, x.height);
      break;
    case F::bc7_unorm:
      DecodeBc7(src, img, x.width, x.height);
      break;
    case F::etc2_rgba8_unorm:
      DecodeRGBA(src, img, x.width, x.height);
      break;
    case F::eac_r11_unorm:
      DecodeR(src, img, x.width, x.height);
      break;
    case F::eac_rg11_unorm:
      DecodeRG(src, img, x.width, x.height);
      break;
    default:
      DecodeRGB(src, img, x.width, x.height);
      break;  // ETC1 and ETC2 RGB
  }
}
#endif

void register_all() {
  using F = TexelFormat;
  for (F f : {F::bc1_rgb_unorm, F::bc2_unorm, F::bc3_unorm, F::bc4_unorm, F::bc5_unorm, F::bc6h_ufloat, F::bc7_unorm,
              F::etc1_rgb, F::etc2_rgb_unorm, F::etc2_rgba8_unorm, F::eac_r11_unorm, F::eac_rg11_unorm}) {
    benchmark::RegisterBenchmark((std::string("decode/texproc/") + format_info(f).name).c_str(), run_texproc, f)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
#ifdef TEXPROC_HAVE_RG_ETC1
    if (f == F::etc1_rgb)
      benchmark::RegisterBenchmark("decode/rg_etc1/etc1_rgb", run_peer, f, rg_etc1_image, 4)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
#endif
#ifdef TEXPROC_HAVE_ETCPAK
    if (etcpak_decodes(f))
      benchmark::RegisterBenchmark((std::string("decode/etcpak/") + format_info(f).name).c_str(), run_peer, f,
                                   etcpak_image, 4)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
#endif
#ifdef TEXPROC_HAVE_BCDEC
    if (f <= F::bc7_unorm && f != F::etc1_rgb)
      benchmark::RegisterBenchmark((std::string("decode/bcdec/") + format_info(f).name).c_str(), run_peer, f,
                                   bcdec_image, bcdec_bytes(f))
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    if (f == F::bc6h_ufloat)
      benchmark::RegisterBenchmark("decode/bcdec_halves/bc6h_ufloat", run_peer, f, bcdec_bc6h_halves, 6)
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
