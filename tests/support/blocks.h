// Images through an encoder and back, for the encoder tests.
#pragma once

#include <cstdint>
#include <vector>

#include "texproc/block_decode.h"
#include "texproc/block_encode.h"
#include "texproc/image.h"

namespace texproc::test {

// `img` compressed to f at q (with `options`), then decoded to `type`.
inline Image round_trip(const Image& img, TexelFormat f, Quality q, PixelType type, const EncodeOptions& options = {}) {
  return decompress_image(compress_image(img.view(), f, q, options), img.width(), img.height(), f, type);
}

}  // namespace texproc::test
