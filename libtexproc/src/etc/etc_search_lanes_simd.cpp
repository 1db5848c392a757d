// ETC1 `normal` and `high`, a block per lane: the Highway twin of the
// scalar reference's search in etc_lanes.cpp. `fast` is in
// etc_lanes_simd.cpp; what they share in etc_lanes_simd-inl.h. See
// etc_lanes.h.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "etc/etc_search_lanes_simd.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include <algorithm>
#include <cstdlib>

#include "etc/etc_lanes.h"
#include "etc/etc_lanes_simd-inl.h"
#include "texproc/runtime.h"

HWY_BEFORE_NAMESPACE();
namespace texproc::etc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
namespace {

// The best block so far per lane: its error, flip, mode and halves.
struct Choice {
  V err, flip, diff;
  Fit a, b;
  HWY_INLINE void consider(M m, int fl, bool differential, const Fit& fa, const Fit& fb) {
    const DI d;
    const V e = hn::Add(fa.err, fb.err);
    const M take = hn::And(m, hn::Lt(e, err));
    err = hn::IfThenElse(take, e, err);
    flip = hn::IfThenElse(take, hn::Set(d, fl), flip);
    diff = hn::IfThenElse(take, hn::Set(d, differential ? 1 : 0), diff);
    select_fit(take, fa, a);
    select_fit(take, fb, b);
  }
};

// `normal` and `high`, stage by stage (the reference's search:: functions in
// etc_lanes.cpp): eval, recentre, fit_normal (its seeds in extremes, `high`'s
// per-table refinement and neighbourhood in fit_high), fit_fixed, and per
// flip search_flip.
struct Etc1SearchBatch {
  const DI d{};
  const DF df{};
  const V zero;
  V r[16], g[16], b[16];

  HWY_ATTR Etc1SearchBatch() : zero(hn::Zero(d)) {}  // not a default member initializer: the target's attributes

  HWY_INLINE V quantize(V sum, int bits) const {  // as fast::quantize_centre
    const V num = hn::Add(hn::Mul(hn::Set(d, bits == 5 ? 62 : 30), sum), hn::Set(d, 2040));
    const V q = hn::ConvertTo(d, hn::Div(hn::ConvertTo(df, num), hn::Set(df, 4080.0f)));
    return hn::Min(hn::Max(q, zero), hn::Set(d, bits == 5 ? 31 : 15));
  }
  HWY_INLINE Fit eval(int h, const V q[3], int bits, V t) const {
    const V base[3] = {extend(q[0], bits), extend(q[1], bits), extend(q[2], bits)};
    Fit f = eval_exact_lanes(r, g, b, fast::kHalf[h], base, t);
    for (int c = 0; c < 3; ++c) f.q[c] = q[c];
    return f;
  }
  // Re-centres `cur` (its table per lane) up to `passes` times while that helps.
  HWY_INLINE Fit recentre(int h, int bits, Fit cur, int passes) const {
    const V ma = modifier_of(cur.table, 0), mb = modifier_of(cur.table, 1);
    M active = hn::Eq(zero, zero);
    for (int pass = 0; pass < passes; ++pass) {
      V centre[3] = {zero, zero, zero};
      for (int i = 0; i < 8; ++i) {
        const int p = fast::kHalf[h][i];
        const V idx = cur.idx[i];
        const V mag = hn::IfThenElse(hn::Eq(hn::And(idx, hn::Set(d, 1)), zero), ma, mb);
        const V m = hn::IfThenElse(hn::Lt(idx, hn::Set(d, 2)), mag, hn::Neg(mag));
        centre[0] = hn::Add(centre[0], hn::Sub(r[p], m));
        centre[1] = hn::Add(centre[1], hn::Sub(g[p], m));
        centre[2] = hn::Add(centre[2], hn::Sub(b[p], m));
      }
      const V q1[3] = {quantize(centre[0], bits), quantize(centre[1], bits), quantize(centre[2], bits)};
      const M same = hn::And(hn::And(hn::Eq(q1[0], cur.q[0]), hn::Eq(q1[1], cur.q[1])), hn::Eq(q1[2], cur.q[2]));
      active = hn::AndNot(same, active);
      if (hn::AllFalse(d, active)) break;
      const Fit next = eval(h, q1, bits, cur.table);
      active = hn::And(active, hn::Lt(next.err, cur.err));
      select_fit(active, next, cur);
    }
    return cur;
  }
  // The two tables with the least error (first of equals).
  HWY_INLINE void best_two(const V err[8], V& t1, V& t2) const {
    V e1 = err[0], e2 = hn::Set(d, -1);
    t1 = zero;
    t2 = zero;
    for (int t = 1; t < 8; ++t) {
      const V tv = hn::Set(d, t);
      const M first = hn::Lt(err[t], e1);
      const M second = hn::AndNot(first, hn::Or(hn::Lt(e2, zero), hn::Lt(err[t], e2)));
      e2 = hn::IfThenElse(first, e1, hn::IfThenElse(second, err[t], e2));
      t2 = hn::IfThenElse(first, t1, hn::IfThenElse(second, tv, t2));
      e1 = hn::IfThenElse(first, err[t], e1);
      t1 = hn::IfThenElse(first, tv, t1);
    }
  }
  HWY_INLINE Fit pick(const Fit* fits, V t) const {  // fits[t] per lane
    Fit f = fits[0];
    for (int j = 1; j < 8; ++j) select_fit(hn::Eq(t, hn::Set(d, j)), fits[j], f);
    return f;
  }
  // Half h's brightest and darkest texels (by R + G + B, first of equals).
  HWY_INLINE void extremes(int h, V bright[3], V dark[3]) const {
    const int p0 = fast::kHalf[h][0];
    bright[0] = dark[0] = r[p0];
    bright[1] = dark[1] = g[p0];
    bright[2] = dark[2] = b[p0];
    V bright_sum = hn::Add(hn::Add(r[p0], g[p0]), b[p0]), dark_sum = bright_sum;
    for (int i = 1; i < 8; ++i) {
      const int p = fast::kHalf[h][i];
      const V sp = hn::Add(hn::Add(r[p], g[p]), b[p]);
      const M up = hn::Gt(sp, bright_sum), down = hn::Lt(sp, dark_sum);
      bright_sum = hn::IfThenElse(up, sp, bright_sum);
      dark_sum = hn::IfThenElse(down, sp, dark_sum);
      const V px[3] = {r[p], g[p], b[p]};
      for (int c = 0; c < 3; ++c) {
        bright[c] = hn::IfThenElse(up, px[c], bright[c]);
        dark[c] = hn::IfThenElse(down, px[c], dark[c]);
      }
    }
  }
  // start replaced by the fit at base = px - m (quantized) where better.
  HWY_INLINE void seed(int h, int bits, Fit& start, const V px[3], V m, V t) const {
    const int top = bits == 5 ? 31 : 15;
    auto quantize8 = [&](V v) {
      const V q = hn::ConvertTo(
          d, hn::Add(hn::Div(hn::ConvertTo(df, hn::Mul(v, hn::Set(d, top))), hn::Set(df, 255.0f)), hn::Set(df, 0.5f)));
      return hn::Min(hn::Max(q, zero), hn::Set(d, top));
    };
    const V q[3] = {quantize8(hn::Sub(px[0], m)), quantize8(hn::Sub(px[1], m)), quantize8(hn::Sub(px[2], m))};
    const Fit f = eval(h, q, bits, t);
    select_fit(hn::Lt(f.err, start.err), f, start);
  }
  // `high`: every table seeded from the extremes minus its extreme
  // modifiers and re-centred three times, then the +-1 neighbourhood of the
  // two best bases; per_table (if set) gets every table's fit and the best.
  HWY_INLINE Fit fit_high(int h, int bits, const Fit at_mean[8], const V bright[3], const V dark[3],
                          Fit* per_table) const {
    const int top = bits == 5 ? 31 : 15;
    Fit best, refined[8];
    V err[8];
    for (int t = 0; t < 8; ++t) {
      Fit start = at_mean[t];
      const V tv = hn::Set(d, t);
      const int seeds[4] = {kModifiers[t][1], -kModifiers[t][1], kModifiers[t][0], -kModifiers[t][0]};
      for (int sd = 0; sd < 4; ++sd) seed(h, bits, start, sd % 2 ? dark : bright, hn::Set(d, seeds[sd]), tv);
      refined[t] = recentre(h, bits, start, 3);
      err[t] = refined[t].err;
      if (t == 0) {
        best = refined[0];
      } else {
        select_fit(hn::Lt(refined[t].err, best.err), refined[t], best);
      }
    }
    V t1, t2;
    best_two(err, t1, t2);
    for (int which = 0; which < 2; ++which) {
      const Fit base = pick(refined, which ? t2 : t1);
      for (int dr = -1; dr <= 1; ++dr)
        for (int dg = -1; dg <= 1; ++dg)
          for (int db = -1; db <= 1; ++db) {
            const V q[3] = {hn::Add(base.q[0], hn::Set(d, dr)), hn::Add(base.q[1], hn::Set(d, dg)),
                            hn::Add(base.q[2], hn::Set(d, db))};
            M valid = hn::Eq(zero, zero);
            for (int c = 0; c < 3; ++c)
              valid = hn::And(valid, hn::And(hn::Not(hn::Lt(q[c], zero)), hn::Not(hn::Gt(q[c], hn::Set(d, top)))));
            if (hn::AllFalse(d, valid)) continue;
            const Fit f = eval(h, q, bits, base.table);
            select_fit(hn::And(valid, hn::Lt(f.err, best.err)), f, best);
          }
    }
    if (per_table) {
      std::copy(refined, refined + 8, per_table);
      per_table[8] = best;
    }
    return best;
  }
  // Half h at `bits`: every table at the mean; `normal`: the best two
  // seeded from the extremes minus the far modifier and re-centred twice;
  // `high`: fit_high.
  HWY_INLINE Fit fit_normal(int h, int bits, bool high, Fit* per_table) const {
    V sum[3] = {zero, zero, zero};
    for (int i = 0; i < 8; ++i) {
      const int p = fast::kHalf[h][i];
      sum[0] = hn::Add(sum[0], r[p]);
      sum[1] = hn::Add(sum[1], g[p]);
      sum[2] = hn::Add(sum[2], b[p]);
    }
    const V q0[3] = {quantize(sum[0], bits), quantize(sum[1], bits), quantize(sum[2], bits)};
    Fit at_mean[8];
    V err[8];
    for (int t = 0; t < 8; ++t) {
      at_mean[t] = eval(h, q0, bits, hn::Set(d, t));
      err[t] = at_mean[t].err;
    }
    V bright[3], dark[3];
    extremes(h, bright, dark);
    if (high) return fit_high(h, bits, at_mean, bright, dark, per_table);
    V t1, t2;
    best_two(err, t1, t2);
    Fit start = pick(at_mean, t1);
    const V far = modifier_of(t1, 1);
    seed(h, bits, start, bright, far, t1);
    seed(h, bits, start, dark, hn::Neg(far), t1);
    Fit best = recentre(h, bits, start, 2);
    Fit start2 = pick(at_mean, t2);
    const V far2 = modifier_of(t2, 1);
    seed(h, bits, start2, bright, far2, t2);
    seed(h, bits, start2, dark, hn::Neg(far2), t2);
    const Fit second = recentre(h, bits, start2, 2);
    select_fit(hn::Lt(second.err, best.err), second, best);
    return best;
  }
  HWY_INLINE Fit fit_fixed(int h, const V q[3]) const {
    Fit best = eval(h, q, 5, zero);
    for (int t = 1; t < 8; ++t) {
      const Fit f = eval(h, q, 5, hn::Set(d, t));
      select_fit(hn::Lt(f.err, best.err), f, best);
    }
    return best;
  }
  // One flip's candidates: the halves' fits where the delta reaches; at
  // `high` every pair of per-table fits it reaches; the individual mode
  // (where it must, or at `high` always); either base pulled within the
  // delta of the other (at `high` with its neighbours).
  HWY_INLINE void search_flip(int flip, bool high, bool differential_only, const Fit f5[4], const Fit tables[4][9],
                              Choice& best) const {
    const int a = 2 * flip, bh = a + 1;
    const M fits = reach_of(f5[a].q, f5[bh].q);
    best.consider(fits, flip, true, f5[a], f5[bh]);
    if (high)
      for (int ta = 0; ta < 9; ++ta)
        for (int tb = 0; tb < 9; ++tb) {
          const M ok = reach_of(tables[a][ta].q, tables[bh][tb].q);
          if (!hn::AllFalse(d, ok)) best.consider(ok, flip, true, tables[a][ta], tables[bh][tb]);
        }
    if (hn::AllTrue(d, fits) && !high) return;
    const M far = hn::Not(fits);
    if (!differential_only)  // `high`: always
      best.consider(high ? hn::Eq(zero, zero) : far, flip, false, fit_normal(a, 4, high, nullptr),
                    fit_normal(bh, 4, high, nullptr));
    if (hn::AllTrue(d, fits)) return;
    V qa[3], qb[3];
    for (int c = 0; c < 3; ++c)
      qa[c] = hn::Min(hn::Max(f5[a].q[c], hn::Sub(f5[bh].q[c], hn::Set(d, 3))), hn::Add(f5[bh].q[c], hn::Set(d, 4)));
    const Fit pa = fit_fixed(a, qa);
    best.consider(far, flip, true, pa, f5[bh]);
    for (int c = 0; c < 3; ++c)
      qb[c] = hn::Min(hn::Max(f5[bh].q[c], hn::Sub(f5[a].q[c], hn::Set(d, 4))), hn::Add(f5[a].q[c], hn::Set(d, 3)));
    const Fit pb = fit_fixed(bh, qb);
    best.consider(far, flip, true, f5[a], pb);
    if (!high) return;
    const V top5 = hn::Set(d, 31);
    auto in_range = [&](const V q[3]) {
      M ok = hn::Eq(zero, zero);
      for (int c = 0; c < 3; ++c) ok = hn::And(ok, hn::And(hn::Not(hn::Lt(q[c], zero)), hn::Not(hn::Gt(q[c], top5))));
      return ok;
    };
    for (int n = 0; n < 27; ++n) {  // as the reference
      if (n == 13) continue;
      const int dd[3] = {n / 9 - 1, n / 3 % 3 - 1, n % 3 - 1};
      V q[3];
      for (int c = 0; c < 3; ++c) q[c] = hn::Add(qa[c], hn::Set(d, dd[c]));
      M ok = hn::And(far, hn::And(in_range(q), reach_of(q, f5[bh].q)));
      if (!hn::AllFalse(d, ok)) best.consider(ok, flip, true, eval(a, q, 5, pa.table), f5[bh]);
      for (int c = 0; c < 3; ++c) q[c] = hn::Add(qb[c], hn::Set(d, dd[c]));
      ok = hn::And(far, hn::And(in_range(q), reach_of(f5[a].q, q)));
      if (!hn::AllFalse(d, ok)) best.consider(ok, flip, true, f5[a], eval(bh, q, 5, pb.table));
    }
  }
};

}  // namespace

void Etc1SearchLanes(const std::uint32_t texel[16][kEtcBatch], int count, bool high, bool differential_only,
                     std::uint8_t out[][8], std::int32_t error[]) {
  const DI d;
  const int lanes = int(hn::Lanes(d));
  for (int k0 = 0; k0 < count; k0 += lanes) {
    Etc1SearchBatch batch;
    load_texels(texel, k0, batch.r, batch.g, batch.b);
    Fit f5[4], tables[4][9];
    for (int h = 0; h < 4; ++h) f5[h] = batch.fit_normal(h, 5, high, high ? tables[h] : nullptr);
    Choice best;
    best.err = hn::Set(d, 0x7fffffff);
    best.flip = hn::Zero(d);
    best.diff = hn::Zero(d);
    best.a = f5[0];
    best.b = f5[1];
    for (int flip = 0; flip < 2; ++flip) batch.search_flip(flip, high, differential_only, f5, tables, best);
    HWY_ALIGN std::int32_t err_o[kEtcBatch];
    hn::Store(best.err, d, err_o);
    for (int k = 0; k < lanes && k0 + k < count; ++k) error[k0 + k] = err_o[k];
    pack_blocks(best.flip, best.diff, best.a, best.b, k0, count, out);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace texproc::etc
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace texproc::etc {
HWY_EXPORT(Etc1SearchLanes);

void etc1_search_lanes(const std::uint32_t texel[16][kEtcBatch], int count, bool high, bool differential_only,
                       std::uint8_t out[][8], std::int32_t error[]) {
  if (force_scalar()) return ref::etc1_search_lanes(texel, count, high, differential_only, out, error);
  HWY_DYNAMIC_DISPATCH(Etc1SearchLanes)(texel, count, high, differential_only, out, error);
}
}  // namespace texproc::etc
#endif
