// Block-compressed levels back to texels, for the encoder tests.
#pragma once

#include <cstdint>
#include <vector>

#include "texproc/block_decode.h"
#include "texproc/block_encode.h"
#include "texproc/image.h"
#include "texproc/texture.h"

namespace texproc::test {

// One level of `blocks` (format f, width x height texels) decoded to `type`.
inline Image decode_blocks(int width, int height, TexelFormat f, std::vector<std::uint8_t> blocks, PixelType type) {
  Texture t;
  t.format = f;
  t.width = std::uint32_t(width);
  t.height = std::uint32_t(height);
  t.images.push_back(std::move(blocks));
  return decode_texture_image(t, 0, 0, 0, type);
}

// `img` compressed to f at q (with `options`), then decoded to `type`.
inline Image round_trip(const Image& img, TexelFormat f, Quality q, PixelType type, const EncodeOptions& options = {}) {
  return decode_blocks(img.width(), img.height(), f, compress_image(img.view(), f, q, options), type);
}

}  // namespace texproc::test
