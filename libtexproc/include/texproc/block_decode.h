// texproc/block_decode.h: decoding BC1-BC7, ETC1, ETC2 and EAC blocks and
// block-compressed textures, to the Khronos Data Format Specification 1.3
// (S3TC, RGTC, ETC1 and ETC2 chapters).
#pragma once

#include <cstdint>
#include <vector>

#include "texproc/image.h"
#include "texproc/texture.h"

namespace texproc {

// Decodes one 4x4 block of `format` (a BC, ETC or EAC format) into texels[16][4], RGBA,
// row by row. UNORM results are in [0, 1], SNORM in [-1, 1], BC6H the half
// floats it holds (ARB_texture_compression_bptc); channels the format lacks
// are 0 (green, blue) and 1 (alpha).
//
// Rounding: the RGTC values (BC4, BC5 and BC2/BC3 alpha interpolation) are
// exact, (a (7 - k) + b k) / 7 / 255 in float, as GPUs return them. BC1
// colours expand 5/6-bit endpoints to 8 bits by bit replication and
// interpolate in 8 bits rounded to nearest: (2 a + b + 1) / 3 and
// (a + b + 1) / 2. Hardware differs by one or two 8-bit levels on the
// interpolated colours; the specification allows that.
void decode_block(TexelFormat format, const std::uint8_t* block, float texels[16][4]);

// Decodes one image (level, layer, face) of a texture of any format texproc
// reads: block formats through decode_block, uncompressed ones converted.
// `type` u8 or u16 stores UNORM values rounded, SNORM values biased as
// (v + 1) / 2; f32 stores the values. Channels: the format's (1, 2 or 4; 3
// for BC1 RGB and ETC1/ETC2 RGB).
Image decode_texture_image(const Texture& t, std::uint32_t level, std::uint32_t layer, std::uint32_t face,
                           PixelType type);

// Rows [y0, y1) of decode_texture_image(t, level, layer, face, type), the
// same bytes (format_info(t.format).channels channels), into `dst` (rows
// `row_stride` bytes apart), decoding only the
// block rows they lie in: a level written out band by band is never whole
// in memory. Throws Error{bad_arguments} for rows outside the level.
void decode_texture_rows(const Texture& t, std::uint32_t level, std::uint32_t layer, std::uint32_t face, PixelType type,
                         int y0, int y1, void* dst, std::size_t row_stride);

// compress_image's inverse: `blocks` (a width x height image in `format`)
// decoded to `type`, as decode_texture_image decodes a level.
Image decompress_image(std::vector<std::uint8_t> blocks, int width, int height, TexelFormat format, PixelType type);

}  // namespace texproc
