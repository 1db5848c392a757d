// ETC1's encoders below `max` (also the ETC1 modes of ETC2 RGB and ETC2
// RGBA's colour), sixteen opaque blocks at a time (a block per SIMD lane),
// SIMD and scalar twins with identical bytes.
//
// `fast`, per block and half block (left, right, top, bottom): the base
// colour is the half's mean, quantized to 5 bits (and to 4 where the
// differential delta cannot reach: individual mode); three intensity tables
// are scored with each texel at the modifier nearest a third of its R + G +
// B offset from the base (unclamped), and the best kept: the two whose
// modifiers are nearest the texels' spread about the mean (mean absolute
// deviation of R + G + B, over 3) and the next smaller one, or in its place
// the table whose far modifier reaches the farthest texel where that is
// larger still (a dark half with one bright texel). The flip with less
// error wins (the first on a tie); then each texel takes its best modifier
// under the decoder's clamping. Integer arithmetic throughout, and one
// float division per quantized channel, the same on both twins.
#pragma once

#include "core/block_batch.h"

#include <cstdint>

namespace texproc::etc {

constexpr int kEtcBatch = kBlockBatch;  // core/block_batch.h

// texel[i][k]: texel i (row by row) of block k as R | G << 8 | B << 16
// (alpha ignored). out: the ETC1 blocks (valid ETC2 RGB blocks too).
// differential_only: no individual-mode blocks (ETC2 punch-through, whose
// bit 33 is the opaque flag: these are its opaque blocks); where the halves'
// bases are too far apart, the second is pulled within the delta of the
// first (`fast`) or either is (`normal`, `high`).
void etc1_fast_lanes(const std::uint32_t texel[16][kEtcBatch], int count, bool differential_only,
                     std::uint8_t out[][8]);

// `normal`: per half every table at the mean, exactly (the decoder's
// clamping, each texel at its best modifier); the best two tables also
// seeded from the half's brightest and darkest texels minus their far
// modifiers (line art: a dark half with one bright texel), then re-centred
// up to twice (base = mean of the texels minus their modifiers) while that
// helps. Halves too far apart for the delta try the individual mode (4-bit
// fits as above) and the differential mode with either base pulled within
// the delta of the other (that half's best table refitted).
// `high` (high true): every table seeded from the half's brightest and
// darkest texels minus the table's extreme modifiers and re-centred up to
// three times, then the +-1 neighbourhood of the two best bases; every pair
// of the halves' per-table fits that the delta reaches; where the halves'
// bases are too far apart, the pulled base's neighbours too; the individual
// mode is always tried (unless differential_only).
// error[k]: block k's squared RGB error as decoded.
void etc1_search_lanes(const std::uint32_t texel[16][kEtcBatch], int count, bool high, bool differential_only,
                       std::uint8_t out[][8], std::int32_t error[]);

namespace ref {
void etc1_fast_lanes(const std::uint32_t texel[16][kEtcBatch], int count, bool differential_only,
                     std::uint8_t out[][8]);
void etc1_search_lanes(const std::uint32_t texel[16][kEtcBatch], int count, bool high, bool differential_only,
                       std::uint8_t out[][8], std::int32_t error[]);
}  // namespace ref

}  // namespace texproc::etc
