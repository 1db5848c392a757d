// BC6H's encoder, sixteen blocks at a time (a block per SIMD lane), SIMD and
// scalar twins with identical bytes (bc6h_lanes_simd.cpp, bc6h_lanes.cpp).
//
// Texels are compared as the decoder's final values (bc6h_shared.h's
// finish: half-float bits with the sign apart), the error per channel the
// squared difference limited to kErrorLimit. Fitting works in floats,
// y = the unquantized 16-bit value / 64, each texel at the centre of the
// values that finish to its half.
//
// Per block, each candidate below is fitted and scored against the exact
// decoder's texels, and the first with the least error is kept:
//   - a block of one colour: mode 13 only (exact);
//   - the one-region modes the level tries (10-13), on one fit of all 16;
//   - the two-region modes the level tries (0-9), on each partition the
//     estimate ranks among the first Bc6hLevel::partitions (the squared
//     residual off each region's principal axis, one power step; ties to
//     the lower partition), each region fitted once per partition.
// A region's fit: the principal axis of its texels (three power iterations
// on the covariance, from its largest diagonal's column) and their extent
// along it, the end nearer the anchor texel first. A mode then quantizes
// the ends (the code that unquantizes nearest; a transformed mode's other
// endpoints as near as a delta from the base reaches), picks each texel's
// index from the exact palette (an anchor among the lower half), and then
// least-squares endpoints for those indices (a region whose indices are
// all equal keeps its ends) while the error falls, up to
// Bc6hLevel::refine times. Floats in the same order on both twins, no FMA.
#pragma once

#include <cstdint>

#include "bc/bc6h_levels.h"
#include "core/block_batch.h"

namespace texproc {

constexpr int kBc6hBatch = kBlockBatch;  // core/block_batch.h

// texel[i][c][k]: channel c (RGB) of texel i (row by row) of block k, the
// target as bc6h::target gives it. out[k]: block k's 16 bytes.
void bc6h_encode_lanes(const std::int32_t texel[16][3][kBc6hBatch], int count, bool is_signed, const Bc6hLevel& level,
                       std::uint8_t out[][16]);

namespace ref {
void bc6h_encode_lanes(const std::int32_t texel[16][3][kBc6hBatch], int count, bool is_signed, const Bc6hLevel& level,
                       std::uint8_t out[][16]);
}  // namespace ref

}  // namespace texproc
