// EAC blocks (R11, R11 signed, ETC2's 8-bit alpha), sixteen at a time (a
// block per SIMD lane), SIMD and scalar twins with identical bytes.
//
// Per block and for each of the 16 modifier tables: the multiplier that
// spreads the table over the values' range (rounded) and, at `normal`, the
// one above it, at `high` the one below and the two above; for each, the
// base that centres the table on the range (rounded) and, at `normal` +-2,
// at `high` +-5 around it (the base matters more than the multiplier:
// values on a coarse 8-bit grid, skewed within the block, want the
// palette's entries on their levels, often 3-5 bases from the centred one).
// Each value takes
// the nearest palette entry (the palette is monotonic in the modifier, so
// the entry follows from the value's place among the midpoints); the
// candidate with the least squared error wins, the first in that order on a
// tie. Float expressions in the same order on both twins, no FMA.
#pragma once

#include "core/block_batch.h"
#include "etc/eac_levels.h"

#include <cstdint>

#include "etc/etc_encode.h"

namespace texproc::etc {

constexpr int kEacBatch = kBlockBatch;  // core/block_batch.h

// v[i][k]: value i (row by row) of block k in the format's units (see
// encode_eac_block; clamped here). window: the level's (eac_levels.h).
// error[k]: the block's squared error in those units.
void eac_encode_lanes(const float v[16][kEacBatch], int count, EacKind kind, const EacWindow& window,
                      std::uint8_t out[][8], float error[]);

namespace ref {
void eac_encode_lanes(const float v[16][kEacBatch], int count, EacKind kind, const EacWindow& window,
                      std::uint8_t out[][8], float error[]);
}  // namespace ref

}  // namespace texproc::etc
