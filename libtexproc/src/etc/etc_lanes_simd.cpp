// ETC1 `fast`, `normal` and `high`, a block per lane: the Highway twin of the scalar
// reference in etc_lanes.cpp (one block at a time, plainly), which packs the
// blocks in lanes too (the reference's packer is the plain statement of the
// layout). See etc_lanes.h.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "etc/etc_lanes_simd.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include <algorithm>
#include <cstdlib>

#include "etc/etc_lanes.h"
#include "etc/etc_lanes_shared.h"
#include "etc/etc_tables.h"
#include "texproc/runtime.h"

HWY_BEFORE_NAMESPACE();
namespace texproc::etc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using D = hn::CappedTag<std::int32_t, kEtcBatch>;
using V = hn::Vec<D>;
using M = hn::Mask<D>;

// A half block's fit, per lane: its error, base, table and modifier indices.
struct Fit {
  V err, q[3], table, idx[8];
};

// The texels of blocks k0, k0 + 1, ... as channel planes.
HWY_INLINE void LoadTexels(const std::uint32_t texel[16][kEtcBatch], int k0, V r[16], V g[16], V b[16]) {
  const D d;
  const hn::Rebind<std::uint32_t, D> du;
  const V mask8 = hn::Set(d, 255);
  for (int i = 0; i < 16; ++i) {
    const V t = hn::BitCast(d, hn::LoadU(du, texel[i] + k0));
    r[i] = hn::And(t, mask8), g[i] = hn::And(hn::ShiftRight<8>(t), mask8), b[i] = hn::And(hn::ShiftRight<16>(t), mask8);
  }
}

// The table's modifier a (column 0) or b (column 1) for each lane's table t.
HWY_INLINE V Modifier(V t, int column) {
  const D d;
  V v = hn::Set(d, kModifiers[0][column]);
  for (int j = 1; j < 8; ++j) v = hn::IfThenElse(hn::Eq(t, hn::Set(d, j)), hn::Set(d, kModifiers[j][column]), v);
  return v;
}

// A 5- or 4-bit base channel extended to 8 bits.
HWY_INLINE V Extend(V q, int bits) {
  return bits == 5 ? hn::Or(hn::ShiftLeft<3>(q), hn::ShiftRight<2>(q)) : hn::Or(hn::ShiftLeft<4>(q), q);
}

// As ref::eval_exact, but for bases given extended to 8 bits (q is left
// to the caller): tables t for the half whose texels are r, g, b[half[0..7]].
HWY_INLINE Fit EvalExact(const V r[16], const V g[16], const V b[16], const int half[8], const V base[3], V t) {
  const D d;
  const V zero = hn::Zero(d), top8 = hn::Set(d, 255);
  Fit f;
  f.table = t;
  const V ma = Modifier(t, 0), mb = Modifier(t, 1);
  const V mods[4] = {ma, mb, hn::Neg(ma), hn::Neg(mb)};
  V pal[4][3];
  for (int c = 0; c < 3; ++c)
    for (int m = 0; m < 4; ++m) pal[m][c] = hn::Min(hn::Max(hn::Add(base[c], mods[m]), zero), top8);
  f.err = zero;
  for (int i = 0; i < 8; ++i) {
    const int p = half[i];
    V be = zero, bi = zero;
    for (int m = 0; m < 4; ++m) {
      const V dr = hn::Sub(r[p], pal[m][0]), dg = hn::Sub(g[p], pal[m][1]), db = hn::Sub(b[p], pal[m][2]);
      const V e = hn::Add(hn::Add(hn::Mul(dr, dr), hn::Mul(dg, dg)), hn::Mul(db, db));
      if (m == 0) {
        be = e;
        continue;
      }
      const M better = hn::Lt(e, be);
      be = hn::IfThenElse(better, e, be);
      bi = hn::IfThenElse(better, hn::Set(d, m), bi);
    }
    f.idx[i] = bi;
    f.err = hn::Add(f.err, be);
  }
  return f;
}

// Writes the blocks of lanes k0.. (as fast::pack does, in lanes): flip and
// differential (0/1 per lane), the halves' fits a (first) and b.
HWY_INLINE void PackBlocks(V flip, V differential, const Fit& a, const Fit& b, int k0, int count, std::uint8_t out[][8]) {
  const D d;
  const hn::Rebind<std::uint32_t, D> du;
  const V seven = hn::Set(d, 7);
  const auto is_diff = hn::Ne(differential, hn::Zero(d));
  V high = hn::Zero(d);
  for (int c = 0; c < 3; ++c) {  // bits 63-40: a byte per channel
    const V byte = hn::IfThenElse(is_diff, hn::Or(hn::ShiftLeft<3>(a.q[c]), hn::And(hn::Sub(b.q[c], a.q[c]), seven)),
                                  hn::Or(hn::ShiftLeft<4>(a.q[c]), b.q[c]));
    high = hn::Or(high, hn::ShiftLeftSame(byte, 24 - 8 * c));
  }
  high = hn::Or(high, hn::Or(hn::Or(hn::ShiftLeft<5>(a.table), hn::ShiftLeft<2>(b.table)),
                             hn::Or(hn::ShiftLeft<1>(differential), flip)));
  // Texel (x, y) at bit x * 4 + y of each 16-bit half of the low word
  // (most significant index bits above); the halves' texels depend on the flip.
  V low[2] = {hn::Zero(d), hn::Zero(d)};
  for (int f = 0; f < 2; ++f)
    for (int s = 0; s < 2; ++s)
      for (int i = 0; i < 8; ++i) {
        const int t = fast::kHalf[2 * f + s][i], bit = (t % 4) * 4 + t / 4;
        const V idx = (s ? b : a).idx[i];
        low[f] = hn::Or(low[f], hn::Or(hn::ShiftLeftSame(hn::ShiftRight<1>(idx), bit + 16),
                                       hn::ShiftLeftSame(hn::And(idx, hn::Set(d, 1)), bit)));
      }
  const V lo = hn::IfThenElse(hn::Ne(flip, hn::Zero(d)), low[1], low[0]);
  HWY_ALIGN std::uint32_t hi_o[kEtcBatch], lo_o[kEtcBatch];
  hn::Store(hn::BitCast(du, high), du, hi_o);
  hn::Store(hn::BitCast(du, lo), du, lo_o);
  for (int k = 0; k < int(hn::Lanes(d)) && k0 + k < count; ++k)
    store_be64(std::uint64_t(hi_o[k]) << 32 | lo_o[k], out[k0 + k]);
}

HWY_INLINE void SelectFit(M m, const Fit& from, Fit& to) {
  to.err = hn::IfThenElse(m, from.err, to.err);
  to.table = hn::IfThenElse(m, from.table, to.table);
  for (int c = 0; c < 3; ++c) to.q[c] = hn::IfThenElse(m, from.q[c], to.q[c]);
  for (int i = 0; i < 8; ++i) to.idx[i] = hn::IfThenElse(m, from.idx[i], to.idx[i]);
}

// Lanes where bases `to` are within the differential delta's reach of
// `from` (to - from in [-4, 3] in every channel).
HWY_INLINE M Reach(const V from[3], const V to[3]) {
  const D d;
  M ok = hn::Eq(hn::Zero(d), hn::Zero(d));
  for (int c = 0; c < 3; ++c) {
    const V delta = hn::Sub(to[c], from[c]);
    ok = hn::And(ok, hn::And(hn::Not(hn::Lt(delta, hn::Set(d, -4))), hn::Not(hn::Gt(delta, hn::Set(d, 3)))));
  }
  return ok;
}

// `fast`, stage by stage (the reference's fast:: functions in etc_lanes.cpp):
// spread_tables, fit, choose (the flip and mode per lane), reclamp.
struct Etc1FastBatch {
  const D d{};
  const hn::Rebind<float, D> df{};
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
      sum[0] = hn::Add(sum[0], r[p]), sum[1] = hn::Add(sum[1], g[p]), sum[2] = hn::Add(sum[2], b[p]);
    }
    V base[3];
    for (int c = 0; c < 3; ++c) {
      const V num = hn::Add(hn::Mul(hn::Set(d, bits == 5 ? 62 : 30), sum[c]), hn::Set(d, 2040));
      best.q[c] = fixed_q ? fixed_q[c] : hn::ConvertTo(d, hn::Div(hn::ConvertTo(df, num), hn::Set(df, 4080.0f)));
      base[c] = Extend(best.q[c], bits);
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
      const V t = dt == -1 ? hn::IfThenElse(hn::Gt(t_far, hn::Add(t0[h], hn::Set(d, 1))), t_far, hn::Max(hn::Sub(t0[h], hn::Set(d, 1)), zero))
                           : hn::Min(hn::Add(t0[h], hn::Set(d, dt)), hn::Set(d, 7));
      const V ma = Modifier(t, 0), mb = Modifier(t, 1);
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
        best.err = err, best.table = t;
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
    for (int fl = 0; fl < 2; ++fl) fits[fl] = Reach(f5[2 * fl].q, f5[2 * fl + 1].q);
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
            qa[c] = hn::Min(hn::Max(f5[ha].q[c], hn::Sub(f5[h].q[c], hn::Set(d, 3))), hn::Add(f5[h].q[c], hn::Set(d, 4)));
            qb[c] = hn::Min(hn::Max(f5[h].q[c], hn::Sub(f5[ha].q[c], hn::Set(d, 4))), hn::Add(f5[ha].q[c], hn::Set(d, 3)));
          }
          Fit pulled_a{}, pulled_b{};  // (zeroed: GCC cannot see fit() set every field)
          fit(ha, 5, pulled_a, qa);
          fit(h, 5, pulled_b, qb);
          const M far = hn::Not(fits[fl]);
          const M move_a = hn::And(far, hn::Lt(hn::Add(pulled_a.err, f5[h].err), hn::Add(f5[ha].err, pulled_b.err)));
          const M move_b = hn::AndNot(move_a, far);
          SelectFit(move_a, pulled_a, chosen[fl][0]);
          SelectFit(move_b, pulled_b, chosen[fl][1]);
          continue;
        }
        fit(h, 4, f4[h], nullptr);
        chosen[fl][s] = f4[h];
        SelectFit(fits[fl], f5[h], chosen[fl][s]);
      }
      err[fl] = hn::Add(chosen[fl][0].err, chosen[fl][1].err);
    }
    flip = hn::Lt(err[1], err[0]);
    differential = differential_only ? hn::Eq(hn::Zero(d), hn::Zero(d)) : hn::Or(hn::And(flip, fits[1]), hn::AndNot(flip, fits[0]));
    pa = chosen[0][0], pb = chosen[0][1];
    SelectFit(flip, chosen[1][0], pa);
    SelectFit(flip, chosen[1][1], pb);
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
      for (int c = 0; c < 3; ++c) base[c] = hn::IfThenElse(differential, Extend(f.q[c], 5), Extend(f.q[c], 4));
      const Fit e = EvalExact(hr, hg, hb, s ? kSecond : kFirst, base, f.table);
      for (int i = 0; i < 8; ++i) f.idx[i] = e.idx[i];
    }
  }
};

void Etc1FastLanes(const std::uint32_t texel[16][kEtcBatch], int count, bool differential_only, std::uint8_t out[][8]) {
  const D d;
  const int lanes = int(hn::Lanes(d));
  for (int k0 = 0; k0 < count; k0 += lanes) {
    Etc1FastBatch batch;
    LoadTexels(texel, k0, batch.r, batch.g, batch.b);
    batch.spread_tables();
    M flip, differential;
    Fit pa, pb;
    batch.choose(differential_only, flip, differential, pa, pb);
    batch.reclamp(flip, differential, pa, pb);
    PackBlocks(hn::IfThenElseZero(flip, hn::Set(d, 1)), hn::IfThenElseZero(differential, hn::Set(d, 1)), pa, pb, k0, count, out);
  }
}

// The best block so far per lane: its error, flip, mode and halves.
struct Choice {
  V err, flip, diff;
  Fit a, b;
  HWY_INLINE void consider(M m, int fl, bool differential, const Fit& fa, const Fit& fb) {
    const D d;
    const V e = hn::Add(fa.err, fb.err);
    const M take = hn::And(m, hn::Lt(e, err));
    err = hn::IfThenElse(take, e, err);
    flip = hn::IfThenElse(take, hn::Set(d, fl), flip);
    diff = hn::IfThenElse(take, hn::Set(d, differential ? 1 : 0), diff);
    SelectFit(take, fa, a);
    SelectFit(take, fb, b);
  }
};

// `normal` and `high`, stage by stage (the reference's search:: functions in
// etc_lanes.cpp): eval, recentre, fit_normal (its seeds in extremes, `high`'s
// per-table refinement and neighbourhood in fit_high), fit_fixed, and per
// flip search_flip.
struct Etc1SearchBatch {
  const D d{};
  const hn::Rebind<float, D> df{};
  const V zero;
  V r[16], g[16], b[16];

  HWY_ATTR Etc1SearchBatch() : zero(hn::Zero(d)) {}  // not a default member initializer: the target's attributes

  HWY_INLINE V quantize(V sum, int bits) const {  // as fast::quantize_centre
    const V num = hn::Add(hn::Mul(hn::Set(d, bits == 5 ? 62 : 30), sum), hn::Set(d, 2040));
    const V q = hn::ConvertTo(d, hn::Div(hn::ConvertTo(df, num), hn::Set(df, 4080.0f)));
    return hn::Min(hn::Max(q, zero), hn::Set(d, bits == 5 ? 31 : 15));
  }
  HWY_INLINE Fit eval(int h, const V q[3], int bits, V t) const {
    const V base[3] = {Extend(q[0], bits), Extend(q[1], bits), Extend(q[2], bits)};
    Fit f = EvalExact(r, g, b, fast::kHalf[h], base, t);
    for (int c = 0; c < 3; ++c) f.q[c] = q[c];
    return f;
  }
  // Re-centres `cur` (its table per lane) up to `passes` times while that helps.
  HWY_INLINE Fit recentre(int h, int bits, Fit cur, int passes) const {
    const V ma = Modifier(cur.table, 0), mb = Modifier(cur.table, 1);
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
      SelectFit(active, next, cur);
    }
    return cur;
  }
  // The two tables with the least error (first of equals).
  HWY_INLINE void best_two(const V err[8], V& t1, V& t2) const {
    V e1 = err[0], e2 = hn::Set(d, -1);
    t1 = zero, t2 = zero;
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
    for (int j = 1; j < 8; ++j) SelectFit(hn::Eq(t, hn::Set(d, j)), fits[j], f);
    return f;
  }
  // Half h's brightest and darkest texels (by R + G + B, first of equals).
  HWY_INLINE void extremes(int h, V bright[3], V dark[3]) const {
    const int p0 = fast::kHalf[h][0];
    bright[0] = dark[0] = r[p0], bright[1] = dark[1] = g[p0], bright[2] = dark[2] = b[p0];
    V bright_sum = hn::Add(hn::Add(r[p0], g[p0]), b[p0]), dark_sum = bright_sum;
    for (int i = 1; i < 8; ++i) {
      const int p = fast::kHalf[h][i];
      const V sp = hn::Add(hn::Add(r[p], g[p]), b[p]);
      const M up = hn::Gt(sp, bright_sum), down = hn::Lt(sp, dark_sum);
      bright_sum = hn::IfThenElse(up, sp, bright_sum), dark_sum = hn::IfThenElse(down, sp, dark_sum);
      const V px[3] = {r[p], g[p], b[p]};
      for (int c = 0; c < 3; ++c) bright[c] = hn::IfThenElse(up, px[c], bright[c]), dark[c] = hn::IfThenElse(down, px[c], dark[c]);
    }
  }
  // start replaced by the fit at base = px - m (quantized) where better.
  HWY_INLINE void seed(int h, int bits, Fit& start, const V px[3], V m, V t) const {
    const int top = bits == 5 ? 31 : 15;
    auto quantize8 = [&](V v) {
      const V q = hn::ConvertTo(d, hn::Add(hn::Div(hn::ConvertTo(df, hn::Mul(v, hn::Set(d, top))), hn::Set(df, 255.0f)),
                                           hn::Set(df, 0.5f)));
      return hn::Min(hn::Max(q, zero), hn::Set(d, top));
    };
    const V q[3] = {quantize8(hn::Sub(px[0], m)), quantize8(hn::Sub(px[1], m)), quantize8(hn::Sub(px[2], m))};
    const Fit f = eval(h, q, bits, t);
    SelectFit(hn::Lt(f.err, start.err), f, start);
  }
  // `high`: every table seeded from the extremes minus its extreme
  // modifiers and re-centred three times, then the +-1 neighbourhood of the
  // two best bases; per_table (if set) gets every table's fit and the best.
  HWY_INLINE Fit fit_high(int h, int bits, const Fit at_mean[8], const V bright[3], const V dark[3], Fit* per_table) const {
    const int top = bits == 5 ? 31 : 15;
    Fit best, refined[8];
    V err[8];
    for (int t = 0; t < 8; ++t) {
      Fit start = at_mean[t];
      const V tv = hn::Set(d, t);
      const int seeds[4] = {kModifiers[t][1], -kModifiers[t][1], kModifiers[t][0], -kModifiers[t][0]};
      for (int sd = 0; sd < 4; ++sd) seed(h, bits, start, sd % 2 ? dark : bright, hn::Set(d, seeds[sd]), tv);
      refined[t] = recentre(h, bits, start, 3), err[t] = refined[t].err;
      if (t == 0) {
        best = refined[0];
      } else {
        SelectFit(hn::Lt(refined[t].err, best.err), refined[t], best);
      }
    }
    V t1, t2;
    best_two(err, t1, t2);
    for (int which = 0; which < 2; ++which) {
      const Fit base = pick(refined, which ? t2 : t1);
      for (int dr = -1; dr <= 1; ++dr)
        for (int dg = -1; dg <= 1; ++dg)
          for (int db = -1; db <= 1; ++db) {
            const V q[3] = {hn::Add(base.q[0], hn::Set(d, dr)), hn::Add(base.q[1], hn::Set(d, dg)), hn::Add(base.q[2], hn::Set(d, db))};
            M valid = hn::Eq(zero, zero);
            for (int c = 0; c < 3; ++c) valid = hn::And(valid, hn::And(hn::Not(hn::Lt(q[c], zero)), hn::Not(hn::Gt(q[c], hn::Set(d, top)))));
            if (hn::AllFalse(d, valid)) continue;
            const Fit f = eval(h, q, bits, base.table);
            SelectFit(hn::And(valid, hn::Lt(f.err, best.err)), f, best);
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
      sum[0] = hn::Add(sum[0], r[p]), sum[1] = hn::Add(sum[1], g[p]), sum[2] = hn::Add(sum[2], b[p]);
    }
    const V q0[3] = {quantize(sum[0], bits), quantize(sum[1], bits), quantize(sum[2], bits)};
    Fit at_mean[8];
    V err[8];
    for (int t = 0; t < 8; ++t) at_mean[t] = eval(h, q0, bits, hn::Set(d, t)), err[t] = at_mean[t].err;
    V bright[3], dark[3];
    extremes(h, bright, dark);
    if (high) return fit_high(h, bits, at_mean, bright, dark, per_table);
    V t1, t2;
    best_two(err, t1, t2);
    Fit start = pick(at_mean, t1);
    const V far = Modifier(t1, 1);
    seed(h, bits, start, bright, far, t1);
    seed(h, bits, start, dark, hn::Neg(far), t1);
    Fit best = recentre(h, bits, start, 2);
    Fit start2 = pick(at_mean, t2);
    const V far2 = Modifier(t2, 1);
    seed(h, bits, start2, bright, far2, t2);
    seed(h, bits, start2, dark, hn::Neg(far2), t2);
    const Fit second = recentre(h, bits, start2, 2);
    SelectFit(hn::Lt(second.err, best.err), second, best);
    return best;
  }
  HWY_INLINE Fit fit_fixed(int h, const V q[3]) const {
    Fit best = eval(h, q, 5, zero);
    for (int t = 1; t < 8; ++t) {
      const Fit f = eval(h, q, 5, hn::Set(d, t));
      SelectFit(hn::Lt(f.err, best.err), f, best);
    }
    return best;
  }
  // One flip's candidates: the halves' fits where the delta reaches; at
  // `high` every pair of per-table fits it reaches; the individual mode
  // (where it must, or at `high` always); either base pulled within the
  // delta of the other (at `high` with its neighbours).
  HWY_INLINE void search_flip(int flip, bool high, bool differential_only, const Fit f5[4], const Fit tables[4][9], Choice& best) const {
    const int a = 2 * flip, bh = a + 1;
    const M fits = Reach(f5[a].q, f5[bh].q);
    best.consider(fits, flip, true, f5[a], f5[bh]);
    if (high)
      for (int ta = 0; ta < 9; ++ta)
        for (int tb = 0; tb < 9; ++tb) {
          const M ok = Reach(tables[a][ta].q, tables[bh][tb].q);
          if (!hn::AllFalse(d, ok)) best.consider(ok, flip, true, tables[a][ta], tables[bh][tb]);
        }
    if (hn::AllTrue(d, fits) && !high) return;
    const M far = hn::Not(fits);
    if (!differential_only)  // `high`: always
      best.consider(high ? hn::Eq(zero, zero) : far, flip, false, fit_normal(a, 4, high, nullptr), fit_normal(bh, 4, high, nullptr));
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
      M ok = hn::And(far, hn::And(in_range(q), Reach(q, f5[bh].q)));
      if (!hn::AllFalse(d, ok)) best.consider(ok, flip, true, eval(a, q, 5, pa.table), f5[bh]);
      for (int c = 0; c < 3; ++c) q[c] = hn::Add(qb[c], hn::Set(d, dd[c]));
      ok = hn::And(far, hn::And(in_range(q), Reach(f5[a].q, q)));
      if (!hn::AllFalse(d, ok)) best.consider(ok, flip, true, f5[a], eval(bh, q, 5, pb.table));
    }
  }
};

void Etc1SearchLanes(const std::uint32_t texel[16][kEtcBatch], int count, bool high, bool differential_only,
                     std::uint8_t out[][8], std::int32_t error[]) {
  const D d;
  const int lanes = int(hn::Lanes(d));
  for (int k0 = 0; k0 < count; k0 += lanes) {
    Etc1SearchBatch batch;
    LoadTexels(texel, k0, batch.r, batch.g, batch.b);
    Fit f5[4], tables[4][9];
    for (int h = 0; h < 4; ++h) f5[h] = batch.fit_normal(h, 5, high, high ? tables[h] : nullptr);
    Choice best;
    best.err = hn::Set(d, 0x7fffffff), best.flip = hn::Zero(d), best.diff = hn::Zero(d);
    best.a = f5[0], best.b = f5[1];
    for (int flip = 0; flip < 2; ++flip) batch.search_flip(flip, high, differential_only, f5, tables, best);
    HWY_ALIGN std::int32_t err_o[kEtcBatch];
    hn::Store(best.err, d, err_o);
    for (int k = 0; k < lanes && k0 + k < count; ++k) error[k0 + k] = err_o[k];
    PackBlocks(best.flip, best.diff, best.a, best.b, k0, count, out);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace texproc::etc
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace texproc::etc {
HWY_EXPORT(Etc1FastLanes);
HWY_EXPORT(Etc1SearchLanes);

void etc1_fast_lanes(const std::uint32_t texel[16][kEtcBatch], int count, bool differential_only, std::uint8_t out[][8]) {
  if (force_scalar()) return ref::etc1_fast_lanes(texel, count, differential_only, out);
  HWY_DYNAMIC_DISPATCH(Etc1FastLanes)(texel, count, differential_only, out);
}

void etc1_search_lanes(const std::uint32_t texel[16][kEtcBatch], int count, bool high, bool differential_only,
                       std::uint8_t out[][8], std::int32_t error[]) {
  if (force_scalar()) return ref::etc1_search_lanes(texel, count, high, differential_only, out, error);
  HWY_DYNAMIC_DISPATCH(Etc1SearchLanes)(texel, count, high, differential_only, out, error);
}
}  // namespace texproc::etc
#endif
