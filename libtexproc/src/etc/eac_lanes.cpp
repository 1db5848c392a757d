// The scalar reference of eac_lanes.h (namespace ref): what eac_lanes_simd.cpp, its
// Highway twin, must equal byte for byte (tests compare them on every target).
#include "etc/eac_lanes.h"
#include "etc/eac_lanes_shared.h"

#include <algorithm>
#include <cmath>

#include "etc/etc_tables.h"

namespace texproc::etc {
namespace ref {

void eac_encode_lanes(const float v[16][kEacBatch], int count, EacKind kind, const EacWindow& window,
                      std::uint8_t out[][8], float error[]) {
  const eac::Kind K = eac::kind_of(kind);
  for (int k = 0; k < count; ++k) {
    float t[16], lo = K.hi_end, hi = K.lo_end;
    for (int i = 0; i < 16; ++i) {
      t[i] = std::min(std::max(v[i][k], K.lo_end), K.hi_end);
      lo = std::min(lo, t[i]);
      hi = std::max(hi, t[i]);
    }
    const float centre = (lo + hi) * 0.5f;
    float best = -1.0f;
    int best_base = 0, best_mult = 0, best_table = 0;
    for (int table = 0; table < 16; ++table) {
      const int mn = kEacModifiers[table][3], mx = kEacModifiers[table][7];
      const int m0 = int(std::floor((hi - lo) / (float(mx - mn) * K.unit) + 0.5f));
      for (int mult = m0 - window.mult_below; mult <= m0 + window.mult_above; ++mult) {
        if (mult < 0 || mult > 15) continue;
        const float step = mult == 0 ? float(K.zero_step) : float(mult) * K.unit;
        const float bf = (centre - K.offset - float(mn + mx) * 0.5f * step) / K.unit;
        const int b0 = std::clamp(int(std::floor(bf + 0.5f)), K.base_lo, K.base_hi);
        for (int base = b0 - window.base_radius; base <= b0 + window.base_radius; ++base) {
          if (base < K.base_lo || base > K.base_hi) continue;
          const float err = eac::candidate_error(K, t, base, mult, table);
          if (best < 0.0f || err < best) {
            best = err;
            best_base = base;
            best_mult = mult;
            best_table = table;
          }
        }
      }
    }
    if (kind == EacKind::alpha8 && hi > lo && hi - lo <= 5.0f) {
      const int base = eac::narrow_base(lo);
      const float err = eac::candidate_error(K, t, base, 1, eac::kNarrowTable);
      if (err < best) {
        best = err;
        best_base = base;
        best_mult = 1;
        best_table = eac::kNarrowTable;
      }
    }
    int codes[16];
    eac::codes_of(K, t, best_base, best_mult, best_table, codes);
    eac::pack(best_base, best_mult, best_table, codes, out[k]);
    error[k] = best;
  }
}

}  // namespace ref
}  // namespace texproc::etc
