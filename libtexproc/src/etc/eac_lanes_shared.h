// What both twins of the EAC lane encoder use (eac_lanes.cpp, the scalar
// reference, and eac_lanes_simd.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "etc/eac_lanes.h"
#include "etc/etc_tables.h"

namespace texproc::etc {
namespace eac {

// The modifier indices of every table in ascending order of modifier (the
// tables list -a, -b, -c, -d, then e < f < g < h, with a < b < c < d).
inline constexpr int kAscending[8] = {3, 2, 1, 0, 4, 5, 6, 7};

// A kind's ranges and units: values in [lo_end, hi_end]; a decoded value is
// base * unit + offset + modifier * multiplier * unit (multiplier 0: the
// modifier unscaled, for 8-bit alpha nothing), clamped.
struct Kind {
  float lo_end, hi_end, unit, offset;
  int base_lo, base_hi, unit_i, offset_i, zero_step;
};
inline Kind kind_of(EacKind k) {
  switch (k) {
    case EacKind::alpha8:
      return {0.0f, 255.0f, 1.0f, 0.0f, 0, 255, 1, 0, 0};
    case EacKind::r11:
      return {0.0f, 2047.0f, 8.0f, 4.0f, 0, 255, 8, 4, 1};
    case EacKind::r11_signed:
      return {-1023.0f, 1023.0f, 8.0f, 0.0f, -127, 127, 8, 0, 1};
  }
  return {};
}

// The palette of (base, mult, table) in ascending order of modifier, as
// floats clamped to the kind's range.
inline void palette(const Kind& K, int base, int mult, int table, float pal[8]) {
  for (int j = 0; j < 8; ++j) {
    const int m = kEacModifiers[table][kAscending[j]];
    const int value = base * K.unit_i + K.offset_i + (mult == 0 ? m * K.zero_step : m * mult * K.unit_i);
    pal[j] = std::min(std::max(float(value), K.lo_end), K.hi_end);
  }
}

// Each value's place in the ascending palette: how many midpoints between
// neighbours it lies above (the nearest entry; the lower of two at a tie).
inline int place(float t, const float pal[8]) {
  int s = 0;
  for (int j = 0; j < 7; ++j) s += t > (pal[j] + pal[j + 1]) * 0.5f ? 1 : 0;
  return s;
}

// The squared error of (base, mult, table) for the 16 clamped values.
inline float candidate_error(const Kind& K, const float t[16], int base, int mult, int table) {
  float pal[8];
  palette(K, base, mult, table, pal);
  float err = 0.0f;
  for (int i = 0; i < 16; ++i) {
    const float d = t[i] - pal[place(t[i], pal)];
    err += d * d;
  }
  return err;
}

// The chosen block's codes (values clamped as the search had them): worked
// out once, after the search has scored its candidates by error alone.
inline void codes_of(const Kind& K, const float t[16], int base, int mult, int table, int codes[16]) {
  float pal[8];
  palette(K, base, mult, table, pal);
  for (int i = 0; i < 16; ++i) codes[i] = kAscending[place(t[i], pal)];
}

// 8-bit alpha over a range of at most 5: table 13's modifiers -3..2 at
// multiplier 1 hold six consecutive levels, so such a block is lossless with
// its base 3 above the least value (at most 253). The search's centred
// multiplier rounds to 0 there, a flat palette, so it is tried on its own.
inline constexpr int kNarrowTable = 13;
inline int narrow_base(float lo) { return std::min(int(lo) + 3, 253); }

inline void pack(int base, int mult, int table, const int codes[16], std::uint8_t out[8]) {
  std::uint64_t v = std::uint64_t(base & 255) << 56 | std::uint64_t(mult) << 52 | std::uint64_t(table) << 48;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) v |= std::uint64_t(codes[y * 4 + x]) << (45 - 3 * (x * 4 + y));
  store_be64(v, out);
}

}  // namespace eac
}  // namespace texproc::etc
