// BC4/BC5 encoding: endpoint search under the exact RGTC decoding
// (Khronos Data Format Specification, "RGTC Compressed Texture Image
// Formats"). For a pair of endpoints the palette is known in closed form, so
// each texel's index is found by rounding, and a candidate costs 16 steps.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "block/value_palette.h"
#include "bc/bc4_lanes.h"
#include "block/block_gather.h"
#include "texproc/block_decode.h"
#include "texproc/block_encode.h"
#include "texproc/error.h"
#include "texproc/runtime.h"

namespace texproc {

namespace {

struct Candidate {
  int r0, r1;
  double error;
  std::uint8_t indices[16];
};

// Evaluates endpoints (r0, r1) in the mode they select (r0 > r1: eight
// values; else six values plus the range's two ends), writing each texel's
// best code. Palette positions are exact fractions of the endpoints.
// The eight decoded values of endpoints (r0, r1), by code, in code units:
// exact rationals (the decoder divides these by 255 or 127).
void palette(int r0, int r1, bool snorm, double pal[8]) {
  pal[0] = r0;
  pal[1] = r1;
  if (r0 > r1) {
    for (int k = 1; k <= 6; ++k) pal[k + 1] = double(r0 * (7 - k) + r1 * k) / 7.0;
  } else {
    for (int k = 1; k <= 4; ++k) pal[k + 1] = double(r0 * (5 - k) + r1 * k) / 5.0;
    pal[6] = snorm ? -127.0 : 0.0;
    pal[7] = snorm ? 127.0 : 255.0;
  }
}

void evaluate(const float v[16], int r0, int r1, bool snorm, Candidate& c) {
  const double lo_end = snorm ? -127.0 : 0.0, hi_end = snorm ? 127.0 : 255.0;
  double pal[8], t[16], errors[16];
  palette(r0, r1, snorm, pal);
  for (int i = 0; i < 16; ++i) t[i] = std::min(std::max(double(v[i]), lo_end), hi_end);
  value_palette_nearest(t, pal, c.indices, errors);  // SIMD twins
  double err = 0.0;
  for (int i = 0; i < 16; ++i) err += errors[i];  // in order: the same sum on every target
  c.r0 = r0;
  c.r1 = r1;
  c.error = err;
}

void write_block(const Candidate& c, bool snorm, std::uint8_t out[8]) {
  out[0] = std::uint8_t(snorm ? std::uint8_t(std::int8_t(c.r0)) : c.r0);
  out[1] = std::uint8_t(snorm ? std::uint8_t(std::int8_t(c.r1)) : c.r1);
  std::uint64_t bits = 0;
  for (int i = 0; i < 16; ++i) bits |= std::uint64_t(c.indices[i]) << (3 * i);
  for (int b = 0; b < 6; ++b) out[2 + b] = std::uint8_t(bits >> (8 * b));
}

// One block through the lanes' search (lane 0 of a batch).
void lane_block(const float v[16], bool snorm, const Bc4LaneSearch& search, std::uint8_t out[8]) {
  float batch[16][kBc4Batch] = {};
  for (int i = 0; i < 16; ++i) batch[i][0] = v[i];
  std::uint8_t block[1][8];
  bc4_encode_lanes(batch, 1, snorm, search, block);
  std::memcpy(out, block[0], 8);
}

}  // namespace

void encode_bc4_block(const float v[16], bool snorm, Quality q, std::uint8_t out[8]) {
  const Bc4Level& level = bc4_level(q);                           // bc4_levels.h
  if (level.lanes) return lane_block(v, snorm, level.lane, out);  // as whole images do: bc4_lanes.h
  // Block by block (`max`): every endpoint pair in both modes, scored with the exact palette;
  // the first pair in this order with the least error, as scoring every pair
  // in full finds it, far sooner. The least starts just above the error of
  // the lanes' block at the row's lane settings (the best pair's cannot exceed it). A pair is dropped
  // once a partial sum reaches it with a margin (the values farthest from
  // the block's mean first, against the palette times 1/7 or 1/5: either
  // rounds differently from the exact sum by far less than the margin);
  // the pairs left are scored exactly, values in order, as `evaluate`
  // scores them.
  const int lo_code = snorm ? -127 : 0, hi_code = snorm ? 127 : 255;
  std::uint8_t start[8];
  lane_block(v, snorm, level.lane, start);
  double least = bc4_block_error(start, v, snorm);
  least += least * 1e-9 + 1e-9;
  double t[16], mean = 0.0;
  for (int i = 0; i < 16; ++i) {
    t[i] = std::min(std::max(double(v[i]), double(lo_code)), double(hi_code));
    mean += t[i] / 16.0;
  }
  int order[16];
  for (int i = 0; i < 16; ++i) order[i] = i;
  std::stable_sort(order, order + 16, [&](int x, int y) { return std::abs(t[x] - mean) > std::abs(t[y] - mean); });
  auto nearest = [&](double x, const double pal[8]) {  // its squared distance to the nearest entry
    double be = (x - pal[0]) * (x - pal[0]);
    for (int k = 1; k < 8; ++k) be = std::min(be, (x - pal[k]) * (x - pal[k]));
    return be;
  };
  int best_a = lo_code, best_b = lo_code;
  for (int a = lo_code; a <= hi_code && least > 0.0; ++a)
    for (int b = lo_code; b <= hi_code && least > 0.0; ++b) {  // after an exact pair nothing is less
      double quick[8];
      quick[0] = a;
      quick[1] = b;
      if (a > b) {
        for (int k = 1; k <= 6; ++k) quick[k + 1] = double(a * (7 - k) + b * k) * (1.0 / 7.0);
      } else {
        for (int k = 1; k <= 4; ++k) quick[k + 1] = double(a * (5 - k) + b * k) * (1.0 / 5.0);
        quick[6] = lo_code;
        quick[7] = hi_code;
      }
      const double cut = least * (1.0 + 1e-9);
      double partial = 0.0;
      int i = 0;
      for (; i < 16 && partial < cut; ++i) partial += nearest(t[order[i]], quick);
      if (partial >= cut) continue;
      double pal[8], err = 0.0;
      palette(a, b, snorm, pal);
      for (int j = 0; j < 16; ++j) err += nearest(t[j], pal);
      if (err < least) {
        least = err;
        best_a = a;
        best_b = b;
      }
    }
  Candidate best;
  evaluate(v, best_a, best_b, snorm, best);
  write_block(best, snorm, out);
}

double bc4_block_error(const std::uint8_t block[8], const float values[16], bool snorm) {
  // Exact palette in code units (the same rationals the decoder returns,
  // before its division by 255 or 127), so a lossless block scores 0.
  const int r0 = snorm ? std::max(-127, int(std::int8_t(block[0]))) : block[0];
  const int r1 = snorm ? std::max(-127, int(std::int8_t(block[1]))) : block[1];
  std::uint64_t bits = 0;
  for (int b = 0; b < 6; ++b) bits |= std::uint64_t(block[2 + b]) << (8 * b);
  const double lo_end = snorm ? -127.0 : 0.0, hi_end = snorm ? 127.0 : 255.0;
  double pal[8];
  palette(r0, r1, snorm, pal);
  double e = 0.0;
  for (int i = 0; i < 16; ++i) {
    const double d = pal[bits >> (3 * i) & 7] - std::clamp(double(values[i]), lo_end, hi_end);
    e += d * d;
  }
  return e;
}

}  // namespace texproc
