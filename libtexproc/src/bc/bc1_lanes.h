// BC1's encoder for opaque blocks at `fast`, `normal` and `high`, sixteen
// blocks at a time (a block per SIMD lane), SIMD and scalar twins with
// identical bytes.
//
// Every level starts from the principal axis of the block's colours (power
// iteration on the covariance, from its row of greatest variance) and the
// colours' extent along it. The knobs are a Bc1LaneSearch (bc1_levels.h):
// - `fast` (thirds_fit): each texel at the nearest third of the extent, one
//   least-squares fit of the endpoints for those positions, each texel's
//   nearest colour of the quantized palette.
// - `normal` (2 offsets, 1 stretch): the extent's ends as endpoints, nearest colours and two
//   least-squares refits (each kept where it lowers the error); then
//   partition variants along the axis: the thirds shifted (offsets of 0.15
//   up to +-0.3) and stretched (+-15%), each a least-squares fit, the 15
//   ranked by their unquantized error and the best two scored exactly;
//   then each quantized endpoint channel nudged by one step while that
//   lowers the error (at most four passes over the twelve moves); with
//   `three`, the three-colour mode (no black) from the extent's ends,
//   refitted once.
// - `high` (4, 2, score_every_variant): as normal, but 45 variants (offsets up to +-0.6, stretches
//   up to +-30%), every one scored exactly and refitted once.
// Integer sums, and float expressions evaluated in the same order by both
// twins (no FMA; divisions and square roots are correctly rounded on every
// target).
#pragma once

#include "bc/bc1_levels.h"
#include "core/block_batch.h"

#include <cstdint>

namespace texproc {

constexpr int kBc1Batch = kBlockBatch;  // core/block_batch.h

// texel[i][k]: texel i (row by row) of block k as R | G << 8 | B << 16 |
// A << 24. `three`: the three-colour mode may be used (BC1, not BC2/BC3's
// colour). `punch` (BC1 with alpha): texels with alpha under 128 are
// transparent (index 3 of the three-colour mode, out of every fit and
// error); a block with any is encoded in the three-colour mode (at `fast`
// from the extent's ends refitted once, at `normal` twice, at `high` then
// 45 partition variants on halves of the extent and one-step nudges). Blocks
// whose opaque texels are all one colour (or that have none) are left to
// the caller (`handled[k]` false; their bytes are not written).
void bc1_encode_lanes(const std::uint32_t texel[16][kBc1Batch], int count, const Bc1LaneSearch& level, bool three,
                      bool punch, std::uint8_t out[][8], bool handled[]);

namespace ref {
// The partition variants: texels split into four runs along the axis at
// thirds of the extent shifted by `offset` steps of 0.15 and stretched by
// `stretch` steps of 0.15 (about the middle). Shared by both twins.
constexpr float kVariantStep = 0.15f;
inline float variant_shift(int offset, int stretch) {
  return 0.5f + kVariantStep * float(offset) - kVariantStep * float(stretch) * 1.5f;
}

void bc1_encode_lanes(const std::uint32_t texel[16][kBc1Batch], int count, const Bc1LaneSearch& level, bool three,
                      bool punch, std::uint8_t out[][8], bool handled[]);
}  // namespace ref

}  // namespace texproc
