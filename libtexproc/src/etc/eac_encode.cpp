// EAC blocks: `fast` to `high` through the lane encoder (eac_lanes), `max`
// here: every multiplier and table around each one's centring base, scored
// under the exact decoding.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "block/value_palette.h"
#include "block/block_gather.h"
#include "etc/eac_lanes.h"
#include "etc/etc_encode.h"
#include "etc/etc_search.h"
#include "etc/etc_tables.h"

namespace texproc::etc {

namespace {

int eac_value(EacKind kind, int base, int mult, int m) {
  switch (kind) {
    case EacKind::alpha8:
      return clamp255(base + m * mult);
    case EacKind::r11:
      return std::clamp(base * 8 + 4 + (mult ? m * mult * 8 : m), 0, 2047);
    case EacKind::r11_signed:
      return std::clamp(base * 8 + (mult ? m * mult * 8 : m), -1023, 1023);
  }
  return 0;
}

struct EacCandidate {
  double err = std::numeric_limits<double>::max();
  int base = 0, mult = 0, table = 0;
  std::uint8_t idx[16] = {};
};

void eac_try(const double t[16], EacKind kind, int base, int mult, int table, EacCandidate& best) {
  double vals[8], errors[16];
  for (int k = 0; k < 8; ++k) vals[k] = eac_value(kind, base, mult, kEacModifiers[table][k]);
  std::uint8_t idx[16];
  value_palette_nearest(t, vals, idx, errors);  // each value's nearest of the 8 (SIMD twins, as for BC4)
  double err = 0;
  for (int i = 0; i < 16; ++i) err += errors[i];
  if (err >= best.err) return;
  best.err = err;
  best.base = base;
  best.mult = mult;
  best.table = table;
  std::memcpy(best.idx, idx, 16);
}

}  // namespace

double encode_eac_block(const float targets[16], EacKind kind, Quality q, std::uint8_t out[8]) {
  const EacLevel& level = eac_level(q);  // eac_levels.h
  if (level.lanes) {                     // as whole images do: eac_lanes.h
    float v[16][kEacBatch] = {};
    for (int i = 0; i < 16; ++i) v[i][0] = targets[i];
    std::uint8_t block[1][8];
    float err[1];
    eac_encode_lanes(v, 1, kind, level.lanes_window, block, err);
    std::memcpy(out, block[0], 8);
    return err[0];
  }
  // Block by block (`max`): the level's window around each table's
  // estimate (every multiplier and +-8 bases).
  const double lo_end = kind == EacKind::r11_signed ? -1023 : 0, hi_end = kind == EacKind::alpha8 ? 255
                                                                          : kind == EacKind::r11  ? 2047
                                                                                                  : 1023;
  double t[16], lo = hi_end, hi = lo_end;
  for (int i = 0; i < 16; ++i) {
    t[i] = std::clamp(double(targets[i]), lo_end, hi_end);
    lo = std::min(lo, t[i]);
    hi = std::max(hi, t[i]);
  }
  const int base_lo = kind == EacKind::r11_signed ? -127 : 0, base_hi = kind == EacKind::r11_signed ? 127 : 255;
  const double unit = kind == EacKind::alpha8 ? 1.0 : 8.0, offset = kind == EacKind::r11 ? 4.0 : 0.0;
  const EacWindow& window = level.block_window;
  EacCandidate best;
  const double centre = (lo + hi) / 2;
  for (int table = 0; table < 16; ++table) {
    const int mn = kEacModifiers[table][3], mx = kEacModifiers[table][7];
    const double mf = (hi - lo) / ((mx - mn) * unit);
    const int m0 = int(std::lround(mf));
    for (int mult = std::max(0, m0 - window.mult_below); mult <= std::min(15, m0 + window.mult_above); ++mult) {
      // Multiplier 0 steps by the modifiers themselves (R11: 1/8 of the
      // multiplier-1 step); for 8-bit alpha it is a constant block.
      const double step = mult == 0 ? (kind == EacKind::alpha8 ? 0.0 : 1.0) : mult * unit;
      const double bf = (centre - offset - (mn + mx) / 2.0 * step) / unit;
      const int b0 = std::clamp(int(std::lround(bf)), base_lo, base_hi);
      for (int base = std::max(base_lo, b0 - window.base_radius); base <= std::min(base_hi, b0 + window.base_radius);
           ++base) {
        eac_try(t, kind, base, mult, table, best);
      }
    }
  }
  std::uint64_t v = 0;
  put(v, 63, 8, best.base & 255);
  put(v, 55, 4, best.mult);
  put(v, 51, 4, best.table);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) put(v, 47 - 3 * (x * 4 + y), 3, best.idx[y * 4 + x]);
  store_be64(v, out);
  return best.err;
}

}  // namespace texproc::etc
