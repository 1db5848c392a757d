// EAC in lanes: the Highway twin of the scalar reference in
// eac_lanes.cpp (one block at a time, plainly); both fill the same per-block parameters, which one packer
// writes. See eac_lanes.h.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "etc/eac_lanes_simd.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include <algorithm>
#include <cmath>

#include "block/block_lanes_simd-inl.h"
#include "etc/eac_lanes.h"
#include "etc/eac_lanes_shared.h"
#include "etc/etc_tables.h"
#include "texproc/runtime.h"

HWY_BEFORE_NAMESPACE();
namespace texproc::etc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
namespace {
// The batch's types (block/block_lanes_simd-inl.h).
using namespace texproc::HWY_NAMESPACE;

}  // namespace

void EacEncodeLanes(const float v[16][kEacBatch], int count, EacKind kind, const EacWindow& window,
                    std::uint8_t out[][8], float error[]) {
  const DF df;
  const DI d;
  const int lanes = int(hn::Lanes(df));
  const eac::Kind K = eac::kind_of(kind);
  const VF lo_end = hn::Set(df, K.lo_end), hi_end = hn::Set(df, K.hi_end), half = hn::Set(df, 0.5f);
  for (int k0 = 0; k0 < count; k0 += lanes) {
    VF t[16], lo = hi_end, hi = lo_end;
    for (int i = 0; i < 16; ++i) {
      t[i] = hn::Min(hn::Max(hn::LoadU(df, v[i] + k0), lo_end), hi_end);
      lo = hn::Min(lo, t[i]);
      hi = hn::Max(hi, t[i]);
    }
    const VF centre = hn::Mul(hn::Add(lo, hi), half);
    VF best = hn::Set(df, -1.0f);
    V best_base = hn::Zero(d), best_mult = best_base, best_table = best_base;
    // As eac::candidate_error, per lane: the palette of table `table` from
    // `at` (base * unit + offset) in steps of `scale`, clamped; each value
    // at its entry by the seven midpoints (the palette ascends, so the last
    // midpoint a value lies above picks it).
    auto candidate_error = [&](V at, V scale, int table) {
      VF pal[8], mid[7];
      for (int j = 0; j < 8; ++j) {
        const V value = hn::Add(at, hn::Mul(hn::Set(d, kEacModifiers[table][eac::kAscending[j]]), scale));
        pal[j] = hn::Min(hn::Max(hn::ConvertTo(df, value), lo_end), hi_end);
      }
      for (int j = 0; j < 7; ++j) mid[j] = hn::Mul(hn::Add(pal[j], pal[j + 1]), half);
      VF err = hn::Zero(df);
      for (int i = 0; i < 16; ++i) {
        VF p = pal[0];
        for (int j = 0; j < 7; ++j) p = hn::IfThenElse(hn::Gt(t[i], mid[j]), pal[j + 1], p);
        const VF diff = hn::Sub(t[i], p);
        err = hn::Add(err, hn::Mul(diff, diff));
      }
      return err;
    };
    auto take_where = [&](hn::Mask<decltype(d)> take, VF err, V base, V mult, int table) {
      best = hn::IfThenElse(hn::RebindMask(df, take), err, best);
      best_base = hn::IfThenElse(take, base, best_base);
      best_mult = hn::IfThenElse(take, mult, best_mult);
      best_table = hn::IfThenElse(take, hn::Set(d, table), best_table);
    };
    for (int table = 0; table < 16; ++table) {
      const int mn = kEacModifiers[table][3], mx = kEacModifiers[table][7];
      const V m0 =
          hn::ConvertTo(d, hn::Floor(hn::Add(hn::Div(hn::Sub(hi, lo), hn::Set(df, float(mx - mn) * K.unit)), half)));
      for (int dm = -window.mult_below; dm <= window.mult_above; ++dm) {
        const V mult = hn::Add(m0, hn::Set(d, dm));
        auto valid = hn::And(hn::Not(hn::Lt(mult, hn::Zero(d))), hn::Not(hn::Gt(mult, hn::Set(d, 15))));
        if (hn::AllFalse(d, valid)) continue;
        const auto zero_mult = hn::Eq(mult, hn::Zero(d));
        const VF step = hn::IfThenElse(hn::RebindMask(df, zero_mult), hn::Set(df, float(K.zero_step)),
                                       hn::Mul(hn::ConvertTo(df, mult), hn::Set(df, K.unit)));
        const VF bf =
            hn::Div(hn::Sub(hn::Sub(centre, hn::Set(df, K.offset)), hn::Mul(hn::Set(df, float(mn + mx) * 0.5f), step)),
                    hn::Set(df, K.unit));
        const V b0 = hn::Min(hn::Max(hn::ConvertTo(d, hn::Floor(hn::Add(bf, half))), hn::Set(d, K.base_lo)),
                             hn::Set(d, K.base_hi));
        // Per modifier: what it adds (multiplier 0: the modifier unscaled).
        const V scale = hn::IfThenElse(zero_mult, hn::Set(d, K.zero_step), hn::Mul(mult, hn::Set(d, K.unit_i)));
        for (int db = -window.base_radius; db <= window.base_radius; ++db) {
          const V base = hn::Add(b0, hn::Set(d, db));
          const auto ok = hn::And(valid, hn::And(hn::Not(hn::Lt(base, hn::Set(d, K.base_lo))),
                                                 hn::Not(hn::Gt(base, hn::Set(d, K.base_hi)))));
          if (hn::AllFalse(d, ok)) continue;
          const V at = hn::Add(hn::Mul(base, hn::Set(d, K.unit_i)), hn::Set(d, K.offset_i));
          const VF err = candidate_error(at, scale, table);
          take_where(hn::And(ok, hn::RebindMask(d, hn::Or(hn::Lt(best, hn::Zero(df)), hn::Lt(err, best)))), err, base,
                     mult, table);
        }
      }
    }
    if (kind == EacKind::alpha8) {  // as the reference: a narrow range in table 13 at multiplier 1
      const auto narrow = hn::RebindMask(d, hn::And(hn::Gt(hi, lo), hn::Le(hn::Sub(hi, lo), hn::Set(df, 5.0f))));
      if (!hn::AllFalse(d, narrow)) {
        const V base = hn::Min(hn::Add(hn::ConvertTo(d, lo), hn::Set(d, 3)), hn::Set(d, 253));
        const V one = hn::Set(d, 1);  // alpha8: unit 1, offset 0, so `at` is the base and the step 1
        const VF err = candidate_error(base, one, eac::kNarrowTable);
        take_where(hn::And(narrow, hn::RebindMask(d, hn::Lt(err, best))), err, base, one, eac::kNarrowTable);
      }
    }
    HWY_ALIGN std::int32_t base_o[kEacBatch], mult_o[kEacBatch], table_o[kEacBatch];
    HWY_ALIGN float err_o[kEacBatch], t_o[16][kEacBatch];
    hn::Store(best_base, d, base_o);
    hn::Store(best_mult, d, mult_o);
    hn::Store(best_table, d, table_o);
    hn::Store(best, df, err_o);
    for (int i = 0; i < 16; ++i) hn::Store(t[i], df, t_o[i]);
    for (int k = 0; k < lanes && k0 + k < count; ++k) {
      float tk[16];
      int codes[16];
      for (int i = 0; i < 16; ++i) tk[i] = t_o[i][k];
      eac::codes_of(K, tk, base_o[k], mult_o[k], table_o[k], codes);
      eac::pack(base_o[k], mult_o[k], table_o[k], codes, out[k0 + k]);
      error[k0 + k] = err_o[k];
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace texproc::etc
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace texproc::etc {
HWY_EXPORT(EacEncodeLanes);

void eac_encode_lanes(const float v[16][kEacBatch], int count, EacKind kind, const EacWindow& window,
                      std::uint8_t out[][8], float error[]) {
  if (force_scalar()) return ref::eac_encode_lanes(v, count, kind, window, out, error);
  HWY_DYNAMIC_DISPATCH(EacEncodeLanes)(v, count, kind, window, out, error);
}
}  // namespace texproc::etc
#endif
