// BC4's `fast`, `normal` and `high` encoders (also BC5's channels and BC3's alpha), sixteen blocks
// at a time (a block per SIMD lane), SIMD and scalar twins with identical
// bytes.
//
// Per block: the values' range, rounded outwards to whole codes, as the
// eight-value mode's endpoints (equal ends: the six-value mode, flat); where
// that range is narrower than 7 codes, also the eight-value palette of whole
// code steps over it (exact for 8-bit levels); and,
// where values lie strictly inside the code range and their own range
// differs, the six-value mode over those inner values (the range's two ends
// come free). Each value's palette position is found by rounding (to
// nearest, ties to even) its place between the endpoints, a multiply by the
// pair's 7 / span or 5 / span (the palette is evenly spaced under the exact
// decoding); a candidate is scored by its squared error alone, from values
// taken 7 or 5 times over, and the one with less error wins (the first on a
// tie). The codes are worked out once, for the pair chosen. Float
// expressions in the same order on both twins, no FMA.
#pragma once

#include "bc/bc4_levels.h"
#include "core/block_batch.h"

#include <cstdint>

namespace texproc {

constexpr int kBc4Batch = kBlockBatch;  // core/block_batch.h

// v[i][k]: value i (row by row) of block k in code units: [0, 255], or
// [-127, 127] with `snorm` (clamped here).
// level: the row's Bc4LaneSearch (bc4_levels.h). `fast`, as above. `normal` then, per mode (eight values from
// the range; six from the inner range), alternates least-squares endpoints
// for the codes (rounded) and codes for the endpoints, twice while that
// helps, and tries the +-1 window around the result in the same mode.
// `high`, the same with a +-2 window, then 45 partition variants per mode:
// the values placed on the mode's grid between its starting endpoints, the
// grid shifted (up to +-0.6 of a step) and stretched (up to +-20%), each
// position set fitted by least squares and scored.
void bc4_encode_lanes(const float v[16][kBc4Batch], int count, bool snorm, const Bc4LaneSearch& level,
                      std::uint8_t out[][8]);

namespace ref {
void bc4_encode_lanes(const float v[16][kBc4Batch], int count, bool snorm, const Bc4LaneSearch& level,
                      std::uint8_t out[][8]);
}  // namespace ref

}  // namespace texproc
