// BC1-BC5 block decoders: the Khronos Data Format Specification's
// arithmetic, one 4x4 block into RGBA floats (decode_block in
// decode/decode_block.cpp picks the format's).
#pragma once

#include <cstdint>

namespace texproc::bc {

// The colour half of BC1/BC2/BC3. `always_four`: BC2 and BC3 always use the
// four-colour mode; BC1 only when c0 > c1. `punch_through`: BC1 with alpha
// (index 3 of the three-colour mode is transparent black). Writes RGB, and
// alpha 1 (or 0 for punch-through's transparent texels).
void decode_color(const std::uint8_t* block, bool always_four, bool punch_through, float out[16][4]);

// A BC4 (RGTC1) block into channel `ch` of out: exact values (UNORM / 255,
// SNORM / 127).
void decode_rgtc(const std::uint8_t* block, bool snorm, int ch, float out[16][4]);

}  // namespace texproc::bc
