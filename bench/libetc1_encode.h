// Android's ETC1 encoder (Debian's android-libetc1-dev, the library behind
// etc1tool) on an RGBA8 image: the peer of texproc's ETC1 in the benchmarks.
#pragma once

#include <etc1.h>

#include <cstdint>
#include <vector>

#include "texproc/image.h"

namespace texproc::bench {

// ETC1 blocks of the RGB of `img` (RGBA8, width and height multiples of 4).
inline std::vector<std::uint8_t> libetc1_encode(const Image& img) {
  std::vector<std::uint8_t> rgb(std::size_t(img.width()) * img.height() * 3);
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x)
      for (int c = 0; c < 3; ++c) rgb[(std::size_t(y) * img.width() + x) * 3 + c] = img.row<std::uint8_t>(y)[4 * x + c];
  std::vector<std::uint8_t> out(etc1_get_encoded_data_size(etc1_uint32(img.width()), etc1_uint32(img.height())));
  etc1_encode_image(rgb.data(), etc1_uint32(img.width()), etc1_uint32(img.height()), 3, etc1_uint32(img.width() * 3),
                    out.data());
  return out;
}

}  // namespace texproc::bench
