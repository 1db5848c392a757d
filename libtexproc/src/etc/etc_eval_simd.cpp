// ETC half-block scoring: the Highway twin of the scalar reference in
// etc_eval.cpp (lanes over the 8 texels; 32-bit integers, so the results are identical).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "etc/etc_eval_simd.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include "etc/etc_eval.h"
#include "etc/etc_eval_shared.h"
#include "etc/etc_tables.h"
#include "texproc/runtime.h"

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

EvalHalfFn eval_half_kernel() { return force_scalar() ? &ref::eval_half : &HWY_DYNAMIC_DISPATCH(EvalHalf); }

long eval_half(const HalfTexels& tx, const int col[3], int t, bool non_opaque, std::uint8_t idx[8]) {
  if (force_scalar()) return ref::eval_half(tx, col, t, non_opaque, idx);
  return HWY_DYNAMIC_DISPATCH(EvalHalf)(tx, col, t, non_opaque, idx);
}
}  // namespace texproc::etc
#endif
