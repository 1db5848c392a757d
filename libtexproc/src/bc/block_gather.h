// Reading an image's texels as the block encoders take them.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "texproc/image.h"

namespace texproc {

// The stored value of channel c (0..3 of RGBA) as 8 bits: gray fills RGB, no
// alpha is 255; 16-bit and float values are rounded.
inline std::uint8_t texel8(const ImageView& img, int x, int y, int c) {
  const int C = img.channels;
  int src = c;
  if (C <= 2 && c < 3) src = 0;
  if (c == 3) src = (C == 2 || C == 4) ? C - 1 : -1;
  if (src < 0) return 255;
  switch (img.type) {
    case PixelType::u8: return img.row<const std::uint8_t>(y)[x * C + src];
    case PixelType::u16: return std::uint8_t((img.row<const std::uint16_t>(y)[x * C + src] * 255 + 32767) / 65535);
    case PixelType::f32:
      return std::uint8_t(std::lround(std::clamp(img.row<const float>(y)[x * C + src], 0.0f, 1.0f) * 255.0f));
  }
  return 0;
}

// Channel c of texel (x, y) as data in [0, 1] (0 for a channel the image lacks).
inline float texel_unit(const ImageView& img, int x, int y, int c) {
  if (c >= img.channels) return 0.0f;
  switch (img.type) {
    case PixelType::u8: return img.row<const std::uint8_t>(y)[x * img.channels + c] / 255.0f;
    case PixelType::u16: return img.row<const std::uint16_t>(y)[x * img.channels + c] / 65535.0f;
    case PixelType::f32: return std::clamp(img.row<const float>(y)[x * img.channels + c], 0.0f, 1.0f);
  }
  return 0.0f;
}

}  // namespace texproc
