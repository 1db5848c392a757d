// ASTC decoding through ARM's astc-encoder (libastcenc), loaded with dlopen
// the first time an ASTC texture is decoded (astc_codec.cpp). Depends on
// nothing of the encoders.
#pragma once

#include <cstddef>
#include <cstdint>

#include "texproc/image.h"
#include "texproc/texture.h"

namespace texproc::astc {

// Decodes a width x height image of `format` blocks to RGBA: u8 for the LDR
// formats (what the decode_unorm8 path returns: astcenc -dl's pixels), f32
// for SFLOAT. `blocks` holds image_bytes(format, width, height) bytes.
Image decode(const std::uint8_t* blocks, std::size_t size, int width, int height, TexelFormat format);

// True when a block of the image uses HDR endpoints (or is an HDR
// constant-colour block): containers that do not record the profile (.astc,
// KTX1) hold LDR and HDR textures under one code.
bool has_hdr_blocks(const std::uint8_t* blocks, std::size_t size, int block_width, int block_height);

}  // namespace texproc::astc
