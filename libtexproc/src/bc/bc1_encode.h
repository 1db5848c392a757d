// The BC1 colour block encoder, shared by BC1, BC2 and BC3.
#pragma once

#include <cstdint>

#include "texproc/block_encode.h"

namespace texproc {

enum class Bc1Mode {
  bc1,                // both BC1 modes, no transparency (index 3 of the three-colour mode unused)
  bc1_punch_through,  // texels with alpha < 128 become index 3 (transparent black)
  four_only           // BC2/BC3: the colour half always decodes in four-colour mode
};

// Encodes 16 RGBA8 texels (row by row) into an 8-byte BC1 colour block.
// Below `max` through the lanes (bc1_lanes.h), as whole images are.
void encode_bc1_color(const std::uint8_t rgba[16][4], Bc1Mode mode, Quality q, std::uint8_t out[8]);
// Block by block: `max`, and the blocks the lanes leave (one opaque colour,
// with or without transparent texels, or none opaque).
void encode_bc1_color_block_by_block(const std::uint8_t rgba[16][4], Bc1Mode mode, Quality q, std::uint8_t out[8]);

// A block of exactly two colours (and, with punch-through, no hole): every
// pair of palette positions for them (either mode where `mode` allows it),
// the ends that put them there exactly, each channel's quantized ends within
// one step; `block` is replaced where that lowers its error. Texts, line art
// and UI edges; `normal` and above.
void bc1_try_two_colours(const std::uint8_t rgba[16][4], Bc1Mode mode, std::uint8_t block[8]);

// Opaque BC1 with the three-colour mode's black (EncodeOptions::bc1_black):
// a set of texels takes index 3 and the others are fitted in the
// three-colour mode (the punch-through encoder at `q`, which leaves index-3
// texels out of its fit); the result replaces `block` where the block's
// squared RGB error falls. The sets: the texels nearer black than to their
// colour in `block`; those within about 4, 8 and 16 levels a channel of
// black; the first again from the best block so far.
void bc1_try_black(const std::uint8_t rgba[16][4], Quality q, std::uint8_t block[8]);

}  // namespace texproc
