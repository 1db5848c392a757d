// BC1 `fast`, `normal` and `high`, a block per lane: the Highway twin of the scalar
// reference in bc1_lanes.cpp (one block at a time, plainly). Both evaluate the same expressions in the
// same order; see bc1_lanes.h.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "bc/bc1_lanes_simd.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "bc/bc1_lanes.h"
#include "block/block_lanes_simd-inl.h"
#include "texproc/runtime.h"

HWY_BEFORE_NAMESPACE();
namespace texproc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
// Not in an anonymous namespace, as the other kernels' helpers are: with
// internal linkage GCC 12 inlines the batch's stages differently and BC1
// `normal` and `high` ran 20-26% slower (bench/compare_builds.py, 7 rounds
// interleaved). The names here are Bc1Batch's and encode_lanes, no other file's.

// The endpoints, codes and error of a candidate in every lane.
struct State {
  V qa[3], qb[3], codes[16], error;
};

// The lanes' blocks through the search, stage by stage (each the scalar
// reference's function of the same name in bc1_lanes.cpp): load (texels,
// principal axis, extent), thirds_fit (`fast`), variants, nudge,
// three_colour, pack. kPunch: BC1 with punch-through alpha (compiled apart,
// so opaque BC1 pays nothing for the transparent texels' masks).
template <bool kPunch>
struct Bc1Batch {
  const DI d;
  const DF df;
  const DU du;
  V r[16], g[16], b[16];
  M clear[16];  // punch-through: transparent texels (index 3 of the three-colour mode)
  V n_opaque;
  M transparent;  // lanes with any transparent texel
  M flat;         // lanes whose opaque texels are one colour (or none): left to the caller
  VF hi, lo, proj[16];
  VF m0, m1, m2, ax, ay, az, mean_p;
  const VF one, zero_f, top, half;
  const V mask8;

  // Written out (not default member initializers): the implicit constructor
  // would be compiled without the target's attributes.
  HWY_ATTR Bc1Batch()
      : one(hn::Set(df, 1.0f)),
        zero_f(hn::Zero(df)),
        top(hn::Set(df, 255.0f)),
        half(hn::Set(df, 0.5f)),
        mask8(hn::Set(d, 255)) {}

  // v where texel i is opaque, else 0 (punch-through only).
  HWY_INLINE V opaque_only(int i, V v) const {
    if constexpr (kPunch) {
      return hn::IfThenZeroElse(clear[i], v);
    } else {
      (void)i;
      return v;
    }
  }
  HWY_INLINE VF clamp255(VF x) const { return hn::Min(hn::Max(x, zero_f), top); }
  HWY_INLINE V quantize(VF x, int max) const {
    const V qv = hn::ConvertTo(d, hn::Add(hn::Mul(x, hn::Set(df, float(max) / 255.0f)), half));
    return hn::Min(hn::Max(qv, hn::Zero(d)), hn::Set(d, max));
  }
  HWY_INLINE void select(M take, const State& n, State& st) const {
    for (int ch = 0; ch < 3; ++ch) {
      st.qa[ch] = hn::IfThenElse(take, n.qa[ch], st.qa[ch]);
      st.qb[ch] = hn::IfThenElse(take, n.qb[ch], st.qb[ch]);
    }
    for (int i = 0; i < 16; ++i) st.codes[i] = hn::IfThenElse(take, n.codes[i], st.codes[i]);
    st.error = hn::IfThenElse(take, n.error, st.error);
  }

  // The opaque texels' colour sums and products, a lane each (transparent
  // texels count as black, that is, not at all).
  struct Moments {
    V sum_r, sum_g, sum_b;
    V rr, rg, rb, gg, gb, bb;
  };

  // The texels of blocks k0.. (r, g, b, clear, n_opaque, transparent) and their moments.
  HWY_INLINE Moments load_texels(const std::uint32_t texel[16][kBc1Batch], int k0) {
    const V zero_i = hn::Zero(d);
    Moments m{zero_i, zero_i, zero_i, zero_i, zero_i, zero_i, zero_i, zero_i, zero_i};
    n_opaque = zero_i;
    for (int i = 0; i < 16; ++i) {
      const auto tu = hn::LoadU(du, texel[i] + k0);
      const V t = hn::BitCast(d, tu);
      clear[i] = kPunch ? hn::RebindMask(d, hn::Lt(hn::ShiftRight<24>(tu), hn::Set(du, 128u))) : hn::Lt(mask8, mask8);
      r[i] = opaque_only(i, hn::And(t, mask8));
      g[i] = opaque_only(i, hn::And(hn::ShiftRight<8>(t), mask8));
      b[i] = opaque_only(i, hn::And(hn::ShiftRight<16>(t), mask8));
      n_opaque = hn::Add(n_opaque, hn::IfThenZeroElse(clear[i], hn::Set(d, 1)));
      m.sum_r = hn::Add(m.sum_r, r[i]);
      m.sum_g = hn::Add(m.sum_g, g[i]);
      m.sum_b = hn::Add(m.sum_b, b[i]);
      m.rr = hn::Add(m.rr, hn::Mul(r[i], r[i]));
      m.rg = hn::Add(m.rg, hn::Mul(r[i], g[i]));
      m.rb = hn::Add(m.rb, hn::Mul(r[i], b[i]));
      m.gg = hn::Add(m.gg, hn::Mul(g[i], g[i]));
      m.gb = hn::Add(m.gb, hn::Mul(g[i], b[i]));
      m.bb = hn::Add(m.bb, hn::Mul(b[i], b[i]));
    }
    transparent = hn::Lt(n_opaque, hn::Set(d, 16));
    return m;
  }

  // The principal axis (ax, ay, az): power iteration on the covariance
  // (times n_opaque^2, exact integers) from its row of greatest variance.
  // Lanes whose colours are all one (flat) are marked in `flat` and
  // `flat_out`, for the caller; their axis is not used.
  HWY_INLINE void principal_axis(const Moments& m, std::int32_t flat_out[]) {
    const V n = n_opaque;
    const V cov_rr_i = hn::Sub(hn::Mul(n, m.rr), hn::Mul(m.sum_r, m.sum_r));
    const V cov_rg_i = hn::Sub(hn::Mul(n, m.rg), hn::Mul(m.sum_r, m.sum_g));
    const V cov_rb_i = hn::Sub(hn::Mul(n, m.rb), hn::Mul(m.sum_r, m.sum_b));
    const V cov_gg_i = hn::Sub(hn::Mul(n, m.gg), hn::Mul(m.sum_g, m.sum_g));
    const V cov_gb_i = hn::Sub(hn::Mul(n, m.gb), hn::Mul(m.sum_g, m.sum_b));
    const V cov_bb_i = hn::Sub(hn::Mul(n, m.bb), hn::Mul(m.sum_b, m.sum_b));
    flat =
        hn::And(hn::And(hn::Eq(cov_rr_i, hn::Zero(d)), hn::Eq(cov_gg_i, hn::Zero(d))), hn::Eq(cov_bb_i, hn::Zero(d)));
    hn::Store(hn::VecFromMask(d, flat), d, flat_out);
    const VF rr = hn::ConvertTo(df, cov_rr_i), rg = hn::ConvertTo(df, cov_rg_i), rb = hn::ConvertTo(df, cov_rb_i);
    const VF gg = hn::ConvertTo(df, cov_gg_i), gb = hn::ConvertTo(df, cov_gb_i), bb = hn::ConvertTo(df, cov_bb_i);
    const auto r_widest = hn::And(hn::Ge(rr, gg), hn::Ge(rr, bb));
    const auto g_widest = hn::Ge(gg, bb);
    VF v0 = hn::IfThenElse(r_widest, rr, hn::IfThenElse(g_widest, rg, rb));
    VF v1 = hn::IfThenElse(r_widest, rg, hn::IfThenElse(g_widest, gg, gb));
    VF v2 = hn::IfThenElse(r_widest, rb, hn::IfThenElse(g_widest, gb, bb));
    // Flat lanes (skipped) divide by 1 instead of 0.
    const auto flat_f = hn::RebindMask(df, flat);
    for (int it = 0; it < 4; ++it) {
      const VF inv = hn::Div(one, hn::IfThenElse(flat_f, one, hn::Max(hn::Abs(v0), hn::Max(hn::Abs(v1), hn::Abs(v2)))));
      const VF x = hn::Mul(v0, inv), y = hn::Mul(v1, inv), z = hn::Mul(v2, inv);
      v0 = hn::Add(hn::Add(hn::Mul(rr, x), hn::Mul(rg, y)), hn::Mul(rb, z));
      v1 = hn::Add(hn::Add(hn::Mul(rg, x), hn::Mul(gg, y)), hn::Mul(gb, z));
      v2 = hn::Add(hn::Add(hn::Mul(rb, x), hn::Mul(gb, y)), hn::Mul(bb, z));
    }
    const VF len =
        hn::IfThenElse(flat_f, one, hn::Sqrt(hn::Add(hn::Add(hn::Mul(v0, v0), hn::Mul(v1, v1)), hn::Mul(v2, v2))));
    const VF inv_len = hn::Div(one, len);
    ax = hn::Mul(v0, inv_len);
    ay = hn::Mul(v1, inv_len);
    az = hn::Mul(v2, inv_len);
  }

  // Each texel's projection on the axis (proj), the opaque texels' extent
  // along it (lo, hi), their mean (m0, m1, m2) and its projection (mean_p).
  HWY_INLINE void project(const Moments& m) {
    lo = hn::Set(df, 1e30f);
    hi = hn::Set(df, -1e30f);
    for (int i = 0; i < 16; ++i) {
      const VF p = hn::Add(hn::Add(hn::Mul(hn::ConvertTo(df, r[i]), ax), hn::Mul(hn::ConvertTo(df, g[i]), ay)),
                           hn::Mul(hn::ConvertTo(df, b[i]), az));
      if constexpr (kPunch) {
        const auto opaque = hn::RebindMask(df, hn::Not(clear[i]));
        lo = hn::IfThenElse(opaque, hn::Min(lo, p), lo);
        hi = hn::IfThenElse(opaque, hn::Max(hi, p), hi);
      } else {
        lo = hn::Min(lo, p);
        hi = hn::Max(hi, p);
      }
      proj[i] = p;
    }
    const VF fn = hn::ConvertTo(df, hn::Max(n_opaque, hn::Set(d, 1)));  // no opaque texel: a flat lane, skipped
    m0 = hn::Div(hn::ConvertTo(df, m.sum_r), fn);
    m1 = hn::Div(hn::ConvertTo(df, m.sum_g), fn);
    m2 = hn::Div(hn::ConvertTo(df, m.sum_b), fn);
    mean_p = hn::Add(hn::Add(hn::Mul(m0, ax), hn::Mul(m1, ay)), hn::Mul(m2, az));
  }

  // The texels of blocks k0.., the principal axis and each texel's place
  // along it; `flat_out` gets the lanes left to the caller.
  HWY_INLINE void load(const std::uint32_t texel[16][kBc1Batch], int k0, std::int32_t flat_out[]) {
    const Moments m = load_texels(texel, k0);
    principal_axis(m, flat_out);
    project(m);
  }

  // The extent's ends as quantized endpoints (codes and error not scored yet: 0).
  HWY_INLINE void extent_ends(State& st) const {
    for (int i = 0; i < 16; ++i) st.codes[i] = hn::Zero(d);
    st.error = hn::Zero(d);
    const VF dhi = hn::Sub(hi, mean_p), dlo = hn::Sub(lo, mean_p);
    st.qa[0] = quantize(clamp255(hn::Add(m0, hn::Mul(dhi, ax))), 31);
    st.qa[1] = quantize(clamp255(hn::Add(m1, hn::Mul(dhi, ay))), 63);
    st.qa[2] = quantize(clamp255(hn::Add(m2, hn::Mul(dhi, az))), 31);
    st.qb[0] = quantize(clamp255(hn::Add(m0, hn::Mul(dlo, ax))), 31);
    st.qb[1] = quantize(clamp255(hn::Add(m1, hn::Mul(dlo, ay))), 63);
    st.qb[2] = quantize(clamp255(hn::Add(m2, hn::Mul(dlo, az))), 31);
  }

  // Nearest palette entry per texel (x / 3 as x * 43691 >> 17, exact for
  // x < 1536); st.codes and st.error.
  HWY_INLINE void nearest(bool four, State& st) const {
    V pal[4][3];
    for (int ch = 0; ch < 3; ++ch) {
      const V qa = st.qa[ch], qb = st.qb[ch];
      const V ea = ch == 1 ? hn::Or(hn::ShiftLeft<2>(qa), hn::ShiftRight<4>(qa))
                           : hn::Or(hn::ShiftLeft<3>(qa), hn::ShiftRight<2>(qa));
      const V eb = ch == 1 ? hn::Or(hn::ShiftLeft<2>(qb), hn::ShiftRight<4>(qb))
                           : hn::Or(hn::ShiftLeft<3>(qb), hn::ShiftRight<2>(qb));
      const V third = hn::Set(d, 43691), one_i = hn::Set(d, 1);
      pal[0][ch] = ea;
      pal[1][ch] = eb;
      pal[2][ch] = four ? hn::ShiftRight<17>(hn::Mul(hn::Add(hn::Add(hn::Add(ea, ea), eb), one_i), third))
                        : hn::ShiftRight<1>(hn::Add(hn::Add(ea, eb), one_i));
      pal[3][ch] = hn::ShiftRight<17>(hn::Mul(hn::Add(hn::Add(hn::Add(eb, eb), ea), one_i), third));
    }
    V total = hn::Zero(d);
    for (int i = 0; i < 16; ++i) {
      V be = hn::Zero(d), best = hn::Zero(d);
      for (int k = 0; k < (four ? 4 : 3); ++k) {
        const V dr = hn::Sub(r[i], pal[k][0]), dg = hn::Sub(g[i], pal[k][1]), db = hn::Sub(b[i], pal[k][2]);
        const V e = hn::Add(hn::Add(hn::Mul(dr, dr), hn::Mul(dg, dg)), hn::Mul(db, db));
        if (k == 0) {
          be = e;
          continue;
        }
        const auto better = hn::Lt(e, be);
        be = hn::IfThenElse(better, e, be);
        best = hn::IfThenElse(better, hn::Set(d, k), best);
      }
      st.codes[i] = kPunch ? hn::IfThenElse(clear[i], hn::Set(d, 3), best) : best;
      total = hn::Add(total, opaque_only(i, be));
    }
    st.error = total;
  }

  // Least-squares endpoints for `w` and u = den - w weights (the sums of
  // every fit below), quantized; `solvable`: the system is not singular.
  HWY_INLINE void solve(const V w[16], const V u[16], int den_s, V qa[3], V qb[3], M& solvable, VF* red) const {
    const V den = hn::Set(d, den_s);
    V aa = hn::Zero(d), ab = aa, bb = aa, at[3] = {aa, aa, aa}, bt[3] = {aa, aa, aa};
    for (int i = 0; i < 16; ++i) {
      aa = hn::Add(aa, hn::Mul(u[i], u[i]));
      ab = hn::Add(ab, hn::Mul(u[i], w[i]));
      bb = hn::Add(bb, hn::Mul(w[i], w[i]));
      at[0] = hn::Add(at[0], hn::Mul(u[i], r[i]));
      at[1] = hn::Add(at[1], hn::Mul(u[i], g[i]));
      at[2] = hn::Add(at[2], hn::Mul(u[i], b[i]));
      bt[0] = hn::Add(bt[0], hn::Mul(w[i], r[i]));
      bt[1] = hn::Add(bt[1], hn::Mul(w[i], g[i]));
      bt[2] = hn::Add(bt[2], hn::Mul(w[i], b[i]));
    }
    const V det = hn::Sub(hn::Mul(aa, bb), hn::Mul(ab, ab));
    solvable = hn::Ne(det, hn::Zero(d));
    const VF inv_det = hn::Div(one, hn::ConvertTo(df, hn::IfThenElse(solvable, det, hn::Set(d, 1))));
    if (red) {  // the unquantized fit's reduction of the squared error
      const VF faa = hn::ConvertTo(df, aa), fab = hn::ConvertTo(df, ab), fbb = hn::ConvertTo(df, bb),
               two = hn::Set(df, 2.0f);
      *red = hn::Zero(df);
      for (int ch = 0; ch < 3; ++ch) {
        const VF x = hn::ConvertTo(df, at[ch]), y = hn::ConvertTo(df, bt[ch]);
        const VF t = hn::Add(hn::Sub(hn::Mul(hn::Mul(x, x), fbb), hn::Mul(hn::Mul(hn::Mul(two, x), y), fab)),
                             hn::Mul(hn::Mul(y, y), faa));
        *red = hn::Add(*red, hn::Mul(t, inv_det));
      }
    }
    for (int ch = 0; ch < 3; ++ch) {
      const int max = ch == 1 ? 63 : 31;
      const V na = hn::Mul(den, hn::Sub(hn::Mul(at[ch], bb), hn::Mul(bt[ch], ab)));
      const V nb = hn::Mul(den, hn::Sub(hn::Mul(bt[ch], aa), hn::Mul(at[ch], ab)));
      qa[ch] = quantize(clamp255(hn::Mul(hn::ConvertTo(df, na), inv_det)), max);
      qb[ch] = quantize(clamp255(hn::Mul(hn::ConvertTo(df, nb), inv_det)), max);
    }
  }

  // One least-squares refit of st's codes; weights by code in thirds (0, 3,
  // 1, 2) or halves (0, 2, 1); kept where it lowers the error.
  HWY_INLINE void refit(bool four, State& st) const {
    const int den_s = four ? 3 : 2;
    const V den = hn::Set(d, den_s), one_i = hn::Set(d, 1);
    V w[16], u[16];
    for (int i = 0; i < 16; ++i) {
      const V c = st.codes[i];
      w[i] = hn::IfThenElse(hn::Eq(c, one_i), den, hn::IfThenElseZero(hn::Gt(c, one_i), hn::Sub(c, one_i)));
      u[i] = hn::Sub(den, w[i]);
      if (kPunch && !four) {  // transparent texels (code 3) are out of the fit
        const M out_of_fit = hn::Eq(c, hn::Set(d, 3));
        w[i] = hn::IfThenZeroElse(out_of_fit, w[i]);
        u[i] = hn::IfThenZeroElse(out_of_fit, u[i]);
      } else if (kPunch) {
        w[i] = opaque_only(i, w[i]);
        u[i] = opaque_only(i, u[i]);
      }
    }
    State n;
    M solvable;
    solve(w, u, den_s, n.qa, n.qb, solvable, nullptr);
    nearest(four, n);
    select(hn::And(solvable, hn::Lt(n.error, st.error)), n, st);
  }

  // Texels at positions p (0..den) along the extent: hi - proj scaled by
  // `scale`, plus `shift`, floored and clamped; their least-squares fit.
  HWY_INLINE void fit_positions(VF scale, VF shift, int den_s, V qa[3], V qb[3], M& solvable, VF* red) const {
    const V den = hn::Set(d, den_s);
    V w[16], u[16];
    for (int i = 0; i < 16; ++i) {
      const V p = hn::Min(
          hn::Max(hn::ConvertTo(d, hn::Floor(hn::Add(hn::Mul(hn::Sub(hi, proj[i]), scale), shift))), hn::Zero(d)), den);
      w[i] = opaque_only(i, p);
      u[i] = opaque_only(i, hn::Sub(den, p));
    }
    solve(w, u, den_s, qa, qb, solvable, red);
  }

  // The reference's nudge() in the lanes `moving`: each quantized endpoint
  // channel moved by one step while that lowers the error (at most four
  // passes; a lane whose pass found nothing is done, and the loop ends
  // when every lane is).
  HWY_INLINE void nudge(bool four_colours, M moving, State& s) const {
    for (int pass = 0; pass < 4; ++pass) {
      M improved = hn::Lt(hn::Zero(d), hn::Zero(d));
      for (int m = 0; m < 12; ++m) {
        const int ch = m % 6 / 2, max = ch == 1 ? 63 : 31;
        State n = s;
        V* q = m < 6 ? n.qa : n.qb;  // a pointer, as in the reference (GCC 12.2, sanitizers)
        V& v = q[ch];
        v = hn::Add(v, hn::Set(d, m % 2 ? 1 : -1));
        const auto valid =
            hn::And(moving, hn::And(hn::Not(hn::Lt(v, hn::Zero(d))), hn::Not(hn::Gt(v, hn::Set(d, max)))));
        if (hn::AllFalse(d, valid)) continue;
        v = hn::Min(hn::Max(v, hn::Zero(d)), hn::Set(d, max));
        nearest(four_colours, n);
        const auto take = hn::And(valid, hn::Lt(n.error, s.error));
        select(take, n, s);
        improved = hn::Or(improved, take);
      }
      if (hn::AllFalse(d, hn::AndNot(flat, improved))) break;
    }
  }

  // `fast` (thirds_fit): each texel at the nearest third of the extent, one
  // least-squares fit for those positions (kept where solvable), the
  // nearest colours. st: the extent's ends on entry.
  HWY_INLINE void thirds_fit(State& st) const {
    const auto wide = hn::Gt(hi, lo);
    const VF scale = hn::IfThenElseZero(wide, hn::Div(hn::Set(df, 3.0f), hn::IfThenElse(wide, hn::Sub(hi, lo), one)));
    const V three_i = hn::Set(d, 3);
    V w[16], u[16];
    for (int i = 0; i < 16; ++i) {
      w[i] = opaque_only(i, hn::Min(hn::ConvertTo(d, hn::Add(hn::Mul(hn::Sub(hi, proj[i]), scale), half)), three_i));
      u[i] = opaque_only(i, hn::Sub(three_i, w[i]));
    }
    State n;
    M solvable;
    solve(w, u, 3, n.qa, n.qb, solvable, nullptr);
    for (int ch = 0; ch < 3; ++ch) {
      st.qa[ch] = hn::IfThenElse(solvable, n.qa[ch], st.qa[ch]);
      st.qb[ch] = hn::IfThenElse(solvable, n.qb[ch], st.qb[ch]);
    }
    nearest(true, st);
  }

  // Partition variants along the axis (see the scalar reference): `normal`
  // ranks them by their unquantized error and scores the best two exactly;
  // `high` (score_every_variant) scores every one, each refitted once.
  HWY_INLINE void variants(const Bc1LaneSearch& level, State& st) const {
    const int offsets = level.variant_offsets, stretches = level.variant_stretches;
    const auto wide = hn::Gt(hi, lo);
    const VF extent = hn::IfThenElse(wide, hn::Sub(hi, lo), one);
    VF e1 = hn::Zero(df), e2 = e1;
    V have = hn::Zero(d), kept1[2][3], kept2[2][3];
    for (int ch = 0; ch < 3; ++ch) kept1[0][ch] = kept1[1][ch] = kept2[0][ch] = kept2[1][ch] = hn::Zero(d);
    for (int o = -offsets; o <= offsets; ++o)
      for (int sv = -stretches; sv <= stretches; ++sv) {
        const VF scale =
            hn::IfThenElseZero(wide, hn::Div(hn::Set(df, 3.0f * (1.0f + ref::kVariantStep * float(sv))), extent));
        const VF shift = hn::Set(df, ref::variant_shift(o, sv));
        State n;
        M solvable;
        VF red;
        fit_positions(scale, shift, 3, n.qa, n.qb, solvable, &red);
        if (level.score_every_variant) {
          nearest(true, n);
          refit(true, n);
          select(hn::And(solvable, hn::Lt(n.error, st.error)), n, st);
          continue;
        }
        const VF e = hn::Neg(red);
        const M none = hn::Eq(have, hn::Zero(d)), one_kept = hn::Eq(have, hn::Set(d, 1));
        const M first = hn::And(solvable, hn::Or(none, hn::RebindMask(d, hn::Lt(e, e1))));
        const M second = hn::AndNot(first, hn::And(solvable, hn::Or(one_kept, hn::RebindMask(d, hn::Lt(e, e2)))));
        const M shift_down = hn::AndNot(none, first);
        e2 = hn::IfThenElse(hn::RebindMask(df, shift_down), e1, hn::IfThenElse(hn::RebindMask(df, second), e, e2));
        for (int k = 0; k < 2; ++k)
          for (int ch = 0; ch < 3; ++ch) {
            const V nq = k ? n.qb[ch] : n.qa[ch];
            kept2[k][ch] = hn::IfThenElse(shift_down, kept1[k][ch], hn::IfThenElse(second, nq, kept2[k][ch]));
            kept1[k][ch] = hn::IfThenElse(first, nq, kept1[k][ch]);
          }
        e1 = hn::IfThenElse(hn::RebindMask(df, first), e, e1);
        have = hn::Min(hn::Add(have, hn::IfThenElseZero(hn::Or(first, second), hn::Set(d, 1))), hn::Set(d, 2));
      }
    for (int m = 0; m < 2 && !level.score_every_variant; ++m) {
      const M valid = hn::Gt(have, hn::Set(d, m));
      if (hn::AllFalse(d, valid)) continue;
      State n;
      for (int ch = 0; ch < 3; ++ch) {
        n.qa[ch] = (m ? kept2 : kept1)[0][ch];
        n.qb[ch] = (m ? kept2 : kept1)[1][ch];
      }
      nearest(true, n);
      select(hn::And(valid, hn::Lt(n.error, st.error)), n, st);
    }
  }

  // Punch-through lanes with transparent texels at `high` (see
  // three_colour_search in the reference): partition variants on halves of
  // the extent, each scored and refitted, then nudges.
  HWY_INLINE void three_colour_search(State& t) const {
    const auto wide = hn::Gt(hi, lo);
    const VF extent = hn::IfThenElse(wide, hn::Sub(hi, lo), one);
    for (int o = -4; o <= 4; ++o)
      for (int sv = -2; sv <= 2; ++sv) {
        const VF scale =
            hn::IfThenElseZero(wide, hn::Div(hn::Set(df, 2.0f * (1.0f + ref::kVariantStep * float(sv))), extent));
        const VF shift = hn::Set(df, 0.5f + ref::kVariantStep * float(o) - ref::kVariantStep * float(sv));
        State n;
        M solvable;
        fit_positions(scale, shift, 2, n.qa, n.qb, solvable, nullptr);
        solvable = hn::And(transparent, solvable);
        if (hn::AllFalse(d, solvable)) continue;
        nearest(false, n);
        refit(false, n);
        select(hn::And(solvable, hn::Lt(n.error, t.error)), n, t);
      }
    nudge(false, transparent, t);
  }

  // The three-colour mode (no black) from the extent's ends `start`, refitted
  // once (lanes with transparent texels: their only mode, refitted twice, and
  // at `high` searched further); taken where it wins or must be used.
  HWY_INLINE void three_colour(const Bc1LaneSearch& level, bool three, const State& start, State& st, M& four) const {
    State t = start;
    nearest(false, t);
    refit(false, t);
    if (kPunch) {
      State t2 = t;
      refit(false, t2);
      select(transparent, t2, t);
    }
    if (kPunch && level.punch_variants && !hn::AllFalse(d, transparent)) three_colour_search(t);
    const auto take = hn::Or(transparent, three ? hn::Lt(t.error, st.error) : hn::Lt(mask8, mask8));
    select(take, t, st);
    four = hn::AndNot(take, four);
  }

  // The blocks' bytes. Four colours: c0 > c1 (swapping the ends flips the
  // codes' low bit; equal ends: every code 0). Three: c0 <= c1 (swapping
  // exchanges codes 0 and 1).
  HWY_INLINE void pack(const State& st, M four, std::uint32_t head[], std::uint32_t bits_out[]) const {
    const V e0 = hn::Or(hn::Or(hn::ShiftLeft<11>(st.qa[0]), hn::ShiftLeft<5>(st.qa[1])), st.qa[2]);
    const V e1 = hn::Or(hn::Or(hn::ShiftLeft<11>(st.qb[0]), hn::ShiftLeft<5>(st.qb[1])), st.qb[2]);
    const auto swap_m = hn::Or(hn::And(four, hn::Lt(e0, e1)), hn::AndNot(four, hn::Gt(e0, e1)));
    const auto zero_codes = hn::And(four, hn::Eq(e0, e1));
    auto bits = hn::Zero(du);
    for (int i = 0; i < 16; ++i) {
      V code = hn::IfThenZeroElse(zero_codes, st.codes[i]);
      const auto flip = hn::And(swap_m, hn::Or(four, hn::Lt(code, hn::Set(d, 2))));
      code = hn::IfThenElse(flip, hn::Xor(code, hn::Set(d, 1)), code);
      bits = hn::Or(bits, hn::ShiftLeftSame(hn::BitCast(du, code), 2 * i));
    }
    const V hi_end = hn::IfThenElse(swap_m, e1, e0), lo_end = hn::IfThenElse(swap_m, e0, e1);
    hn::Store(hn::BitCast(du, hn::Or(hi_end, hn::ShiftLeft<16>(lo_end))), du, head);
    hn::Store(bits, du, bits_out);
  }
};

template <bool kPunch>
HWY_INLINE void encode_lanes(const std::uint32_t texel[16][kBc1Batch], int count, const Bc1LaneSearch& level,
                             bool three, std::uint8_t out[][8], bool handled[]) {
  const int lanes = int(hn::Lanes(DI()));
  for (int k0 = 0; k0 < count; k0 += lanes) {
    Bc1Batch<kPunch> batch;
    HWY_ALIGN std::int32_t flat_out[kBc1Batch];
    batch.load(texel, k0, flat_out);
    State st;
    batch.extent_ends(st);
    const State start = st;
    M four = hn::Eq(hn::Zero(batch.d), hn::Zero(batch.d));
    if (level.thirds_fit) {
      batch.thirds_fit(st);
      if (!hn::AllFalse(batch.d, batch.transparent)) {  // the three-colour mode from the extent's ends, refitted once
        State t = start;
        batch.nearest(false, t);
        batch.refit(false, t);
        batch.select(batch.transparent, t, st);
        four = hn::AndNot(batch.transparent, four);
      }
    } else if (kPunch && hn::AllTrue(batch.d, hn::Or(batch.transparent, batch.flat))) {
      batch.nearest(true, st);  // every lane takes the three-colour mode below
    } else {
      batch.nearest(true, st);
      batch.refit(true, st);
      batch.refit(true, st);
      batch.variants(level, st);
      batch.nudge(true, hn::Eq(batch.mask8, batch.mask8), st);
    }
    if (!level.thirds_fit && (three || !hn::AllFalse(batch.d, batch.transparent)))
      batch.three_colour(level, three, start, st, four);
    HWY_ALIGN std::uint32_t head[kBc1Batch], bits_out[kBc1Batch];
    batch.pack(st, four, head, bits_out);
    for (int k = 0; k < lanes && k0 + k < count; ++k) {
      handled[k0 + k] = flat_out[k] == 0;
      if (!handled[k0 + k]) continue;
      std::memcpy(out[k0 + k], head + k, 4);
      std::memcpy(out[k0 + k] + 4, bits_out + k, 4);
    }
  }
}

void Bc1EncodeLanes(const std::uint32_t texel[16][kBc1Batch], int count, const Bc1LaneSearch& level, bool three,
                    bool punch, std::uint8_t out[][8], bool handled[]) {
  if (punch) {
    encode_lanes<true>(texel, count, level, three, out, handled);
  } else {
    encode_lanes<false>(texel, count, level, three, out, handled);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace texproc
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace texproc {
HWY_EXPORT(Bc1EncodeLanes);

void bc1_encode_lanes(const std::uint32_t texel[16][kBc1Batch], int count, const Bc1LaneSearch& level, bool three,
                      bool punch, std::uint8_t out[][8], bool handled[]) {
  if (force_scalar()) return ref::bc1_encode_lanes(texel, count, level, three, punch, out, handled);
  HWY_DYNAMIC_DISPATCH(Bc1EncodeLanes)(texel, count, level, three, punch, out, handled);
}
}  // namespace texproc
#endif
