// BC7's encoder, sixteen blocks at a time (a block per SIMD lane), SIMD and
// scalar twins with identical bytes (bc7_lanes_simd.cpp, bc7_lanes.cpp).
//
// Per block, each candidate below is fitted and scored against the exact
// decoder's texels (squared error over R, G, B and A, integers), and the
// first with the least error is kept:
//   - one colour: mode 5, exact for every colour (its 7-bit endpoints at
//     weight 21, its alpha 8-bit);
//   - mode 6 (RGBA together, 7-bit endpoints and a p-bit each, 4-bit
//     indices); an opaque block's p-bits are 1, so its alpha stays 255;
//   - modes 1 and 3 on the two-subset partitions the estimate ranks first,
//     then modes 0 and 2 on the three-subset ones (Bc7Level);
//   - blocks with alpha: mode 5, then mode 4 (each rotation, each index
//     selection the level tries), then mode 7 on the two-subset partitions
//     kept; opaque blocks, where the level says, modes 5 and 4 with
//     rotations 1-3 only;
//   - then, where the level says, the winner's endpoint codes stepped
//     (modes 0-3, 6, 7; the SIMD twin gathers a span's winners mode by
//     mode into full vectors first), its indices assigned with the
//     neighbouring-index check where the level says (exact_winner).
// A set's fit: the texels' principal axis (three power iterations on the
// covariance, from its largest diagonal's column), the texels' extent along
// it as endpoints, quantized (the p-bit that quantizes the endpoint better,
// ties to 0, or every p-bit choice where the level says), indices by
// projection onto the quantized endpoints' line (and, where the level says,
// the neighbouring index that decodes closer), then least-squares endpoints
// for those indices while the error falls, then the level's endpoint steps.
// The partition estimate: each subset's squared residual off its principal
// axis (two power iterations), summed; the K least kept, ties to the lower
// partition. Floats in the same order on both twins, no FMA.
#pragma once

#include <cstdint>

#include "bc/bc7_levels.h"
#include "core/block_batch.h"

namespace texproc {

constexpr int kBc7Batch = kBlockBatch;  // core/block_batch.h
// A batch's texels: [i][k] is texel i (row by row) of block k, RGBA8 packed
// as block_gather.h's pack_texel.
using Bc7Texels = std::uint32_t[16][kBc7Batch];
// How many blocks the SIMD twin searches before it steps their winners
// (each mode's winners gathered into full vectors, bc7_lanes_simd.cpp).
constexpr int kBc7Span = 16 * kBc7Batch;

// Blocks 0 to count - 1, block b in texel[b / kBc7Batch][.][b % kBc7Batch];
// out[b]: block b's 16 bytes. Any count; the bytes of a block do not depend
// on the others.
void bc7_encode_lanes(const Bc7Texels* texel, int count, const Bc7Level& level, std::uint8_t out[][16]);

namespace ref {
void bc7_encode_lanes(const Bc7Texels* texel, int count, const Bc7Level& level, std::uint8_t out[][16]);
}  // namespace ref

}  // namespace texproc
