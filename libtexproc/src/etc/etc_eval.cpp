// The scalar reference of etc_eval.h (namespace ref): what etc_eval_simd.cpp, its
// Highway twin, must equal byte for byte (tests compare them on every target).
#include "etc/etc_eval.h"

#include "etc/etc_eval_shared.h"
#include "etc/etc_tables.h"

namespace texproc::etc {

namespace ref {
long eval_half(const HalfTexels& tx, const int col[3], int t, bool non_opaque, std::uint8_t idx[8]) {
  int pal[4][3];
  const bool clamps = make_palette(col, t, non_opaque, pal);
  const int a = kModifiers[t][0], b = kModifiers[t][1];
  const int base_sum = col[0] + col[1] + col[2];
  long err = 0;
  for (int i = 0; i < 8; ++i) {
    if (non_opaque && tx.transparent[i]) {
      idx[i] = 2;
      continue;
    }
    const int px[3] = {tx.r[i], tx.g[i], tx.b[i]};
    int bk;
    long best;
    if (!clamps) {
      const int d2 = 2 * (tx.sum[i] - base_sum);
      if (non_opaque) {
        bk = d2 < -3 * b ? 3 : d2 < 3 * b ? 0 : 1;
      } else {
        bk = d2 < -3 * (a + b) ? 3 : d2 < 0 ? 2 : d2 < 3 * (a + b) ? 0 : 1;
      }
      const long dr = pal[bk][0] - px[0], dg = pal[bk][1] - px[1], db = pal[bk][2] - px[2];
      best = dr * dr + dg * dg + db * db;
    } else {
      best = -1;
      bk = 0;
      for (int k = 0; k < 4; ++k) {
        if (non_opaque && k == 2) continue;
        const long dr = pal[k][0] - px[0], dg = pal[k][1] - px[1], db = pal[k][2] - px[2];
        const long e = dr * dr + dg * dg + db * db;
        if (best < 0 || e < best) {
          best = e;
          bk = k;
        }
      }
    }
    idx[i] = std::uint8_t(bk);
    err += best;
  }
  return err;
}
}  // namespace ref

}  // namespace texproc::etc
