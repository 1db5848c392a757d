// ETC1 `fast`, a block per lane: the Highway twin of the scalar reference
// in etc_lanes.cpp (one block at a time, plainly), which packs the blocks in
// lanes too (the reference's packer is the plain statement of the layout).
// `normal` and `high` are in etc_search_lanes_simd.cpp; what they share in
// etc_lanes_simd-inl.h. See etc_lanes.h.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "etc/etc_lanes_simd.cpp"
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

// `fast`, stage by stage (the reference's fast:: functions in etc_lanes.cpp):
// spread_tables, fit, choose (the flip and mode per lane), reclamp.
struct Etc1FastBatch {
  const DI d{};
  const DF df{};
  V r[16], g[16], b[16];
  V t0[4];  // per half: the table whose modifiers are nearest the half's spread

  HWY_INLINE void spread_tables() {
    for (int h = 0; h < 4; ++h) {
      V total = hn::Zero(d), spread = hn::Zero(d);
      for (int i = 0; i < 8; ++i) {
        const int p = fast::kHalf[h][i];
        total = hn::Add(total, hn::Add(hn::Add(r[p], g[p]), b[p]));
      }
      for (int i = 0; i < 8; ++i) {
        const int p = fast::kHalf[h][i];
        spread = hn::Add(spread, hn::Abs(hn::Sub(hn::Mul(hn::Set(d, 8), hn::Add(hn::Add(r[p], g[p]), b[p])), total)));
      }
      V best_t = hn::Zero(d), best_dist = hn::Abs(hn::Sub(hn::Set(d, fast::kMid96[0]), spread));
      for (int t = 1; t < 8; ++t) {
        const V dist = hn::Abs(hn::Sub(hn::Set(d, fast::kMid96[t]), spread));
        const M closer = hn::Lt(dist, best_dist);
        best_dist = hn::IfThenElse(closer, dist, best_dist);
        best_t = hn::IfThenElse(closer, hn::Set(d, t), best_t);
      }
      t0[h] = best_t;
    }
  }

  // Half h at `bits` (base: the mean, or fixed_q): three tables around t0
  // (or the far-reaching table), each texel at the modifier nearest a third
  // of its offset from the base (unclamped).
  HWY_INLINE void fit(int h, int bits, Fit& best, const V* fixed_q) const {
    V sum[3] = {hn::Zero(d), hn::Zero(d), hn::Zero(d)};
    for (int i = 0; i < 8; ++i) {
      const int p = fast::kHalf[h][i];
      sum[0] = hn::Add(sum[0], r[p]);
      sum[1] = hn::Add(sum[1], g[p]);
      sum[2] = hn::Add(sum[2], b[p]);
    }
    V base[3];
    for (int c = 0; c < 3; ++c) {
      const V num = hn::Add(hn::Mul(hn::Set(d, bits == 5 ? 62 : 30), sum[c]), hn::Set(d, 2040));
      best.q[c] = fixed_q ? fixed_q[c] : hn::ConvertTo(d, hn::Div(hn::ConvertTo(df, num), hn::Set(df, 4080.0f)));
      base[c] = extend(best.q[c], bits);
    }
    const V zero = hn::Zero(d);
    V d2[8], dl[8];
    for (int i = 0; i < 8; ++i) {
      const int p = fast::kHalf[h][i];
      const V dr = hn::Sub(r[p], base[0]), dg = hn::Sub(g[p], base[1]), db = hn::Sub(b[p], base[2]);
      d2[i] = hn::Add(hn::Add(hn::Mul(dr, dr), hn::Mul(dg, dg)), hn::Mul(db, db));
      dl[i] = hn::Add(hn::Add(dr, dg), db);
    }
    V reach = zero, t_far = zero;
    for (int i = 0; i < 8; ++i) reach = hn::Max(reach, hn::Abs(dl[i]));
    V far_dist = hn::Abs(hn::Sub(hn::Set(d, 3 * kModifiers[0][1]), reach));
    for (int t = 1; t < 8; ++t) {
      const V dist = hn::Abs(hn::Sub(hn::Set(d, 3 * kModifiers[t][1]), reach));
      const M closer = hn::Lt(dist, far_dist);
      far_dist = hn::IfThenElse(closer, dist, far_dist);
      t_far = hn::IfThenElse(closer, hn::Set(d, t), t_far);
    }
    for (int dt = -1; dt <= 1; ++dt) {
      const V t = dt == -1 ? hn::IfThenElse(hn::Gt(t_far, hn::Add(t0[h], hn::Set(d, 1))), t_far,
                                            hn::Max(hn::Sub(t0[h], hn::Set(d, 1)), zero))
                           : hn::Min(hn::Add(t0[h], hn::Set(d, dt)), hn::Set(d, 7));
      const V ma = modifier_of(t, 0), mb = modifier_of(t, 1);
      const V edge = hn::Mul(hn::Set(d, 3), hn::Add(ma, mb));
      V err = zero, idx[8];
      for (int i = 0; i < 8; ++i) {
        const M up = hn::Not(hn::Lt(dl[i], zero));
        const V twice = hn::Add(dl[i], dl[i]);
        const M far = hn::Or(hn::And(up, hn::Gt(twice, edge)), hn::AndNot(up, hn::Lt(twice, hn::Neg(edge))));
        const V mag = hn::IfThenElse(far, mb, ma);
        const V m = hn::IfThenElse(up, mag, hn::Neg(mag));
        idx[i] = hn::Add(hn::IfThenElseZero(far, hn::Set(d, 1)), hn::IfThenZeroElse(up, hn::Set(d, 2)));
        err = hn::Add(err, hn::Add(d2[i], hn::Mul(m, hn::Sub(hn::Mul(hn::Set(d, 3), m), twice))));
      }
      if (dt == -1) {
        best.err = err;
        best.table = t;
        for (int i = 0; i < 8; ++i) best.idx[i] = idx[i];
        continue;
      }
      const M better = hn::Lt(err, best.err);
      best.err = hn::IfThenElse(better, err, best.err);
      best.table = hn::IfThenElse(better, t, best.table);
      for (int i = 0; i < 8; ++i) best.idx[i] = hn::IfThenElse(better, idx[i], best.idx[i]);
    }
  }

  // Per flip, the halves' fits: differential where the 5-bit bases' delta
  // fits; elsewhere individual (4-bit), or with differential_only either
  // base pulled within the delta of the other. The flip with less error
  // wins; pa, pb its halves.
  HWY_INLINE void choose(bool differential_only, M& flip, M& differential, Fit& pa, Fit& pb) const {
    Fit f5[4], f4[4];
    for (int h = 0; h < 4; ++h) fit(h, 5, f5[h], nullptr);
    M fits[2];
    for (int fl = 0; fl < 2; ++fl) fits[fl] = reach_of(f5[2 * fl].q, f5[2 * fl + 1].q);
    // Individual mode only where a flip's delta does not fit (lanes that do
    // not need it ignore it).
    V err[2];
    Fit chosen[2][2];
    for (int fl = 0; fl < 2; ++fl) {
      const bool any4 = !hn::AllTrue(d, fits[fl]);
      for (int s = 0; s < 2; ++s) {
        const int h = 2 * fl + s;
        chosen[fl][s] = f5[h];
        if (!any4) continue;
        if (differential_only) {  // as the reference: either base pulled within the delta of the other
          if (s == 0) continue;
          const int ha = h - 1;
          V qa[3], qb[3];
          for (int c = 0; c < 3; ++c) {
            qa[c] =
                hn::Min(hn::Max(f5[ha].q[c], hn::Sub(f5[h].q[c], hn::Set(d, 3))), hn::Add(f5[h].q[c], hn::Set(d, 4)));
            qb[c] =
                hn::Min(hn::Max(f5[h].q[c], hn::Sub(f5[ha].q[c], hn::Set(d, 4))), hn::Add(f5[ha].q[c], hn::Set(d, 3)));
          }
          Fit pulled_a{}, pulled_b{};  // (zeroed: GCC cannot see fit() set every field)
          fit(ha, 5, pulled_a, qa);
          fit(h, 5, pulled_b, qb);
          const M far = hn::Not(fits[fl]);
          const M move_a = hn::And(far, hn::Lt(hn::Add(pulled_a.err, f5[h].err), hn::Add(f5[ha].err, pulled_b.err)));
          const M move_b = hn::AndNot(move_a, far);
          select_fit(move_a, pulled_a, chosen[fl][0]);
          select_fit(move_b, pulled_b, chosen[fl][1]);
          continue;
        }
        fit(h, 4, f4[h], nullptr);
        chosen[fl][s] = f4[h];
        select_fit(fits[fl], f5[h], chosen[fl][s]);
      }
      err[fl] = hn::Add(chosen[fl][0].err, chosen[fl][1].err);
    }
    flip = hn::Lt(err[1], err[0]);
    differential = differential_only ? hn::Eq(hn::Zero(d), hn::Zero(d))
                                     : hn::Or(hn::And(flip, fits[1]), hn::AndNot(flip, fits[0]));
    pa = chosen[0][0];
    pb = chosen[0][1];
    select_fit(flip, chosen[1][0], pa);
    select_fit(flip, chosen[1][1], pb);
  }

  // The modifiers again under the decoder's clamping (as the reference):
  // each lane's chosen halves gathered into texels 0-7 and 8-15.
  HWY_INLINE void reclamp(M flip, M differential, Fit& pa, Fit& pb) const {
    V hr[16], hg[16], hb[16];
    for (int s = 0; s < 2; ++s)
      for (int i = 0; i < 8; ++i) {
        const int p0 = fast::kHalf[s][i], p1 = fast::kHalf[2 + s][i];
        hr[8 * s + i] = hn::IfThenElse(flip, r[p1], r[p0]);
        hg[8 * s + i] = hn::IfThenElse(flip, g[p1], g[p0]);
        hb[8 * s + i] = hn::IfThenElse(flip, b[p1], b[p0]);
      }
    static constexpr int kFirst[8] = {0, 1, 2, 3, 4, 5, 6, 7}, kSecond[8] = {8, 9, 10, 11, 12, 13, 14, 15};
    for (int s = 0; s < 2; ++s) {
      Fit& f = s ? pb : pa;
      V base[3];
      for (int c = 0; c < 3; ++c) base[c] = hn::IfThenElse(differential, extend(f.q[c], 5), extend(f.q[c], 4));
      const Fit e = eval_exact_lanes(hr, hg, hb, s ? kSecond : kFirst, base, f.table);
      for (int i = 0; i < 8; ++i) f.idx[i] = e.idx[i];
    }
  }
};

}  // namespace

void Etc1FastLanes(const std::uint32_t texel[16][kEtcBatch], int count, bool differential_only, std::uint8_t out[][8]) {
  const DI d;
  const int lanes = int(hn::Lanes(d));
  for (int k0 = 0; k0 < count; k0 += lanes) {
    Etc1FastBatch batch;
    load_texels(texel, k0, batch.r, batch.g, batch.b);
    batch.spread_tables();
    M flip, differential;
    Fit pa, pb;
    batch.choose(differential_only, flip, differential, pa, pb);
    batch.reclamp(flip, differential, pa, pb);
    pack_blocks(hn::IfThenElseZero(flip, hn::Set(d, 1)), hn::IfThenElseZero(differential, hn::Set(d, 1)), pa, pb, k0,
                count, out);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace texproc::etc
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace texproc::etc {
HWY_EXPORT(Etc1FastLanes);

void etc1_fast_lanes(const std::uint32_t texel[16][kEtcBatch], int count, bool differential_only,
                     std::uint8_t out[][8]) {
  if (force_scalar()) return ref::etc1_fast_lanes(texel, count, differential_only, out);
  HWY_DYNAMIC_DISPATCH(Etc1FastLanes)(texel, count, differential_only, out);
}
}  // namespace texproc::etc
#endif
