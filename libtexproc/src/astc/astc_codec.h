// ASTC through ARM's astc-encoder (libastcenc), loaded with dlopen the first
// time an ASTC texture is encoded or decoded, so that no other run maps it.
// texproc writes no ASTC search of its own: this file feeds the library
// texproc's images and threads and keeps its contexts for reuse.
#pragma once

#include <cstddef>
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
std::vector<std::uint8_t> encode(const ImageView& image, TexelFormat format, Quality q, const EncodeOptions& options);

// Decodes a width x height image of `format` blocks to RGBA: u8 for the LDR
// formats (what the decode_unorm8 path returns: astcenc -dl's pixels), f32
// for SFLOAT. `blocks` holds image_bytes(format, width, height) bytes.
Image decode(const std::uint8_t* blocks, std::size_t size, int width, int height, TexelFormat format);

// True when a block of the image uses HDR endpoints (or is an HDR
// constant-colour block): containers that do not record the profile (.astc,
// KTX1) hold LDR and HDR textures under one code.
bool has_hdr_blocks(const std::uint8_t* blocks, std::size_t size, int block_width, int block_height);

}  // namespace texproc::astc
