// What both twins of the ETC half-block scoring use (etc_eval.cpp, the
// scalar reference, and etc_eval_simd.cpp).
#pragma once

#include "etc/etc_tables.h"

namespace texproc::etc {

// The palette of base `col` and table `t` (clamped), and whether any entry clamps.
inline bool make_palette(const int col[3], int t, bool non_opaque, int pal[4][3]) {
  bool clamps = false;
  for (int k = 0; k < 4; ++k) {
    const int m = non_opaque && (k == 0 || k == 2) ? 0 : kModifiers[t][k];
    for (int c = 0; c < 3; ++c) {
      pal[k][c] = clamp255(col[c] + m);
      clamps |= pal[k][c] != col[c] + m;
    }
  }
  return clamps;
}

}  // namespace texproc::etc
