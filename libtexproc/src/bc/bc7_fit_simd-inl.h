// BC7's endpoint fit, a block per lane, for bc7_lanes_simd.cpp (included
// once per Highway target, as Highway's -inl headers are): a subset's ends
// from its principal line or its seeds, quantized (alone or jointly) to the
// mode's codes and p-bits, the indices assigned, refined by least squares
// and stepped. As the ref:: functions of the same names in bc7_lanes.cpp.
// The texel passes (line_ends, assign, lsq_ends) and quantize_joint are
// out of line, one copy for each channel count (1, 3, 4), and so is
// fit_set: inlined into every caller, bc7_lanes_simd.cpp took 5-7 minutes
// to compile for every target, and ran 7-10% slower.
#if defined(TEXPROC_BC7_FIT_SIMD_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef TEXPROC_BC7_FIT_SIMD_INL_H_
#undef TEXPROC_BC7_FIT_SIMD_INL_H_
#else
#define TEXPROC_BC7_FIT_SIMD_INL_H_
#endif

#include <hwy/highway.h>

#include <algorithm>
#include <climits>
#include <cstdint>
#include <type_traits>

#include "bc/bc7_estimate_simd-inl.h"
#include "bc/bc7_lanes.h"
#include "bc/bc7_shared.h"

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

// Whether a lane's two 16-bit halves can hold two channels (every target
// but HWY_SCALAR, whose one lane has no halves): the texel passes of sets
// of 3 and 4 channels then work on pairs (under `if constexpr` in the
// per-channel-count templates, so that HWY_SCALAR never instantiates them).
constexpr bool kChannelPairs = HWY_TARGET != HWY_SCALAR;

// The texels' channels in pairs (pair16): R G, B alone, B A; a set of 3
// channels uses the first two, of 4 the first and the third.
using PairsV = V[3];
HWY_INLINE void make_pairs(const V x[4], PairsV& xp) {
  xp[0] = pair16(x[0], x[1]);
  xp[1] = x[2];
  xp[2] = pair16(x[2], x[3]);
}

// As the reference's Set: the texels (possibly rotated), the members (a
// mask per texel), the channels; the texels in pairs too (for sets of 3
// and 4 channels from channel 0, where kChannelPairs).
struct SetV {
  const V (*x)[4];
  const M* member;
  int c0, n;
  const PairsV* xp;
};

// The fit of one subset at a time, on every lane: what Bc7Batch builds on.
struct Bc7FitLanes {
  const DI d;
  const DF df;
  const Bc7Level& level;
  V weight_table[3];  // 2-, 3- and 4-bit indices' weights, as many as the lanes hold
  V weight_pairs[3];  // the same, each weight in both 16-bit halves

  HWY_ATTR explicit Bc7FitLanes(const Bc7Level& l) : level(l) {
    for (int b = 2; b <= 4; ++b) {
      std::int32_t w[kBc7Batch] = {};
      for (int j = 0; j < std::min(1 << b, kBc7Batch); ++j) w[j] = bptc::weights(b)[j];
      weight_table[b - 2] = hn::LoadU(d, w);
      weight_pairs[b - 2] = pair16(weight_table[b - 2], weight_table[b - 2]);
    }
  }

  HWY_INLINE VF f(V v) const { return hn::ConvertTo(df, v); }

  // f(N) with the set's channel count N (1, 3 or 4) a constant: the texel
  // passes' one copy for each count.
  template <class F>
  static HWY_INLINE auto by_channels(int n, F&& f) {
    if (n == 3) return f(std::integral_constant<int, 3>());
    if (n == 4) return f(std::integral_constant<int, 4>());
    return f(std::integral_constant<int, 1>());
  }

  // As ref::line_ends.
  template <int N>  // the channels, 1, 3 or 4
  HWY_NOINLINE void line_ends_n(const SetV& s, VF e[2][4]) const {
    V cnt = hn::Zero(d), S[4], Q[4][4], mn[4], mx[4];
    for (int a = 0; a < N; ++a) {
      S[a] = hn::Zero(d);
      mn[a] = hn::Set(d, 255);
      mx[a] = hn::Zero(d);
      for (int b = a; b < N; ++b) Q[a][b] = hn::Zero(d);
    }
    for (int i = 0; i < 16; ++i) {
      const M m = s.member[i];
      cnt = hn::Add(cnt, hn::IfThenElseZero(m, hn::Set(d, 1)));
      for (int a = 0; a < N; ++a) {
        const V xa = s.x[i][s.c0 + a];
        S[a] = hn::Add(S[a], hn::IfThenElseZero(m, xa));
        mn[a] = hn::IfThenElse(m, hn::Min(mn[a], xa), mn[a]);
        mx[a] = hn::IfThenElse(m, hn::Max(mx[a], xa), mx[a]);
        for (int b = a; b < N; ++b) Q[a][b] = hn::Add(Q[a][b], hn::IfThenElseZero(m, mul16(xa, s.x[i][s.c0 + b])));
      }
    }
    VF mean[4];
    for (int a = 0; a < N; ++a) mean[a] = hn::Div(f(S[a]), f(cnt));
    if (N == 1) {
      e[0][s.c0] = f(mn[0]);
      e[1][s.c0] = f(mx[0]);
      return;
    }
    VF C[4][4];
    for (int a = 0; a < N; ++a)
      for (int b = a; b < N; ++b) C[a][b] = C[b][a] = f(hn::Sub(hn::Mul(cnt, Q[a][b]), mul16(S[a], S[b])));
    VF diag = C[0][0], v[4];
    for (int a = 0; a < N; ++a) v[a] = C[a][0];
    for (int j = 1; j < N; ++j) {
      const auto gt = hn::Gt(C[j][j], diag);
      diag = hn::IfThenElse(gt, C[j][j], diag);
      for (int a = 0; a < N; ++a) v[a] = hn::IfThenElse(gt, C[a][j], v[a]);
    }
    const auto flat = hn::Eq(diag, hn::Zero(df));
    for (int it = 0; it < 3; ++it) {
      VF w[4], m = hn::Zero(df);
      for (int a = 0; a < N; ++a) {
        w[a] = hn::Zero(df);
        for (int b = 0; b < N; ++b) w[a] = hn::Add(w[a], hn::Mul(C[a][b], v[b]));
        m = hn::Max(m, hn::Abs(w[a]));
      }
      const auto moved = hn::Ne(m, hn::Zero(df));
      const VF inv = hn::Div(hn::Set(df, 1.0f), hn::IfThenElse(moved, m, hn::Set(df, 1.0f)));
      for (int a = 0; a < N; ++a) v[a] = hn::IfThenElse(moved, hn::Mul(w[a], inv), v[a]);
    }
    VF tmin = hn::Set(df, HUGE_VALF), tmax = hn::Set(df, -HUGE_VALF), tmean = hn::Zero(df), vv = hn::Zero(df);
    for (int i = 0; i < 16; ++i) {
      VF t = hn::Zero(df);
      for (int a = 0; a < N; ++a) t = hn::Add(t, hn::Mul(v[a], f(s.x[i][s.c0 + a])));
      const auto m = hn::RebindMask(df, s.member[i]);
      tmin = hn::IfThenElse(m, hn::Min(tmin, t), tmin);
      tmax = hn::IfThenElse(m, hn::Max(tmax, t), tmax);
    }
    for (int a = 0; a < N; ++a) {
      tmean = hn::Add(tmean, hn::Mul(v[a], mean[a]));
      vv = hn::Add(vv, hn::Mul(v[a], v[a]));
    }
    const VF safe_vv = hn::IfThenElse(flat, hn::Set(df, 1.0f), vv);
    const VF s0 = hn::Div(hn::Sub(tmin, tmean), safe_vv), s1 = hn::Div(hn::Sub(tmax, tmean), safe_vv);
    for (int a = 0; a < N; ++a) {
      e[0][s.c0 + a] = hn::IfThenElse(flat, mean[a], hn::Add(mean[a], hn::Mul(s0, v[a])));
      e[1][s.c0 + a] = hn::IfThenElse(flat, mean[a], hn::Add(mean[a], hn::Mul(s1, v[a])));
    }
  }
  HWY_INLINE void line_ends(const SetV& s, VF e[2][4]) const {
    return by_channels(s.n, [&](auto N) { line_ends_n<N>(s, e); });
  }

  // As ref::quantize_ends; `force_p1` per lane.
  HWY_INLINE void quantize_ends(const SetV& s, const VF e[2][4], EndpointFormat fmt, M force_p1, SetFitV& fit,
                                int combo = -1) const {
    const std::int32_t* table = bc7::kQuantPairs[fmt.bits - 4][fmt.pbit == Pbit::none ? 0 : 1];
    V v[2][4], q0[2][4], q1[2][4];
    V err0[2] = {hn::Zero(d), hn::Zero(d)}, err1[2] = {hn::Zero(d), hn::Zero(d)};
    for (int k = 0; k < 2; ++k)
      for (int a = 0; a < s.n; ++a) {
        v[k][a] = round_clamped(e[k][s.c0 + a], 255.0f);
        const V pair = hn::GatherIndex(d, table, v[k][a]);
        q0[k][a] = hn::And(pair, hn::Set(d, 0xFFFF));
        q1[k][a] = hn::And(hn::ShiftRight<16>(pair), hn::Set(d, 0xFFFF));  // the shift is arithmetic
        const V d0 = hn::Sub(hn::ShiftRight<8>(q0[k][a]), v[k][a]), d1 = hn::Sub(hn::ShiftRight<8>(q1[k][a]), v[k][a]);
        err0[k] = hn::Add(err0[k], hn::Mul(d0, d0));
        err1[k] = hn::Add(err1[k], hn::Mul(d1, d1));
      }
    M p1[2] = {hn::FirstN(d, 0), hn::FirstN(d, 0)};
    if (fmt.pbit != Pbit::none && combo >= 0) {
      const int second = fmt.pbit == Pbit::unique ? combo >> 1 & 1 : combo & 1;
      p1[0] = hn::Or(force_p1, hn::FirstN(d, (combo & 1) ? kBc7Batch : 0));
      p1[1] = hn::Or(force_p1, hn::FirstN(d, second ? kBc7Batch : 0));
    } else if (fmt.pbit == Pbit::unique) {
      for (int k = 0; k < 2; ++k) p1[k] = hn::Or(force_p1, hn::Lt(err1[k], err0[k]));
    } else if (fmt.pbit == Pbit::shared) {
      p1[0] = p1[1] = hn::Or(force_p1, hn::Lt(hn::Add(err1[0], err1[1]), hn::Add(err0[0], err0[1])));
    }
    for (int k = 0; k < 2; ++k) {
      fit.pbit[k] = hn::IfThenElseZero(p1[k], hn::Set(d, 1));
      for (int a = 0; a < s.n; ++a) {
        const V q = hn::IfThenElse(p1[k], q1[k][a], q0[k][a]);
        fit.code[k][s.c0 + a] = hn::And(q, hn::Set(d, 255));
        fit.value[k][s.c0 + a] = hn::ShiftRight<8>(q);
      }
    }
  }

  // As ref::quantize_joint (forced lanes' p-bits 1 in every choice, so
  // their first is kept, as the reference's only one).
  template <int N>  // the channels, 1, 3 or 4
  HWY_NOINLINE void quantize_joint_n(const SetV& s, const VF e[2][4], const VF H[3], EndpointFormat fmt, M force_p1,
                                     SetFitV& fit) const {
    const std::int32_t* table = bc7::kQuantPairs[fmt.bits - 4][fmt.pbit == Pbit::none ? 0 : 1];
    const int top = (1 << fmt.bits) - 1;
    const int combos = fmt.pbit == Pbit::none ? 1 : fmt.pbit == Pbit::unique ? 4 : 2;
    V v[2][4], pair[2][4];
    for (int k = 0; k < 2; ++k)
      for (int a = 0; a < N; ++a) {
        v[k][a] = round_clamped(e[k][s.c0 + a], 255.0f);
        pair[k][a] = hn::GatherIndex(d, table, v[k][a]);
      }
    VF best_total = hn::Set(df, HUGE_VALF);
    for (int combo = 0; combo < combos; ++combo) {
      M p1[2];
      const bool second = fmt.pbit == Pbit::unique ? (combo >> 1 & 1) : (combo & 1);
      p1[0] = hn::Or(force_p1, hn::FirstN(d, (combo & 1) ? kBc7Batch : 0));
      p1[1] = hn::Or(force_p1, hn::FirstN(d, second ? kBc7Batch : 0));
      if (fmt.pbit == Pbit::none) p1[0] = p1[1] = hn::FirstN(d, 0);
      V pbit[2], code[2][4], value[2][4];
      VF total = hn::Zero(df);
      for (int k = 0; k < 2; ++k) pbit[k] = hn::IfThenElseZero(p1[k], hn::Set(d, 1));
      for (int a = 0; a < N; ++a) {
        V cand[2][2], val[2][2];
        for (int k = 0; k < 2; ++k) {
          const V pr = pair[k][a];
          const V q = hn::IfThenElse(p1[k], hn::And(hn::ShiftRight<16>(pr), hn::Set(d, 0xFFFF)),
                                     hn::And(pr, hn::Set(d, 0xFFFF)));
          cand[k][0] = hn::And(q, hn::Set(d, 255));
          val[k][0] = hn::ShiftRight<8>(q);
          const V step = hn::IfThenElse(hn::Lt(val[k][0], v[k][a]), hn::Set(d, 1), hn::Set(d, -1));
          cand[k][1] = hn::Min(hn::Max(hn::Add(cand[k][0], step), hn::Zero(d)), hn::Set(d, top));
          val[k][1] = expand(cand[k][1], pbit[k], fmt);
        }
        VF least = hn::Set(df, HUGE_VALF);
        for (int i = 0; i < 2; ++i)
          for (int j = 0; j < 2; ++j) {
            const VF d0 = hn::Sub(f(val[0][i]), e[0][s.c0 + a]), d1 = hn::Sub(f(val[1][j]), e[1][s.c0 + a]);
            const VF t = hn::Add(hn::Add(hn::Mul(hn::Mul(H[0], d0), d0), hn::Mul(hn::Mul(H[1], d0), d1)),
                                 hn::Mul(hn::Mul(H[2], d1), d1));
            const auto lt = hn::Lt(t, least);
            const M lti = hn::RebindMask(d, lt);
            least = hn::IfThenElse(lt, t, least);
            code[0][a] = i == 0 && j == 0 ? cand[0][0] : hn::IfThenElse(lti, cand[0][i], code[0][a]);
            code[1][a] = i == 0 && j == 0 ? cand[1][0] : hn::IfThenElse(lti, cand[1][j], code[1][a]);
            value[0][a] = i == 0 && j == 0 ? val[0][0] : hn::IfThenElse(lti, val[0][i], value[0][a]);
            value[1][a] = i == 0 && j == 0 ? val[1][0] : hn::IfThenElse(lti, val[1][j], value[1][a]);
          }
        total = hn::Add(total, least);
      }
      const auto better = hn::Lt(total, best_total);
      const M take = hn::RebindMask(d, better);
      best_total = hn::IfThenElse(better, total, best_total);
      for (int k = 0; k < 2; ++k) {
        fit.pbit[k] = hn::IfThenElse(take, pbit[k], fit.pbit[k]);
        for (int a = 0; a < N; ++a) {
          fit.code[k][s.c0 + a] = hn::IfThenElse(take, code[k][a], fit.code[k][s.c0 + a]);
          fit.value[k][s.c0 + a] = hn::IfThenElse(take, value[k][a], fit.value[k][s.c0 + a]);
        }
      }
    }
  }
  HWY_INLINE void quantize_joint(const SetV& s, const VF e[2][4], const VF H[3], EndpointFormat fmt, M force_p1,
                                 SetFitV& fit) const {
    return by_channels(s.n, [&](auto N) { quantize_joint_n<N>(s, e, H, fmt, force_p1, fit); });
  }

  // The weight (out of 64) of index j of 2^bits: the table's, one lane
  // permute where a vector holds the table, else round(64 j / L) as
  // floor((128 j + L) / 2L), which is never a whole number, so the float
  // product floors exactly (tests compare both with the tables).
  HWY_INLINE V weight(V j, int L) const {
    if (L < int(hn::Lanes(d)))
      return hn::TableLookupLanes(weight_table[L == 3 ? 0 : L == 7 ? 1 : 2], hn::IndicesFromVec(d, j));
    const VF num = f(hn::Add(hn::Mul(j, hn::Set(d, 128)), hn::Set(d, L)));
    return hn::ConvertTo(d, hn::Floor(hn::Mul(num, hn::Set(df, 1.0f / float(2 * L)))));
  }
  // The weight in both 16-bit halves.
  HWY_INLINE V weight_pair(V j, int L) const {
    if (L < int(hn::Lanes(d)))
      return hn::TableLookupLanes(weight_pairs[L == 3 ? 0 : L == 7 ? 1 : 2], hn::IndicesFromVec(d, j));
    const V w = weight(j, L);
    return hn::Or(w, hn::ShiftLeft<16>(w));
  }
  // Texel i's squared error at index j: each channel's palette entry
  // (64 - w) e0 + w e1 + 32 >> 6 as e0 + (w (e1 - e0) + 32 >> 6), the same
  // integer (64 e0 is a whole multiple of 64).
  template <int N>
  HWY_INLINE V texel_error(const SetV& s, const SetFitV& fit, const V dv[4], int i, V j, int L) const {
    const V w = weight(j, L);
    V t = hn::Zero(d);
    for (int a = 0; a < N; ++a) {
      const V p = hn::Add(fit.value[0][s.c0 + a], hn::ShiftRight<6>(hn::Add(mul16(w, dv[a]), hn::Set(d, 32))));
      const V e = hn::Sub(p, s.x[i][s.c0 + a]);
      t = hn::Add(t, hn::Mul(e, e));
    }
    return t;
  }

  // texel_error for 3 or 4 channels from channel 0, two channels a lane:
  // the same integers in 16-bit halves (|w (e1 - e0)| <= 64 255, the
  // palette entry and the texel in [0, 255]), the squares' pair sums by
  // dot16. dvp and v0p: (e1 - e0) and e0 in pairs as s.xp's. (D16 is a
  // parameter so that HWY_SCALAR, which has no 16-bit halves and never
  // calls this, does not check the body.)
  template <int N, class D16 = hn::Repartition<std::int16_t, DI>>
  HWY_INLINE V texel_error_pairs(const SetV& s, const V dvp[2], const V v0p[2], int i, V j, int L) const {
    const D16 d16;
    const auto w = hn::BitCast(d16, weight_pair(j, L));
    V t = hn::Zero(d);
    for (int k = 0; k < 2; ++k) {
      const auto p = hn::Add(hn::BitCast(d16, v0p[k]),
                             hn::ShiftRight<6>(hn::Add(hn::Mul(w, hn::BitCast(d16, dvp[k])), hn::Set(d16, 32))));
      const V e = hn::BitCast(d, hn::Sub(p, hn::BitCast(d16, s.xp[i][k == 0 ? 0 : N == 3 ? 1 : 2])));
      t = hn::Add(t, dot16(e, e));
    }
    return t;
  }

  // Texel i's x d.
  template <int N>
  HWY_INLINE V projection(const SetV& s, const V dv[4], int i) const {
    V t = mul16(s.x[i][s.c0], dv[0]);
    for (int a = 1; a < N; ++a) t = hn::Add(t, mul16(s.x[i][s.c0 + a], dv[a]));
    return t;
  }

  // As ref::assign; the projection's sum of (x - e0) d as x d - e0 d.
  HWY_INLINE void assign(const SetV& s, int bits, SetFitV& fit) const { assign(s, bits, level.exact_indices, fit); }
  template <int N>  // the channels, 1, 3 or 4
  HWY_NOINLINE void assign_n(const SetV& s, int bits, bool exact, SetFitV& fit) const {
    const int L = (1 << bits) - 1;
    V dv[4], dd = hn::Zero(d), origin = hn::Zero(d);
    for (int a = 0; a < N; ++a) {
      dv[a] = hn::Sub(fit.value[1][s.c0 + a], fit.value[0][s.c0 + a]);
      dd = hn::Add(dd, hn::Mul(dv[a], dv[a]));
      origin = hn::Add(origin, mul16(fit.value[0][s.c0 + a], dv[a]));
    }
    const auto spread = hn::RebindMask(df, hn::Gt(dd, hn::Zero(d)));
    const VF scale = hn::IfThenElseZero(spread, hn::Div(hn::Set(df, float(L)), f(hn::Max(dd, hn::Set(d, 1)))));
    // Two channels a lane where the target has halves (the set's channels
    // from 0: sets of 3 and 4 always are).
    constexpr bool paired = kChannelPairs && N >= 3;
    V dvp[2], v0p[2];
    if constexpr (paired) {
      const V* v0 = fit.value[0];
      dvp[0] = pair16(dv[0], dv[1]);
      v0p[0] = pair16(v0[0], v0[1]);
      dvp[1] = N == 4 ? pair16(dv[2], dv[3]) : hn::And(dv[2], hn::Set(d, 0xFFFF));
      v0p[1] = N == 4 ? pair16(v0[2], v0[3]) : v0[2];
    }
    auto error_at = [&](int i, V j) {
      if constexpr (paired)
        return texel_error_pairs<N>(s, dvp, v0p, i, j, L);
      else
        return texel_error<N>(s, fit, dv, i, j, L);
    };
    auto project = [&](int i) {
      if constexpr (paired)
        return hn::Add(dot16(s.xp[i][0], dvp[0]), dot16(s.xp[i][N == 3 ? 1 : 2], dvp[1]));
      else
        return projection<N>(s, dv, i);
    };
    fit.error = hn::Zero(d);
    for (int i = 0; i < 16; ++i) {
      const V t = hn::Sub(project(i), origin);
      V j = round_clamped(hn::Mul(f(t), scale), float(L));
      V e = error_at(i, j);
      if (exact) {
        const V j0 = j, lo = hn::Sub(j0, hn::Set(d, 1)), hi = hn::Add(j0, hn::Set(d, 1));
        const V elo = error_at(i, hn::Max(lo, hn::Zero(d)));
        const M take_lo = hn::And(hn::Gt(j0, hn::Zero(d)), hn::Lt(elo, e));
        e = hn::IfThenElse(take_lo, elo, e);
        j = hn::IfThenElse(take_lo, lo, j);
        const V ehi = error_at(i, hn::Min(hi, hn::Set(d, L)));
        const M take_hi = hn::And(hn::Lt(j0, hn::Set(d, L)), hn::Lt(ehi, e));
        e = hn::IfThenElse(take_hi, ehi, e);
        j = hn::IfThenElse(take_hi, hi, j);
      }
      fit.index[i] = hn::IfThenElse(s.member[i], j, fit.index[i]);
      fit.error = hn::Add(fit.error, hn::IfThenElseZero(s.member[i], e));
    }
  }
  HWY_INLINE void assign(const SetV& s, int bits, bool exact, SetFitV& fit) const {
    return by_channels(s.n, [&](auto N) { assign_n<N>(s, bits, exact, fit); });
  }

  // As ref::lsq_ends: the mask of lanes with a determined solution; the
  // weights' sums as floats in H (AA, 2 AB, BB: ref::quantize_joint's).
  template <int N>  // the channels, 1, 3 or 4
  HWY_NOINLINE M lsq_ends_n(const SetV& s, int bits, const SetFitV& fit, VF e[2][4], VF H[3]) const {
    const int L = (1 << bits) - 1;
    // With a = 64 - b on the members, the reference's sums from b's alone
    // and the texels' (the same integers): AA = 4096 n - 128 Sb + BB,
    // AB = 64 Sb - BB, RA = 64 Sx - RB.
    V n = hn::Zero(d), Sb = n, BB = n, Sx[4], RB[4], RA[4];
    for (int c = 0; c < N; ++c) Sx[c] = RB[c] = hn::Zero(d);
    for (int i = 0; i < 16; ++i) {
      const M m = s.member[i];
      const V b = hn::IfThenElseZero(m, weight(fit.index[i], L));
      n = hn::Sub(n, hn::VecFromMask(d, m));  // the mask's lanes are -1
      Sb = hn::Add(Sb, b);
      BB = hn::Add(BB, mul16(b, b));
      for (int c = 0; c < N; ++c) {
        const V x = s.x[i][s.c0 + c];
        Sx[c] = hn::IfThenElse(m, hn::Add(Sx[c], x), Sx[c]);
        RB[c] = hn::Add(RB[c], mul16(b, x));
      }
    }
    const V AA = hn::Add(hn::Sub(hn::ShiftLeft<12>(n), hn::ShiftLeft<7>(Sb)), BB),
            AB = hn::Sub(hn::ShiftLeft<6>(Sb), BB);
    for (int c = 0; c < N; ++c) RA[c] = hn::Sub(hn::ShiftLeft<6>(Sx[c]), RB[c]);
    const VF fAA = f(AA), fAB = f(AB), fBB = f(BB);
    H[0] = fAA;
    H[1] = hn::Mul(hn::Set(df, 2.0f), fAB);
    H[2] = fBB;
    const VF det = hn::Sub(hn::Mul(fAA, fBB), hn::Mul(fAB, fAB));
    const auto ok = hn::Gt(det, hn::Zero(df));
    const VF inv = hn::Div(hn::Set(df, 64.0f), hn::IfThenElse(ok, det, hn::Set(df, 1.0f)));
    for (int c = 0; c < N; ++c) {
      e[0][s.c0 + c] = hn::Mul(hn::Sub(hn::Mul(f(RA[c]), fBB), hn::Mul(f(RB[c]), fAB)), inv);
      e[1][s.c0 + c] = hn::Mul(hn::Sub(hn::Mul(f(RB[c]), fAA), hn::Mul(f(RA[c]), fAB)), inv);
    }
    return hn::RebindMask(d, ok);
  }
  HWY_INLINE M lsq_ends(const SetV& s, int bits, const SetFitV& fit, VF e[2][4], VF H[3]) const {
    return by_channels(s.n, [&](auto N) { return lsq_ends_n<N>(s, bits, fit, e, H); });
  }

  HWY_INLINE void select_fit(M m, const SetFitV& from, SetFitV& to, const SetV& s) const {
    for (int k = 0; k < 2; ++k) {
      to.pbit[k] = hn::IfThenElse(m, from.pbit[k], to.pbit[k]);
      for (int a = s.c0; a < s.c0 + s.n; ++a) {
        to.code[k][a] = hn::IfThenElse(m, from.code[k][a], to.code[k][a]);
        to.value[k][a] = hn::IfThenElse(m, from.value[k][a], to.value[k][a]);
      }
    }
    for (int i = 0; i < 16; ++i) to.index[i] = hn::IfThenElse(m, from.index[i], to.index[i]);
    to.error = hn::IfThenElse(m, from.error, to.error);
  }

  // As ref::quantize_assign (forced lanes' p-bits stay 1 in every choice).
  HWY_INLINE void quantize_assign(const SetV& s, const VF e[2][4], EndpointFormat fmt, int bits, M force_p1,
                                  SetFitV& fit) const {
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

  // As ref::seed_ends.
  HWY_INLINE void seed_ends(const SetV& s, const VF line[2][4], int seed, int L, VF e[2][4]) const {
    const int lo = seed >> 1 & 1, hi = seed & 1, inside = L - lo - hi;
    const VF f0 = hn::Set(df, -float(lo) / float(inside)), f1 = hn::Set(df, float(hi) / float(inside) + 1.0f);
    for (int a = s.c0; a < s.c0 + s.n; ++a) {
      const VF dl = hn::Sub(line[1][a], line[0][a]);
      e[0][a] = seed == 0 ? line[0][a] : hn::Add(line[0][a], hn::Mul(f0, dl));
      e[1][a] = seed == 0 ? line[1][a] : hn::Add(line[0][a], hn::Mul(f1, dl));
    }
  }

  // As ref::fit_seed.
  HWY_INLINE void fit_seed(const SetV& s, const VF line[2][4], int seed, EndpointFormat fmt, int bits, M force_p1,
                           SetFitV& fit) const {
    VF e[2][4];
    seed_ends(s, line, seed, (1 << bits) - 1, e);
    for (auto& j : fit.index) j = hn::Zero(d);
    quantize_assign(s, e, fmt, bits, force_p1, fit);
    M active = hn::Gt(fit.error, hn::Zero(d));
    for (int pass = 0; pass < level.refine && !hn::AllFalse(d, active); ++pass) {
      VF H[3];
      const M ok = lsq_ends(s, bits, fit, e, H);
      SetFitV next = fit;
      if (level.joint) {
        quantize_joint(s, e, H, fmt, force_p1, next);
        assign(s, bits, next);
      } else {
        quantize_assign(s, e, fmt, bits, force_p1, next);
      }
      const M better = hn::And(hn::And(active, ok), hn::Lt(next.error, fit.error));
      select_fit(better, next, fit, s);
      active = hn::And(better, hn::Gt(fit.error, hn::Zero(d)));
    }
  }

  // As ref::fit_set.
  HWY_NOINLINE void fit_set(const SetV& s, EndpointFormat fmt, int bits, M force_p1, SetFitV& best_fit) const {
    VF line[2][4];
    line_ends(s, line);
    for (int seed = 0; seed < std::max(level.seeds, 1); ++seed) {
      if (seed == 0) {
        fit_seed(s, line, seed, fmt, bits, force_p1, best_fit);
      } else {
        SetFitV fit;
        fit_seed(s, line, seed, fmt, bits, force_p1, fit);
        select_fit(hn::Lt(fit.error, best_fit.error), fit, best_fit, s);
      }
      if (hn::AllTrue(d, hn::Eq(best_fit.error, hn::Zero(d)))) break;
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
  HWY_INLINE void step_ends(const SetV& s, EndpointFormat fmt, int bits, bool exact, int rounds, M going,
                            SetFitV& best_fit) const {
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
};

}  // namespace HWY_NAMESPACE
}  // namespace texproc
HWY_AFTER_NAMESPACE();

#endif  // TEXPROC_BC7_FIT_SIMD_INL_H_
