// The BC1 colour block encoder, shared by BC1, BC2 and BC3.
#pragma once

#include <cstdint>

#include "bc/bc1_assign.h"
#include "texproc/block_encode.h"

namespace texproc {

enum class ColorMode {
  bc1,                // both BC1 modes, no transparency (index 3 of the three-colour mode unused)
  bc1_punch_through,  // texels with alpha < 128 become index 3 (transparent black)
  four_only           // BC2/BC3: the colour half always decodes in four-colour mode
};

// Encodes 16 RGBA8 texels (row by row) into an 8-byte BC1 colour block.
void encode_bc1_color(const std::uint8_t rgba[16][4], ColorMode mode, Quality q, std::uint8_t out[8]);
// The same from texel planes (transparent texels already marked; none for
// `bc1` and `four_only`).
void encode_bc1_color(const Bc1Texels& tx, ColorMode mode, Quality q, std::uint8_t out[8]);

}  // namespace texproc
