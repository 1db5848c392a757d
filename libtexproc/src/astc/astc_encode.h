// ASTC encoding through ARM's astc-encoder (libastcenc), loaded with dlopen
// the first time an ASTC texture is encoded, so that no other run maps it.
// texproc writes no ASTC search of its own: astc_codec.cpp feeds the library
// texproc's images and threads and keeps its contexts for reuse.
#pragma once

#include <cstdint>
#include <vector>

#include "texproc/block_encode.h"
#include "texproc/image.h"
#include "texproc/texture.h"

namespace texproc::astc {

// astc-encoder's effort (its "quality", 0-100) for a texproc quality level:
// fast 10 (-fast), normal 60 (-medium), high 98 (-thorough), max 100
// (-exhaustive); docs/compression.md has the measured cost and gain of each.
float effort_for(Quality q);

// Encodes an image to `format` (any ASTC format), as compress_image
// documents. Bytes are the same for any thread count.
std::vector<std::uint8_t> encode(const ConstImageView& image, TexelFormat format, Quality q,
                                 const EncodeOptions& options);

}  // namespace texproc::astc
