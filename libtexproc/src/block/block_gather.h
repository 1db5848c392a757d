// Reading an image's texels as the block encoders take them.
#pragma once

#include "core/block_batch.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "texproc/image.h"

namespace texproc {

// The stored value of channel c (0..3 of RGBA) as 8 bits: gray fills RGB, no
// alpha is 255; 16-bit and float values are rounded.
inline std::uint8_t texel8(const ConstImageView& img, int x, int y, int c) {
  const int C = img.channels;
  int src = c;
  if (C <= 2 && c < 3) src = 0;
  if (c == 3) src = (C == 2 || C == 4) ? C - 1 : -1;
  if (src < 0) return 255;
  switch (img.type) {
    case PixelType::u8:
      return img.row<const std::uint8_t>(y)[x * C + src];
    case PixelType::u16:
      return std::uint8_t((img.row<const std::uint16_t>(y)[x * C + src] * 255 + 32767) / 65535);
    case PixelType::f32:
      return std::uint8_t(std::lround(std::clamp(img.row<const float>(y)[x * C + src], 0.0f, 1.0f) * 255.0f));
  }
  return 0;
}

// Channel c of texel (x, y) as data in [0, 1] (0 for a channel the image lacks).
inline float texel_unit(const ConstImageView& img, int x, int y, int c) {
  if (c >= img.channels) return 0.0f;
  switch (img.type) {
    case PixelType::u8:
      return img.row<const std::uint8_t>(y)[x * img.channels + c] / 255.0f;
    case PixelType::u16:
      return img.row<const std::uint16_t>(y)[x * img.channels + c] / 65535.0f;
    case PixelType::f32:
      return std::clamp(img.row<const float>(y)[x * img.channels + c], 0.0f, 1.0f);
  }
  return 0.0f;
}

}  // namespace texproc

namespace texproc {

// The 4x4 block at block coordinates (bx, by) as RGBA8 texels, row by row;
// texels past the image's right and bottom edges repeat the edge texels.
inline void gather_rgba8(const ConstImageView& img, int bx, int by, std::uint8_t rgba[16][4]) {
  const int x0 = bx * 4, y0 = by * 4;
  if (img.type == PixelType::u8 && img.channels == 4 && x0 + 4 <= img.width && y0 + 4 <= img.height) {
    for (int y = 0; y < 4; ++y) std::memcpy(rgba[4 * y], img.row<const std::uint8_t>(y0 + y) + 4 * x0, 16);
    return;
  }
  if (img.type == PixelType::u8 && img.channels == 3 && x0 + 4 <= img.width && y0 + 4 <= img.height) {
    for (int y = 0; y < 4; ++y) {
      const std::uint8_t* src = img.row<const std::uint8_t>(y0 + y) + 3 * x0;
      for (int x = 0; x < 4; ++x) {
        std::uint8_t* dst = rgba[4 * y + x];
        dst[0] = src[3 * x];
        dst[1] = src[3 * x + 1];
        dst[2] = src[3 * x + 2];
        dst[3] = 255;
      }
    }
    return;
  }
  for (int i = 0; i < 16; ++i) {
    const int x = std::min(x0 + i % 4, img.width - 1), y = std::min(y0 + i / 4, img.height - 1);
    for (int c = 0; c < 4; ++c) rgba[i][c] = texel8(img, x, y, c);
  }
}

// Block encoders that work on sixteen blocks at a time take their texels
// as texel[i][k]: texel i (row by row) of block k, R | G << 8 | B << 16 |
// A << 24 (only BC1 with punch-through alpha reads A). kBlockBatch: core/block_batch.h.

// Whether block k's texels (R | G << 8 | B << 16 | A << 24) hold exactly
// two RGB colours, alpha aside; `a` gets texel 0's, `b` the other.
inline bool two_colours(const std::uint32_t texel[16][kBlockBatch], int k, std::uint32_t* a = nullptr,
                        std::uint32_t* b = nullptr) {
  const std::uint32_t first = texel[0][k] & 0xFFFFFF;
  std::uint32_t second = first;
  for (int i = 1; i < 16; ++i) {
    const std::uint32_t t = texel[i][k] & 0xFFFFFF;
    if (t == first || t == second) continue;
    if (second != first) return false;  // a third colour
    second = t;
  }
  if (a) *a = first;
  if (b) *b = second;
  return second != first;
}

// Whether block k's texels are one RGB colour and, with `opaque`, none has
// alpha under 128 (punch-through's transparent texels); `rgb` gets it.
inline bool one_colour(const std::uint32_t texel[16][kBlockBatch], int k, bool opaque, std::uint32_t* rgb = nullptr) {
  const std::uint32_t first = texel[0][k];
  for (int i = 0; i < 16; ++i)
    if ((texel[i][k] & 0xFFFFFF) != (first & 0xFFFFFF) || (opaque && (texel[i][k] >> 24) < 128)) return false;
  if (rgb) *rgb = first & 0xFFFFFF;
  return true;
}

inline std::uint32_t pack_texel(const std::uint8_t px[4]) {
  return std::uint32_t(px[0]) | std::uint32_t(px[1]) << 8 | std::uint32_t(px[2]) << 16 | std::uint32_t(px[3]) << 24;
}

// The `count` blocks from (bx0, by) straight from the rows of an RGBA8
// image. False, and nothing read, where that
// does not apply: another layout, or a block past the image's edges.
inline bool gather_rows_rgba8(const ConstImageView& img, int bx0, int by, int count,
                              std::uint32_t texel[16][kBlockBatch]) {
  if (img.type != PixelType::u8 || img.channels != 4 || (bx0 + count) * 4 > img.width || by * 4 + 4 > img.height)
    return false;
  for (int y = 0; y < 4; ++y) {
    const std::uint8_t* row = img.row<const std::uint8_t>(by * 4 + y) + bx0 * 16;
    for (int k = 0; k < count; ++k)
      for (int x = 0; x < 4; ++x) std::memcpy(&texel[4 * y + x][k], row + 16 * k + 4 * x, 4);
  }
  return true;
}

}  // namespace texproc
