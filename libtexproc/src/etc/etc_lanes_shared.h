// What both twins of the ETC1 lane encoder use (etc_lanes.cpp, the scalar
// reference, and etc_lanes_simd.cpp): half-block layouts, the packed
// parameters, the base quantizers.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdlib>

#include "etc/etc_lanes.h"
#include "etc/etc_tables.h"

namespace texproc::etc {
namespace fast {

// The texels of each half block (row by row indices): left, right, top, bottom.
inline constexpr int kHalf[4][8] = {
    {0, 1, 4, 5, 8, 9, 12, 13}, {2, 3, 6, 7, 10, 11, 14, 15}, {0, 1, 2, 3, 4, 5, 6, 7}, {8, 9, 10, 11, 12, 13, 14, 15}};
// 96 (a + b) for each table: compared with the summed absolute deviation.
inline constexpr int kMid96[8] = {960, 2112, 3648, 5280, 7488, 9984, 13344, 22080};

// A block's choice: flip (halves 2, 3 instead of 0, 1), differential (5-bit
// bases) or individual (4-bit), per half its base, table and modifier
// index per texel (in kHalf order).
struct Params {
  int flip, differential;
  int q[2][3], table[2], idx[2][8];
};

// The block's 64 bits as the specification numbers them (bit 63 first).
inline void pack(const Params& p, std::uint8_t out[8]) {
  std::uint64_t v = 0;
  for (int c = 0; c < 3; ++c) {  // bits 63-40: a byte per channel
    const int byte = p.differential ? p.q[0][c] << 3 | ((p.q[1][c] - p.q[0][c]) & 7) : p.q[0][c] << 4 | p.q[1][c];
    v |= std::uint64_t(byte) << (56 - 8 * c);
  }
  v |= std::uint64_t(p.table[0] << 5 | p.table[1] << 2 | p.differential << 1 | p.flip) << 32;
  std::uint32_t msb = 0, lsb = 0;  // texel (x, y) at bit x * 4 + y of each
  for (int s = 0; s < 2; ++s)
    for (int i = 0; i < 8; ++i) {
      const int t = kHalf[2 * p.flip + s][i], k = (t % 4) * 4 + t / 4;
      msb |= std::uint32_t(p.idx[s][i] >> 1) << k;
      lsb |= std::uint32_t(p.idx[s][i] & 1) << k;
    }
  store_be64(v | std::uint64_t(msb) << 16 | lsb, out);
}

// The quantized mean of 8 values summing to `sum`: 5 or 4 bits.
inline int quantize_sum(int sum, int bits) { return int(float((bits == 5 ? 62 : 30) * sum + 2040) / 4080.0f); }

// The same for a sum that may leave [0, 2040] (texels minus modifiers): clamped.
inline int quantize_centre(int sum, int bits) {
  return std::clamp(int(float((bits == 5 ? 62 : 30) * sum + 2040) / 4080.0f), 0, bits == 5 ? 31 : 15);
}

// Whether the differential mode reaches from base a to base b (5 bits):
// b - a in [-4, 3] per channel.
inline bool delta_reaches(const int a[3], const int b[3]) {
  for (int c = 0; c < 3; ++c)
    if (b[c] - a[c] < -4 || b[c] - a[c] > 3) return false;
  return true;
}

}  // namespace fast
}  // namespace texproc::etc
