// The C++ side of bench/bench_python.py: one library call timed in-process,
// as a C++ program calls it, so that the Python binding's overhead over the
// same call on the same pixels can be measured.
//
//   bench_calls bc7|mips IMAGE ROUNDS
//
// Reads IMAGE, runs the call once to warm up (thread pool, caches), then
// ROUNDS times, and prints each round's milliseconds, one per line.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "texproc/block_encode.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/mip.h"
#include "texproc/texture.h"

namespace {

using Clock = std::chrono::steady_clock;

// What texproc.compress(image, "bc7_srgb") does: normal quality, one level.
std::size_t run_bc7(const texproc::Image& image) {
  std::vector<std::vector<texproc::Image>> chains(1);
  chains[0].push_back(image);  // the Python call copies its input likewise
  const texproc::Texture t = texproc::compress_texture(chains, {}, texproc::parse_texel_format("bc7_srgb"),
                                                       texproc::Quality::normal, texproc::TextureEncodeOptions{});
  return t.images.size();
}

// What texproc.generate_mips(image) does: a Gaussian chain with the defaults.
std::size_t run_mips(const texproc::Image& image) {
  const texproc::MipChain chain = texproc::generate_mips(image.view(), texproc::MipOptions{});
  return chain.levels.size();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: bench_calls bc7|mips IMAGE ROUNDS\n");
    return 2;
  }
  const std::string op = argv[1];
  const int rounds = std::atoi(argv[3]);
  if ((op != "bc7" && op != "mips") || rounds < 1) {
    std::fprintf(stderr, "bench_calls: bad arguments\n");
    return 2;
  }
  try {
    const texproc::Image image = texproc::read_image(argv[2]);
    auto once = [&] { return op == "bc7" ? run_bc7(image) : run_mips(image); };
    std::size_t sink = once();
    for (int i = 0; i < rounds; ++i) {
      const auto t0 = Clock::now();
      sink += once();
      const std::chrono::duration<double, std::milli> ms = Clock::now() - t0;
      std::printf("%.3f\n", ms.count());
    }
    return sink == 0 ? 1 : 0;
  } catch (const texproc::Error& e) {
    std::fprintf(stderr, "bench_calls: %s\n", e.what());
    return 1;
  }
}
