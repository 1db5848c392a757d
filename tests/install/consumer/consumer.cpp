// A program that uses an installed libtexproc: a mip chain of a generated
// 64x48 RGB image, BC1 of level 0, decoded again and compared. Exit 0 when
// every figure is as expected; prints what is not.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "texproc/block_decode.h"
#include "texproc/block_encode.h"
#include "texproc/image_io.h"
#include "texproc/metrics.h"
#include "texproc/mip.h"
#include "texproc/version.h"

static_assert(TEXPROC_VERSION == TEXPROC_VERSION_MAJOR * 10000 + TEXPROC_VERSION_MINOR * 100 + TEXPROC_VERSION_PATCH);

int main(int argc, char** argv) {
  using namespace texproc;
  const std::string header = std::to_string(TEXPROC_VERSION_MAJOR) + "." + std::to_string(TEXPROC_VERSION_MINOR) + "." +
                             std::to_string(TEXPROC_VERSION_PATCH);
  if (header != version_string()) {
    std::printf("headers %s, library %s\n", header.c_str(), version_string());
    return 1;
  }
  Image img(64, 48, 3, PixelType::u8);
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      std::uint8_t* p = img.row<std::uint8_t>(y) + 3 * x;
      p[0] = std::uint8_t(x * 4);
      p[1] = std::uint8_t(y * 5);
      p[2] = std::uint8_t(128);
    }
  const MipChain chain = generate_mips(img.view(), MipOptions{});
  if (chain.levels.size() != 7 || chain.levels[6].width() != 1 || chain.levels[6].height() != 1) {
    std::printf("mip chain: %zu levels\n", chain.levels.size());
    return 1;
  }
  const std::vector<std::uint8_t> blocks = compress_image(img.view(), TexelFormat::bc1_rgb_unorm, Quality::normal);
  if (blocks.size() != std::size_t(16 * 12) * 8) {
    std::printf("bc1: %zu bytes\n", blocks.size());
    return 1;
  }
  const Image back = decompress_image(blocks, 64, 48, TexelFormat::bc1_rgb_unorm, PixelType::u8);
  const ImageDifference m = compare_images(img.view(), back.view());
  if (!(m.psnr() > 35.0)) {
    std::printf("bc1 round trip: %.2f dB\n", m.psnr());
    return 1;
  }
  // An OpenEXR file goes through the runtime module: it must be found.
  if (argc > 1) {
    write_image(argv[1], chain.levels[1].view());
    const Image again = read_image(argv[1]);
    if (again.width() != 32 || again.height() != 24) return 1;
  }
  std::printf("texproc %s: %zu levels, BC1 %.2f dB\n", version_string(), chain.levels.size(), m.psnr());
  return 0;
}
