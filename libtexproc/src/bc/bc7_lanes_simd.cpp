// BC7, a block per lane: the Highway twin of the scalar reference in
// bc7_lanes.cpp. Both evaluate the same expressions in the same order (see
// bc7_lanes.h); where the reference stops early for a block (a refinement
// that no longer helps), the lane stops updating. Lanes with one colour are
// packed from bc7_shared.h's table, as the reference does.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "bc/bc7_lanes_simd.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include <algorithm>
#include <climits>
#include <memory>

#include "bc/bc7_lanes.h"
#include "bc/bc7_shared.h"
#include "bc/bc7_estimate_simd-inl.h"
#include "bc/bc7_span_simd-inl.h"
#include "texproc/runtime.h"

HWY_BEFORE_NAMESPACE();
namespace texproc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using bc7::EndpointFormat;
using bc7::Pbit;

// As the reference's SetFit, a lane each.
struct SetFitV {
  V code[2][4], pbit[2], value[2][4];
  V index[16];
  V error;
};

// As the reference's Set: the texels (possibly rotated), the members (a
// mask per texel), the channels.
struct SetV {
  const V (*x)[4];
  const M* member;
  int c0, n;
};

// The lanes' best candidate so far (the reference's Best and Choice).
struct BestV {
  V error, mode, partition, rotation, isel;
  V code[3][2][4], pbit[3][2];
  V color_index[16], alpha_index[16];
};

struct Bc7Batch {
  const DI d;
  const DF df;
  const Bc7Level& level;
  V x[16][4];
  M opaque, solid;
  V alpha_error;
  BestV best;
  M all_members[16];
  V weight_table[3];  // 2-, 3- and 4-bit indices' weights, as many as the lanes hold

  HWY_ATTR explicit Bc7Batch(const Bc7Level& l) : level(l) {
    for (auto& m : all_members) m = hn::FirstN(d, kBc7Batch);
    for (int b = 2; b <= 4; ++b) {
      std::int32_t w[kBc7Batch] = {};
      for (int j = 0; j < std::min(1 << b, kBc7Batch); ++j) w[j] = bptc::weights(b)[j];
      weight_table[b - 2] = hn::LoadU(d, w);
    }
  }

  HWY_INLINE VF f(V v) const { return hn::ConvertTo(df, v); }

  HWY_INLINE void load(const std::uint32_t texel[16][kBc7Batch], int k0) {
    opaque = hn::FirstN(d, kBc7Batch), solid = opaque;
    alpha_error = hn::Zero(d);
    const V first = hn::LoadU(d, reinterpret_cast<const std::int32_t*>(texel[0]) + k0);
    for (int i = 0; i < 16; ++i) {
      const V t = hn::LoadU(d, reinterpret_cast<const std::int32_t*>(texel[i]) + k0);
      for (int c = 0; c < 4; ++c) x[i][c] = hn::And(hn::ShiftRightSame(t, 8 * c), hn::Set(d, 255));  // masked: the shift is arithmetic
      opaque = hn::And(opaque, hn::Eq(x[i][3], hn::Set(d, 255)));
      solid = hn::And(solid, hn::Eq(t, first));
      const V da = hn::Sub(hn::Set(d, 255), x[i][3]);
      alpha_error = hn::Add(alpha_error, hn::Mul(da, da));
    }
    best.error = hn::IfThenElse(solid, hn::Zero(d), hn::Set(d, INT_MAX));
  }

  // As ref::line_ends.
  HWY_INLINE void line_ends(const SetV& s, VF e[2][4]) const {
    V cnt = hn::Zero(d), S[4], Q[4][4], mn[4], mx[4];
    for (int a = 0; a < s.n; ++a) {
      S[a] = hn::Zero(d), mn[a] = hn::Set(d, 255), mx[a] = hn::Zero(d);
      for (int b = a; b < s.n; ++b) Q[a][b] = hn::Zero(d);
    }
    for (int i = 0; i < 16; ++i) {
      const M m = s.member[i];
      cnt = hn::Add(cnt, hn::IfThenElseZero(m, hn::Set(d, 1)));
      for (int a = 0; a < s.n; ++a) {
        const V xa = s.x[i][s.c0 + a];
        S[a] = hn::Add(S[a], hn::IfThenElseZero(m, xa));
        mn[a] = hn::IfThenElse(m, hn::Min(mn[a], xa), mn[a]), mx[a] = hn::IfThenElse(m, hn::Max(mx[a], xa), mx[a]);
        for (int b = a; b < s.n; ++b) Q[a][b] = hn::Add(Q[a][b], hn::IfThenElseZero(m, hn::Mul(xa, s.x[i][s.c0 + b])));
      }
    }
    VF mean[4];
    for (int a = 0; a < s.n; ++a) mean[a] = hn::Div(f(S[a]), f(cnt));
    if (s.n == 1) {
      e[0][s.c0] = f(mn[0]), e[1][s.c0] = f(mx[0]);
      return;
    }
    VF C[4][4];
    for (int a = 0; a < s.n; ++a)
      for (int b = a; b < s.n; ++b) C[a][b] = C[b][a] = f(hn::Sub(hn::Mul(cnt, Q[a][b]), hn::Mul(S[a], S[b])));
    VF diag = C[0][0], v[4];
    for (int a = 0; a < s.n; ++a) v[a] = C[a][0];
    for (int j = 1; j < s.n; ++j) {
      const auto gt = hn::Gt(C[j][j], diag);
      diag = hn::IfThenElse(gt, C[j][j], diag);
      for (int a = 0; a < s.n; ++a) v[a] = hn::IfThenElse(gt, C[a][j], v[a]);
    }
    const auto flat = hn::Eq(diag, hn::Zero(df));
    for (int it = 0; it < 3; ++it) {
      VF w[4], m = hn::Zero(df);
      for (int a = 0; a < s.n; ++a) {
        w[a] = hn::Zero(df);
        for (int b = 0; b < s.n; ++b) w[a] = hn::Add(w[a], hn::Mul(C[a][b], v[b]));
        m = hn::Max(m, hn::Abs(w[a]));
      }
      const auto moved = hn::Ne(m, hn::Zero(df));
      const VF inv = hn::Div(hn::Set(df, 1.0f), hn::IfThenElse(moved, m, hn::Set(df, 1.0f)));
      for (int a = 0; a < s.n; ++a) v[a] = hn::IfThenElse(moved, hn::Mul(w[a], inv), v[a]);
    }
    VF tmin = hn::Set(df, HUGE_VALF), tmax = hn::Set(df, -HUGE_VALF), tmean = hn::Zero(df), vv = hn::Zero(df);
    for (int i = 0; i < 16; ++i) {
      VF t = hn::Zero(df);
      for (int a = 0; a < s.n; ++a) t = hn::Add(t, hn::Mul(v[a], f(s.x[i][s.c0 + a])));
      const auto m = hn::RebindMask(df, s.member[i]);
      tmin = hn::IfThenElse(m, hn::Min(tmin, t), tmin), tmax = hn::IfThenElse(m, hn::Max(tmax, t), tmax);
    }
    for (int a = 0; a < s.n; ++a) tmean = hn::Add(tmean, hn::Mul(v[a], mean[a])), vv = hn::Add(vv, hn::Mul(v[a], v[a]));
    const VF safe_vv = hn::IfThenElse(flat, hn::Set(df, 1.0f), vv);
    const VF s0 = hn::Div(hn::Sub(tmin, tmean), safe_vv), s1 = hn::Div(hn::Sub(tmax, tmean), safe_vv);
    for (int a = 0; a < s.n; ++a) {
      e[0][s.c0 + a] = hn::IfThenElse(flat, mean[a], hn::Add(mean[a], hn::Mul(s0, v[a])));
      e[1][s.c0 + a] = hn::IfThenElse(flat, mean[a], hn::Add(mean[a], hn::Mul(s1, v[a])));
    }
  }

  // As ref::quantize_ends; `force_p1` per lane.
  HWY_INLINE void quantize_ends(const SetV& s, const VF e[2][4], EndpointFormat fmt, M force_p1, SetFitV& fit, int combo = -1) const {
    const std::int32_t* table = bc7::kQuantPairs[fmt.bits - 4][fmt.pbit == Pbit::none ? 0 : 1];
    V v[2][4], q0[2][4], q1[2][4];
    V err0[2] = {hn::Zero(d), hn::Zero(d)}, err1[2] = {hn::Zero(d), hn::Zero(d)};
    for (int k = 0; k < 2; ++k)
      for (int a = 0; a < s.n; ++a) {
        const VF c = hn::Min(hn::Max(e[k][s.c0 + a], hn::Zero(df)), hn::Set(df, 255.0f));
        v[k][a] = hn::ConvertTo(d, hn::Round(c));
        const V pair = hn::GatherIndex(d, table, v[k][a]);
        q0[k][a] = hn::And(pair, hn::Set(d, 0xFFFF)), q1[k][a] = hn::And(hn::ShiftRight<16>(pair), hn::Set(d, 0xFFFF));  // the shift is arithmetic
        const V d0 = hn::Sub(hn::ShiftRight<8>(q0[k][a]), v[k][a]), d1 = hn::Sub(hn::ShiftRight<8>(q1[k][a]), v[k][a]);
        err0[k] = hn::Add(err0[k], hn::Mul(d0, d0)), err1[k] = hn::Add(err1[k], hn::Mul(d1, d1));
      }
    M p1[2] = {hn::FirstN(d, 0), hn::FirstN(d, 0)};
    if (fmt.pbit != Pbit::none && combo >= 0) {
      const int second = fmt.pbit == Pbit::unique ? combo >> 1 & 1 : combo & 1;
      p1[0] = hn::Or(force_p1, hn::FirstN(d, (combo & 1) ? kBc7Batch : 0)), p1[1] = hn::Or(force_p1, hn::FirstN(d, second ? kBc7Batch : 0));
    } else if (fmt.pbit == Pbit::unique) {
      for (int k = 0; k < 2; ++k) p1[k] = hn::Or(force_p1, hn::Lt(err1[k], err0[k]));
    } else if (fmt.pbit == Pbit::shared) {
      p1[0] = p1[1] = hn::Or(force_p1, hn::Lt(hn::Add(err1[0], err1[1]), hn::Add(err0[0], err0[1])));
    }
    for (int k = 0; k < 2; ++k) {
      fit.pbit[k] = hn::IfThenElseZero(p1[k], hn::Set(d, 1));
      for (int a = 0; a < s.n; ++a) {
        const V q = hn::IfThenElse(p1[k], q1[k][a], q0[k][a]);
        fit.code[k][s.c0 + a] = hn::And(q, hn::Set(d, 255)), fit.value[k][s.c0 + a] = hn::ShiftRight<8>(q);
      }
    }
  }

  // The weight (out of 64) of index j of 2^bits: the table's, one lane
  // permute where a vector holds the table, else round(64 j / L) as
  // floor((128 j + L) / 2L), which is never a whole number, so the float
  // product floors exactly (tests compare both with the tables).
  HWY_INLINE V weight(V j, int L) const {
    if (L < int(hn::Lanes(d))) return hn::TableLookupLanes(weight_table[L == 3 ? 0 : L == 7 ? 1 : 2], hn::IndicesFromVec(d, j));
    const VF num = f(hn::Add(hn::Mul(j, hn::Set(d, 128)), hn::Set(d, L)));
    return hn::ConvertTo(d, hn::Floor(hn::Mul(num, hn::Set(df, 1.0f / float(2 * L)))));
  }
  // Texel i's squared error at index j: each channel's palette entry
  // (64 - w) e0 + w e1 + 32 >> 6 as e0 + (w (e1 - e0) + 32 >> 6), the same
  // integer (64 e0 is a whole multiple of 64).
  HWY_INLINE V texel_error(const SetV& s, const SetFitV& fit, const V dv[4], int i, V j, int L) const {
    const V w = weight(j, L);
    V t = hn::Zero(d);
    for (int a = 0; a < s.n; ++a) {
      const V p = hn::Add(fit.value[0][s.c0 + a], hn::ShiftRight<6>(hn::Add(hn::Mul(w, dv[a]), hn::Set(d, 32))));
      const V e = hn::Sub(p, s.x[i][s.c0 + a]);
      t = hn::Add(t, hn::Mul(e, e));
    }
    return t;
  }

  // As ref::assign; the projection's sum of (x - e0) d as x d - e0 d.
  HWY_INLINE void assign(const SetV& s, int bits, SetFitV& fit) const { assign(s, bits, level.exact_indices, fit); }
  HWY_INLINE void assign(const SetV& s, int bits, bool exact, SetFitV& fit) const {
    const int L = (1 << bits) - 1;
    V dv[4], dd = hn::Zero(d), origin = hn::Zero(d);
    for (int a = 0; a < s.n; ++a) {
      dv[a] = hn::Sub(fit.value[1][s.c0 + a], fit.value[0][s.c0 + a]), dd = hn::Add(dd, hn::Mul(dv[a], dv[a]));
      origin = hn::Add(origin, hn::Mul(fit.value[0][s.c0 + a], dv[a]));
    }
    const auto spread = hn::RebindMask(df, hn::Gt(dd, hn::Zero(d)));
    const VF scale = hn::IfThenElseZero(spread, hn::Div(hn::Set(df, float(L)), f(hn::Max(dd, hn::Set(d, 1)))));
    fit.error = hn::Zero(d);
    for (int i = 0; i < 16; ++i) {
      V t = hn::Neg(origin);
      for (int a = 0; a < s.n; ++a) t = hn::Add(t, hn::Mul(s.x[i][s.c0 + a], dv[a]));
      V j = hn::ConvertTo(d, hn::Round(hn::Mul(f(t), scale)));
      j = hn::Min(hn::Max(j, hn::Zero(d)), hn::Set(d, L));
      V e = texel_error(s, fit, dv, i, j, L);
      if (exact) {
        const V j0 = j, lo = hn::Sub(j0, hn::Set(d, 1)), hi = hn::Add(j0, hn::Set(d, 1));
        const V elo = texel_error(s, fit, dv, i, hn::Max(lo, hn::Zero(d)), L);
        const M take_lo = hn::And(hn::Gt(j0, hn::Zero(d)), hn::Lt(elo, e));
        e = hn::IfThenElse(take_lo, elo, e), j = hn::IfThenElse(take_lo, lo, j);
        const V ehi = texel_error(s, fit, dv, i, hn::Min(hi, hn::Set(d, L)), L);
        const M take_hi = hn::And(hn::Lt(j0, hn::Set(d, L)), hn::Lt(ehi, e));
        e = hn::IfThenElse(take_hi, ehi, e), j = hn::IfThenElse(take_hi, hi, j);
      }
      fit.index[i] = hn::IfThenElse(s.member[i], j, fit.index[i]);
      fit.error = hn::Add(fit.error, hn::IfThenElseZero(s.member[i], e));
    }
  }

  // As ref::lsq_ends: the mask of lanes with a determined solution.
  HWY_INLINE M lsq_ends(const SetV& s, int bits, const SetFitV& fit, VF e[2][4]) const {
    const int L = (1 << bits) - 1;
    V AA = hn::Zero(d), AB = AA, BB = AA, RA[4], RB[4];
    for (int c = 0; c < s.n; ++c) RA[c] = RB[c] = hn::Zero(d);
    for (int i = 0; i < 16; ++i) {
      const M m = s.member[i];
      const V b = hn::IfThenElseZero(m, weight(fit.index[i], L)), a = hn::IfThenElseZero(m, hn::Sub(hn::Set(d, 64), b));
      AA = hn::Add(AA, hn::Mul(a, a)), AB = hn::Add(AB, hn::Mul(a, b)), BB = hn::Add(BB, hn::Mul(b, b));
      for (int c = 0; c < s.n; ++c) RA[c] = hn::Add(RA[c], hn::Mul(a, s.x[i][s.c0 + c])), RB[c] = hn::Add(RB[c], hn::Mul(b, s.x[i][s.c0 + c]));
    }
    const VF fAA = f(AA), fAB = f(AB), fBB = f(BB);
    const VF det = hn::Sub(hn::Mul(fAA, fBB), hn::Mul(fAB, fAB));
    const auto ok = hn::Gt(det, hn::Zero(df));
    const VF inv = hn::Div(hn::Set(df, 64.0f), hn::IfThenElse(ok, det, hn::Set(df, 1.0f)));
    for (int c = 0; c < s.n; ++c) {
      e[0][s.c0 + c] = hn::Mul(hn::Sub(hn::Mul(f(RA[c]), fBB), hn::Mul(f(RB[c]), fAB)), inv);
      e[1][s.c0 + c] = hn::Mul(hn::Sub(hn::Mul(f(RB[c]), fAA), hn::Mul(f(RA[c]), fAB)), inv);
    }
    return hn::RebindMask(d, ok);
  }

  HWY_INLINE void select_fit(M m, const SetFitV& from, SetFitV& to, const SetV& s) const {
    for (int k = 0; k < 2; ++k) {
      to.pbit[k] = hn::IfThenElse(m, from.pbit[k], to.pbit[k]);
      for (int a = s.c0; a < s.c0 + s.n; ++a)
        to.code[k][a] = hn::IfThenElse(m, from.code[k][a], to.code[k][a]), to.value[k][a] = hn::IfThenElse(m, from.value[k][a], to.value[k][a]);
    }
    for (int i = 0; i < 16; ++i) to.index[i] = hn::IfThenElse(m, from.index[i], to.index[i]);
    to.error = hn::IfThenElse(m, from.error, to.error);
  }

  // As ref::quantize_assign (forced lanes' p-bits stay 1 in every choice).
  HWY_INLINE void quantize_assign(const SetV& s, const VF e[2][4], EndpointFormat fmt, int bits, M force_p1, SetFitV& fit) const {
    quantize_ends(s, e, fmt, force_p1, fit);
    assign(s, bits, fit);
    if (!level.pbit_search || fmt.pbit == Pbit::none || hn::AllTrue(d, force_p1)) return;
    for (int combo = 0; combo < (fmt.pbit == Pbit::unique ? 4 : 2); ++combo) {
      SetFitV next = fit;
      quantize_ends(s, e, fmt, force_p1, next, combo);
      assign(s, bits, next);
      select_fit(hn::Lt(next.error, fit.error), next, fit, s);
    }
  }

  // As ref::fit_set.
  HWY_INLINE void fit_set(const SetV& s, EndpointFormat fmt, int bits, M force_p1, SetFitV& best_fit) const {
    VF e[2][4];
    line_ends(s, e);
    for (auto& j : best_fit.index) j = hn::Zero(d);
    quantize_assign(s, e, fmt, bits, force_p1, best_fit);
    M active = hn::Gt(best_fit.error, hn::Zero(d));
    for (int pass = 0; pass < level.refine && !hn::AllFalse(d, active); ++pass) {
      const M ok = lsq_ends(s, bits, best_fit, e);
      SetFitV next = best_fit;
      quantize_assign(s, e, fmt, bits, force_p1, next);
      const M better = hn::And(hn::And(active, ok), hn::Lt(next.error, best_fit.error));
      select_fit(better, next, best_fit, s);
      active = hn::And(better, hn::Gt(best_fit.error, hn::Zero(d)));
    }
    step_ends(s, fmt, bits, level.exact_indices, level.perturb, hn::FirstN(d, kBc7Batch), best_fit);
  }

  // As bc7::expand: a code (and its p-bit where the format has one) as
  // the decoder widens it to 8 bits.
  HWY_INLINE V expand(V code, V pbit, EndpointFormat fmt) const {
    const bool has_p = fmt.pbit != Pbit::none;
    const int n = fmt.bits + (has_p ? 1 : 0);
    const V v = has_p ? hn::Or(hn::ShiftLeft<1>(code), pbit) : code;
    return hn::And(hn::Or(hn::ShiftLeftSame(v, 8 - n), hn::ShiftRightSame(v, 2 * n - 8)), hn::Set(d, 255));
  }

  // As ref::step_ends, in the lanes `going`.
  HWY_INLINE void step_ends(const SetV& s, EndpointFormat fmt, int bits, bool exact, int rounds, M going, SetFitV& best_fit) const {
    const int top = (1 << fmt.bits) - 1;
    for (int round = 0; round < rounds; ++round) {
      const M now = hn::And(going, hn::Gt(best_fit.error, hn::Zero(d)));
      if (hn::AllFalse(d, now)) break;
      M moved = hn::FirstN(d, 0);
      for (int k = 0; k < 2; ++k)
        for (int a = 0; a < s.n; ++a)
          for (const int step : {-1, 1}) {
            const V code = hn::Add(best_fit.code[k][s.c0 + a], hn::Set(d, step));
            const M valid = hn::And(now, hn::And(hn::Gt(code, hn::Set(d, -1)), hn::Lt(code, hn::Set(d, top + 1))));
            if (hn::AllFalse(d, valid)) continue;
            SetFitV next = best_fit;
            next.code[k][s.c0 + a] = code;
            next.value[k][s.c0 + a] = expand(code, best_fit.pbit[k], fmt);
            assign(s, bits, exact, next);
            const M better = hn::And(valid, hn::Lt(next.error, best_fit.error));
            select_fit(better, next, best_fit, s);
            moved = hn::Or(moved, better);
          }
      if (level.pair_steps)
        for (int a = 0; a < s.n; ++a)
          for (const int step : {0, 1, 2, 3}) {  // both up, both down, apart, together
            V code[2];
            M valid = now;
            for (int k = 0; k < 2; ++k) {
              const int dk = step == 0 ? 1 : step == 1 ? -1 : (step == 2) == (k == 1) ? 1 : -1;
              code[k] = hn::Add(best_fit.code[k][s.c0 + a], hn::Set(d, dk));
              valid = hn::And(valid, hn::And(hn::Gt(code[k], hn::Set(d, -1)), hn::Lt(code[k], hn::Set(d, top + 1))));
            }
            if (hn::AllFalse(d, valid)) continue;
            SetFitV next = best_fit;
            for (int k = 0; k < 2; ++k) {
              next.code[k][s.c0 + a] = code[k];
              next.value[k][s.c0 + a] = expand(code[k], best_fit.pbit[k], fmt);
            }
            assign(s, bits, exact, next);
            const M better = hn::And(valid, hn::Lt(next.error, best_fit.error));
            select_fit(better, next, best_fit, s);
            moved = hn::Or(moved, better);
          }
      going = hn::And(now, moved);
    }
  }

  // A candidate's mode, partition, rotation and index selection, a lane each.
  struct Header {
    V mode, partition, rotation, isel;
  };

  // As ref::Best::offer: the candidate replaces the best where `allowed` and its error is less.
  HWY_INLINE void offer(M allowed, V error, const Header& h, const V code[3][2][4], const V pbit[3][2], const V* color_index,
                        const V* alpha_index) {
    const M take = hn::And(allowed, hn::Lt(error, best.error));
    if (hn::AllFalse(d, take)) return;
    best.error = hn::IfThenElse(take, error, best.error);
    best.mode = hn::IfThenElse(take, h.mode, best.mode);
    best.partition = hn::IfThenElse(take, h.partition, best.partition);
    best.rotation = hn::IfThenElse(take, h.rotation, best.rotation);
    best.isel = hn::IfThenElse(take, h.isel, best.isel);
    for (int s = 0; s < 3; ++s)
      for (int k = 0; k < 2; ++k) {
        best.pbit[s][k] = hn::IfThenElse(take, pbit[s][k], best.pbit[s][k]);
        for (int c = 0; c < 4; ++c) best.code[s][k][c] = hn::IfThenElse(take, code[s][k][c], best.code[s][k][c]);
      }
    for (int i = 0; i < 16; ++i) {
      best.color_index[i] = hn::IfThenElse(take, color_index[i], best.color_index[i]);
      best.alpha_index[i] = hn::IfThenElse(take, alpha_index[i], best.alpha_index[i]);
    }
  }

  // Mode 6 (as the reference's first candidate). With every lane opaque,
  // alpha is left out of the fit: its covariance row is zero (R, G and B
  // get the same floats), its ends 255 (code 127, p-bit 1, as forced).
  HWY_INLINE void try_mode6() {
    SetFitV fit;
    const bool rgb = hn::AllTrue(d, opaque);
    fit_set(SetV{x, all_members, 0, rgb ? 3 : 4}, bc7::color_format(6), 4, opaque, fit);
    if (rgb)
      for (int k = 0; k < 2; ++k) fit.code[k][3] = hn::Set(d, 127), fit.value[k][3] = hn::Set(d, 255);
    V code[3][2][4], pbit[3][2], zero[16];
    zero_candidate(code, pbit, zero);
    for (int k = 0; k < 2; ++k) {
      pbit[0][k] = fit.pbit[k];
      for (int a = 0; a < 4; ++a) code[0][k][a] = fit.code[k][a];
    }
    const Header header{hn::Set(d, 6), hn::Zero(d), hn::Zero(d), hn::Zero(d)};
    offer(hn::FirstN(d, kBc7Batch), fit.error, header, code, pbit, fit.index, zero);
  }

  HWY_INLINE void zero_candidate(V code[3][2][4], V pbit[3][2], V zero[16]) const {
    for (int s = 0; s < 3; ++s)
      for (int k = 0; k < 2; ++k) {
        pbit[s][k] = hn::Zero(d);
        for (int c = 0; c < 4; ++c) code[s][k][c] = hn::Zero(d);
      }
    for (int i = 0; i < 16; ++i) zero[i] = hn::Zero(d);
  }

  // As ref::try_partitioned; the partition per lane.
  HWY_INLINE void try_partitioned(int mode, V part, M allowed) {
    const bptc::Bc7Mode& Md = bptc::kBc7Modes[mode];
    const std::int32_t* table = reinterpret_cast<const std::int32_t*>(Md.subsets == 2 ? bptc::kPartitions2 : bptc::kPartitions3);
    const V bits = hn::GatherIndex(d, table, part);
    const int n = Md.alpha_bits ? 4 : 3;
    V code[3][2][4], pbit[3][2], color_index[16], zero[16];
    zero_candidate(code, pbit, zero);
    for (int i = 0; i < 16; ++i) color_index[i] = hn::Zero(d);
    V error = n == 3 ? alpha_error : hn::Zero(d);
    const M force = n == 4 ? opaque : hn::FirstN(d, 0);
    for (int s = 0; s < Md.subsets; ++s) {
      M member[16];
      for (int i = 0; i < 16; ++i) member[i] = hn::Eq(hn::And(hn::ShiftRightSame(bits, 2 * i), hn::Set(d, 3)), hn::Set(d, s));
      SetFitV fit;
      fit_set(SetV{x, member, 0, n}, bc7::color_format(mode), Md.index_bits, force, fit);
      error = hn::Add(error, fit.error);
      for (int k = 0; k < 2; ++k) {
        pbit[s][k] = fit.pbit[k];
        for (int a = 0; a < n; ++a) code[s][k][a] = fit.code[k][a];
      }
      for (int i = 0; i < 16; ++i) color_index[i] = hn::IfThenElse(member[i], fit.index[i], color_index[i]);
    }
    const Header header{hn::Set(d, mode), part, hn::Zero(d), hn::Zero(d)};
    offer(allowed, error, header, code, pbit, color_index, zero);
  }

  // As ref::try_rotated.
  HWY_INLINE void try_rotated(int mode, int rotation, int isel, M allowed) {
    if (hn::AllFalse(d, hn::AndNot(solid, allowed))) return;
    const bptc::Bc7Mode& Md = bptc::kBc7Modes[mode];
    V y[16][4];
    for (int i = 0; i < 16; ++i) {
      for (int c = 0; c < 4; ++c) y[i][c] = x[i][c];
      if (rotation) std::swap(y[i][3], y[i][rotation - 1]);
    }
    const int color_bits = isel ? Md.index2_bits : Md.index_bits, alpha_bits = isel ? Md.index_bits : Md.index2_bits;
    const M none = hn::FirstN(d, 0);
    SetFitV rgb, alpha;
    fit_set(SetV{y, all_members, 0, 3}, {Md.color_bits, Pbit::none}, color_bits, none, rgb);
    fit_set(SetV{y, all_members, 3, 1}, {Md.alpha_bits, Pbit::none}, alpha_bits, none, alpha);
    V code[3][2][4], pbit[3][2], zero[16];
    zero_candidate(code, pbit, zero);
    for (int k = 0; k < 2; ++k) {
      for (int a = 0; a < 3; ++a) code[0][k][a] = rgb.code[k][a];
      code[0][k][3] = alpha.code[k][3];
    }
    const Header header{hn::Set(d, mode), hn::Zero(d), hn::Set(d, rotation), hn::Set(d, isel)};
    offer(allowed, hn::Add(rgb.error, alpha.error), header, code, pbit, rgb.index, alpha.index);
  }

  // As ref::step_winner, on the lanes `here`, whose winner is `mode`.
  HWY_INLINE void step_mode(int mode, M here) {
    const bptc::Bc7Mode& Md = bptc::kBc7Modes[mode];
    const EndpointFormat fmt = bc7::color_format(mode);
    const int n = Md.alpha_bits ? 4 : 3;
    V bits = hn::Zero(d);
    if (Md.subsets > 1) {
      const std::int32_t* table = reinterpret_cast<const std::int32_t*>(Md.subsets == 2 ? bptc::kPartitions2 : bptc::kPartitions3);
      bits = hn::GatherIndex(d, table, hn::And(best.partition, hn::Set(d, 63)));
    }
    for (int s = 0; s < Md.subsets; ++s) {
      M member[16];
      for (int i = 0; i < 16; ++i) member[i] = hn::Eq(hn::And(hn::ShiftRightSame(bits, 2 * i), hn::Set(d, 3)), hn::Set(d, s));
      const SetV set{x, member, 0, n};
      SetFitV fit;
      for (int k = 0; k < 2; ++k) {
        fit.pbit[k] = best.pbit[s][k];
        for (int a = 0; a < n; ++a) {
          fit.code[k][a] = best.code[s][k][a];
          fit.value[k][a] = expand(fit.code[k][a], fit.pbit[k], fmt);
        }
      }
      for (int i = 0; i < 16; ++i) fit.index[i] = best.color_index[i];
      const bool exact = level.exact_indices || level.exact_winner;
      assign(set, Md.index_bits, exact, fit);
      step_ends(set, fmt, Md.index_bits, exact, level.winner_steps, here, fit);
      for (int k = 0; k < 2; ++k)
        for (int a = 0; a < n; ++a) best.code[s][k][a] = hn::IfThenElse(here, fit.code[k][a], best.code[s][k][a]);
      for (int i = 0; i < 16; ++i) best.color_index[i] = hn::IfThenElse(hn::And(here, member[i]), fit.index[i], best.color_index[i]);
    }
  }

  // As ref::encode_block, the lanes together; lanes of one colour are
  // packed by the caller.
  HWY_INLINE void search() {
    best.mode = best.partition = best.rotation = best.isel = hn::Zero(d);
    zero_candidate(best.code, best.pbit, best.color_index);
    for (auto& v : best.alpha_index) v = hn::Zero(d);
    const M all = hn::FirstN(d, kBc7Batch);
    try_mode6();
    RankedV two;
    init(two, std::min(level.partitions2, level.estimated2));
    if (level.partitions2 > 0) {
      rank_partitions(x, 2, level.estimated2, two, nullptr);
      for (int r = 0; r < two.k; ++r) {
        try_partitioned(1, two.partition[r], all);
        if (level.mode3) try_partitioned(3, two.partition[r], all);
      }
    }
    if (level.partitions3 > 0) {
      RankedV three, three16;
      init(three, std::min(level.partitions3, 64)), init(three16, std::min(level.partitions3, 16));
      rank_partitions(x, 3, 64, three, &three16);
      for (int r = 0; r < three16.k; ++r) try_partitioned(0, three16.partition[r], all);
      for (int r = 0; r < three.k; ++r) try_partitioned(2, three.partition[r], all);
    }
    const M with_alpha = hn::Not(opaque), rotated = level.opaque_rotated ? hn::FirstN(d, kBc7Batch) : with_alpha;
    if (hn::AllFalse(d, hn::AndNot(solid, rotated))) return;
    for (int rot = 0; rot < level.rotations; ++rot) try_rotated(5, rot, 0, rot ? rotated : with_alpha);
    for (int rot = 0; rot < level.rotations; ++rot)
      for (int isel = 0; isel < (level.index_selection ? 2 : 1); ++isel) try_rotated(4, rot, isel, rot ? rotated : with_alpha);
    if (level.mode7 && !hn::AllFalse(d, hn::AndNot(solid, with_alpha)))
      for (int r = 0; r < two.k; ++r) try_partitioned(7, two.partition[r], with_alpha);
  }

  // The lanes' choices into t's lanes k0 on (every field stored once; the
  // packer reads them a lane a block), and back.
  HWY_INLINE void store(bc7::LaneChoices& t, int k0) const {
    hn::StoreU(hn::VecFromMask(d, solid), d, t.solid + k0);
    for (int c = 0; c < 4; ++c) hn::StoreU(x[0][c], d, t.x0[c] + k0);
    hn::StoreU(best.mode, d, t.mode + k0), hn::StoreU(best.partition, d, t.partition + k0);
    hn::StoreU(best.rotation, d, t.rotation + k0), hn::StoreU(best.isel, d, t.isel + k0);
    for (int s = 0; s < 3; ++s)
      for (int e = 0; e < 2; ++e) {
        hn::StoreU(best.pbit[s][e], d, t.pbit[s][e] + k0);
        for (int ch = 0; ch < 4; ++ch) hn::StoreU(best.code[s][e][ch], d, t.code[s][e][ch] + k0);
      }
    for (int i = 0; i < 16; ++i) hn::StoreU(best.color_index[i], d, t.color_index[i] + k0), hn::StoreU(best.alpha_index[i], d, t.alpha_index[i] + k0);
  }
  HWY_INLINE void load_choices(const bc7::LaneChoices& t) {
    best.mode = hn::LoadU(d, t.mode), best.partition = hn::LoadU(d, t.partition);
    best.rotation = hn::LoadU(d, t.rotation), best.isel = hn::LoadU(d, t.isel);
    for (int s = 0; s < 3; ++s)
      for (int e = 0; e < 2; ++e) {
        best.pbit[s][e] = hn::LoadU(d, t.pbit[s][e]);
        for (int ch = 0; ch < 4; ++ch) best.code[s][e][ch] = hn::LoadU(d, t.code[s][e][ch]);
      }
    for (int i = 0; i < 16; ++i) best.color_index[i] = hn::LoadU(d, t.color_index[i]), best.alpha_index[i] = hn::LoadU(d, t.alpha_index[i]);
  }
};

void Bc7EncodeLanes(const Bc7Texels* texel, int count, const Bc7Level& level, std::uint8_t out[][16]) {
  Bc7Batch batch(level);
  const int step = int(hn::Lanes(batch.d));
  // Without winner steps a batch is packed as soon as it is searched (its
  // choices still in cache); with them, a span's choices wait for the steps.
  // Not zeroed: only the lanes searched are read.
  const bool stepped = level.winner_steps > 0;
  const std::unique_ptr<bc7::LaneChoices[]> t(new bc7::LaneChoices[stepped ? kBc7Span / kBc7Batch : 1]);
  for (int s0 = 0; s0 < count; s0 += kBc7Span) {
    const int span = std::min(kBc7Span, count - s0);
    for (int b = 0; b * kBc7Batch < span; ++b) {
      bc7::LaneChoices& tb = t[stepped ? b : 0];
      for (int k0 = 0; k0 < kBc7Batch && b * kBc7Batch + k0 < span; k0 += step) {
        batch.load(texel[s0 / kBc7Batch + b], k0);
        if (!hn::AllTrue(batch.d, batch.solid)) batch.search();
        batch.store(tb, k0);
      }
      if (!stepped) bc7::pack_lanes_simd(tb, std::min(kBc7Batch, span - b * kBc7Batch), out + s0 + b * kBc7Batch);
    }
    if (!stepped) continue;
    step_winners(batch, texel + s0 / kBc7Batch, t.get(), span);
    for (int b = 0; b * kBc7Batch < span; ++b) bc7::pack_lanes_simd(t[b], std::min(kBc7Batch, span - b * kBc7Batch), out + s0 + b * kBc7Batch);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace texproc
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace texproc {
HWY_EXPORT(Bc7EncodeLanes);

void bc7_encode_lanes(const Bc7Texels* texel, int count, const Bc7Level& level, std::uint8_t out[][16]) {
  if (force_scalar()) return ref::bc7_encode_lanes(texel, count, level, out);
  HWY_DYNAMIC_DISPATCH(Bc7EncodeLanes)(texel, count, level, out);
}
}  // namespace texproc
#endif
