// ETC half-block scoring: the scalar reference and its Highway twin (lanes
// over the 8 texels; 32-bit integers, so the results are identical).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "etc/etc_eval_simd.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include "etc/etc_eval.h"
#include "etc/etc_tables.h"
#include "texproc/runtime.h"

#ifndef TEXPROC_ETC_EVAL_COMMON
#define TEXPROC_ETC_EVAL_COMMON
namespace texproc::etc {
namespace {
// The palette of base `col` and table `t` (clamped), and whether any entry clamps.
bool make_palette(const int col[3], int t, bool non_opaque, int pal[4][3]) {
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
}  // namespace

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
        if (best < 0 || e < best) best = e, bk = k;
      }
    }
    idx[i] = std::uint8_t(bk);
    err += best;
  }
  return err;
}
}  // namespace ref
}  // namespace texproc::etc
#endif

HWY_BEFORE_NAMESPACE();
namespace texproc::etc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

long EvalHalf(const HalfTexels& tx, const int col[3], int t, bool non_opaque, std::uint8_t idx[8]) {
  const hn::CappedTag<std::int32_t, 8> d;
  const int lanes = int(hn::Lanes(d));
  int pal[4][3];
  const bool clamps = make_palette(col, t, non_opaque, pal);
  const int a = kModifiers[t][0], b = kModifiers[t][1];
  const int base_sum = col[0] + col[1] + col[2];
  long err = 0;
  HWY_ALIGN std::int32_t idx_out[8], err_out[8];
  for (int i0 = 0; i0 < 8; i0 += lanes) {
    const auto r = hn::LoadU(d, tx.r + i0), g = hn::LoadU(d, tx.g + i0), bl = hn::LoadU(d, tx.b + i0);
    auto pick = hn::Zero(d);
    auto best = hn::Zero(d);
    auto error_of = [&](int k) {
      const auto dr = hn::Sub(hn::Set(d, pal[k][0]), r), dg = hn::Sub(hn::Set(d, pal[k][1]), g),
                 db = hn::Sub(hn::Set(d, pal[k][2]), bl);
      return hn::Add(hn::Add(hn::Mul(dr, dr), hn::Mul(dg, dg)), hn::Mul(db, db));
    };
    if (!clamps) {
      const auto d2 = hn::Mul(hn::Set(d, 2), hn::Sub(hn::LoadU(d, tx.sum + i0), hn::Set(d, base_sum)));
      if (non_opaque) {
        // d2 < -3b ? 3 : d2 < 3b ? 0 : 1
        pick = hn::IfThenElse(hn::Lt(d2, hn::Set(d, 3 * b)), hn::Zero(d), hn::Set(d, 1));
        pick = hn::IfThenElse(hn::Lt(d2, hn::Set(d, -3 * b)), hn::Set(d, 3), pick);
      } else {
        pick = hn::IfThenElse(hn::Lt(d2, hn::Set(d, 3 * (a + b))), hn::Zero(d), hn::Set(d, 1));
        pick = hn::IfThenElse(hn::Lt(d2, hn::Zero(d)), hn::Set(d, 2), pick);
        pick = hn::IfThenElse(hn::Lt(d2, hn::Set(d, -3 * (a + b))), hn::Set(d, 3), pick);
      }
      best = error_of(0);
      for (int k = 1; k < 4; ++k) best = hn::IfThenElse(hn::Eq(pick, hn::Set(d, k)), error_of(k), best);
    } else {
      // The first least error over k = 0..3 (2 skipped for punch-through).
      best = error_of(0);
      for (int k = 1; k < 4; ++k) {
        if (non_opaque && k == 2) continue;
        const auto e = error_of(k);
        const auto better = hn::Lt(e, best);
        best = hn::IfThenElse(better, e, best);
        pick = hn::IfThenElse(better, hn::Set(d, k), pick);
      }
    }
    if (non_opaque) {
      const auto transparent = hn::Ne(hn::LoadU(d, tx.transparent + i0), hn::Zero(d));
      pick = hn::IfThenElse(transparent, hn::Set(d, 2), pick);
      best = hn::IfThenElse(transparent, hn::Zero(d), best);
    }
    hn::StoreU(pick, d, idx_out + i0);
    hn::StoreU(best, d, err_out + i0);
  }
  for (int i = 0; i < 8; ++i) {
    idx[i] = std::uint8_t(idx_out[i]);
    err += err_out[i];
  }
  return err;
}

}  // namespace HWY_NAMESPACE
}  // namespace texproc::etc
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace texproc::etc {
HWY_EXPORT(EvalHalf);

long eval_half(const HalfTexels& tx, const int col[3], int t, bool non_opaque, std::uint8_t idx[8]) {
  if (force_scalar()) return ref::eval_half(tx, col, t, non_opaque, idx);
  return HWY_DYNAMIC_DISPATCH(EvalHalf)(tx, col, t, non_opaque, idx);
}
}  // namespace texproc::etc
#endif
