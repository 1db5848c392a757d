// BC1-BC5 block decoders: the Khronos Data Format Specification's
// arithmetic, one 4x4 block into RGBA floats (decode_block in
// decode/decode_block.cpp picks the format's).
#pragma once

#include <cstddef>
#include <cstdint>

namespace texproc::bc {

// The colour half of BC1/BC2/BC3. `always_four`: BC2 and BC3 always use the
// four-colour mode; BC1 only when c0 > c1. `punch_through`: BC1 with alpha
// (index 3 of the three-colour mode is transparent black). Writes RGB, and
// alpha 1 (or 0 for punch-through's transparent texels).
void decode_color(const std::uint8_t* block, bool always_four, bool punch_through, float out[16][4]);

// The same as RGBA8 (the palette's integers).
void decode_color_rgba8(const std::uint8_t* block, bool always_four, bool punch_through, std::uint8_t out[16][4]);

// A BC4 (RGTC1) block into channel `ch` of out: exact values (UNORM / 255,
// SNORM / 127).
void decode_rgtc(const std::uint8_t* block, bool snorm, int ch, float out[16][4]);
// The same as 8-bit values, each palette value converted as Image::set
// converts a float (SNORM biased to [0, 1] first, as 8-bit outputs store it).
void decode_rgtc_u8(const std::uint8_t* block, bool snorm, int ch, std::uint8_t out[16][4]);

// A float in [0, 1] to 8 bits exactly as Image::set stores it (clamped,
// times 255, plus 0.5, truncated).
inline std::uint8_t to_unorm8(float v) {
  const float cl = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;
  return static_cast<std::uint8_t>(cl * 255.0f + 0.5f);
}

// Straight into an image's rows: `count` whole blocks side by side
// (`block_bytes` apart) at `dst`, rows `stride` bytes apart, `channels`
// bytes a texel. The colour half as RGB (3) or RGBA (4, alpha as
// decode_color_rgba8 gives it); BC4 into channel `ch` of 1, 2 or 4 (the same
// bytes as decode_rgtc_u8).
void decode_color_run(const std::uint8_t* blocks, int count, int block_bytes, bool always_four, bool punch_through,
                      int channels, std::uint8_t* dst, std::size_t stride);
// `count` whole BC2 blocks side by side straight into RGBA8 rows: the colour
// half as decode_color_run gives it (always four colours), alpha the 4-bit
// value times 17.
void decode_bc2_run(const std::uint8_t* blocks, int count, std::uint8_t* dst, std::size_t stride);
// `count` whole BC3 blocks side by side straight into RGBA8 rows: the bytes
// of decode_color_run (always four colours) and decode_rgtc_run (UNORM,
// channel 3) together, in one pass.
void decode_bc3_run(const std::uint8_t* blocks, int count, std::uint8_t* dst, std::size_t stride);
void decode_rgtc_run(const std::uint8_t* blocks, int count, int block_bytes, bool snorm, int channels, int ch,
                     std::uint8_t* dst, std::size_t stride);

// A BC7 block: RGBA8 texels, row by row (ARB_texture_compression_bptc; the
// reserved mode decodes to 0 in every channel, as Direct3D's does).
void decode_bc7(const std::uint8_t* block, std::uint8_t out[16][4]);
// `count` whole BC7 blocks side by side straight into RGBA8 rows (as decode_color_run).
void decode_bc7_run(const std::uint8_t* blocks, int count, std::uint8_t* dst, std::size_t stride);

// A BC6H block: RGB half-float bits, row by row (`is_signed`: SF16, else
// UF16; reserved modes decode to 0).
void decode_bc6h(const std::uint8_t* block, bool is_signed, std::uint16_t out[16][3]);
// The same halves as floats straight into four rows of RGB floats (`dst`,
// rows `stride` floats apart): each palette entry converted once.
void decode_bc6h_f32_rows(const std::uint8_t* block, bool is_signed, float* dst, std::size_t stride);

}  // namespace texproc::bc
