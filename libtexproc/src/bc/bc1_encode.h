// The BC1 colour block encoder, shared by BC1, BC2 and BC3.
#pragma once

#include <cstdint>

#include "texproc/block_encode.h"

namespace texproc {

enum class ColorMode {
  bc1,                // both BC1 modes, no transparency (index 3 of the three-colour mode unused)
  bc1_punch_through,  // texels with alpha < 128 become index 3 (transparent black)
  four_only           // BC2/BC3: the colour half always decodes in four-colour mode
};

// Encodes 16 RGBA8 texels (row by row) into an 8-byte BC1 colour block.
// Below `max` through the lanes (bc1_lanes.h), as whole images are.
void encode_bc1_color(const std::uint8_t rgba[16][4], ColorMode mode, Quality q, std::uint8_t out[8]);
// Block by block: `max`, and the blocks the lanes leave (one opaque colour,
// with or without transparent texels, or none opaque).
void encode_bc1_color_block_by_block(const std::uint8_t rgba[16][4], ColorMode mode, Quality q, std::uint8_t out[8]);

}  // namespace texproc
