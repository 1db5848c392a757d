// BC6H, a block per lane: the Highway twin of the scalar reference in
// bc6h_lanes.cpp. Both evaluate the same expressions in the same order (see
// bc6h_lanes.h); where the reference stops early for a block (a refinement
// that no longer helps), the lane stops updating, and where it skips a
// candidate (a block of one colour tries mode 13 only), the lane ignores it.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "bc/bc6h_lanes_simd.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include <algorithm>
#include <climits>
#include <cmath>

#include "bc/axis_residual_simd-inl.h"
#include "bc/bc6h_lanes.h"
#include "bc/bc6h_shared.h"
#include "block/block_lanes_simd-inl.h"
#include "texproc/runtime.h"

HWY_BEFORE_NAMESPACE();
namespace texproc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
// Not in an anonymous namespace, as the large lane kernels are not (BC1,
// BC4, BC7: internal linkage changes how GCC 12 inlines their stages, and
// made them 10-26% slower; bench/compare_builds.py). Bc6hBatch is no
// other file's name.

// A candidate: mode, partition, codes and indices per lane (the reference's Choice).
struct CandidateV {
  V partition;
  V code[4][3];
  V index[16];
};

struct Bc6hBatch {
  const DI d;
  const DF df;
  const Bc6hLevel& level;
  const bool is_signed;
  V x[16][3];
  VF y[16][3];
  M solid;
  V best_error, best_mode;
  CandidateV best;

  HWY_ATTR Bc6hBatch(const Bc6hLevel& l, bool s) : level(l), is_signed(s) {}

  HWY_INLINE VF f(V v) const { return hn::ConvertTo(df, v); }
  HWY_INLINE MF fm(M m) const { return hn::RebindMask(df, m); }

  // As ref::fit_value.
  HWY_INLINE VF fit_value(V xv) const {
    if (!is_signed) return hn::Div(f(hn::Add(hn::Add(xv, xv), hn::Set(d, 1))), hn::Set(df, 62.0f));
    const V a = hn::Abs(xv);
    const VF m = hn::Div(f(hn::Add(hn::Add(a, a), hn::Set(d, 1))), hn::Set(df, 124.0f));
    const VF signed_m = hn::IfThenElse(fm(hn::Lt(xv, hn::Zero(d))), hn::Neg(m), m);
    return hn::IfThenElseZero(fm(hn::Ne(xv, hn::Zero(d))), signed_m);
  }

  HWY_INLINE void load(const std::int32_t texel[16][3][kBc6hBatch], int k0) {
    solid = hn::FirstN(d, kBc6hBatch);
    for (int i = 0; i < 16; ++i)
      for (int c = 0; c < 3; ++c) {
        x[i][c] = hn::LoadU(d, texel[i][c] + k0);
        y[i][c] = fit_value(x[i][c]);
        solid = hn::And(solid, hn::Eq(x[i][c], x[0][c]));
      }
    best_error = hn::Set(d, INT_MAX);
    best_mode = hn::Set(d, bc6h::kOneRegion);
    best.partition = hn::Zero(d);
    for (auto& e : best.code)
      for (auto& v : e) v = hn::Zero(d);
    for (auto& v : best.index) v = hn::Zero(d);
  }

  // As ref::line_ends; members a mask per texel, the anchor per lane.
  HWY_INLINE void line_ends(const M member[16], V anchor, VF e[2][3]) const {
    V cnt = hn::Zero(d);
    VF S[3] = {hn::Zero(df), hn::Zero(df), hn::Zero(df)};
    for (int i = 0; i < 16; ++i) {
      cnt = hn::Add(cnt, hn::IfThenElseZero(member[i], hn::Set(d, 1)));
      for (int c = 0; c < 3; ++c) S[c] = hn::Add(S[c], hn::IfThenElseZero(fm(member[i]), y[i][c]));
    }
    VF mean[3], C[3][3];
    for (int c = 0; c < 3; ++c) mean[c] = hn::Div(S[c], f(cnt));
    for (int p = 0; p < 3; ++p)
      for (int q = p; q < 3; ++q) C[p][q] = hn::Zero(df);
    for (int i = 0; i < 16; ++i) {
      VF dv[3];
      for (int c = 0; c < 3; ++c) dv[c] = hn::Sub(y[i][c], mean[c]);
      const MF m = fm(member[i]);
      for (int p = 0; p < 3; ++p)
        for (int q = p; q < 3; ++q) C[p][q] = hn::Add(C[p][q], hn::IfThenElseZero(m, hn::Mul(dv[p], dv[q])));
    }
    for (int p = 0; p < 3; ++p)
      for (int q = 0; q < p; ++q) C[p][q] = C[q][p];
    VF diag = C[0][0], v[3];
    for (int c = 0; c < 3; ++c) v[c] = C[c][0];
    for (int j = 1; j < 3; ++j) {
      const MF gt = hn::Gt(C[j][j], diag);
      diag = hn::IfThenElse(gt, C[j][j], diag);
      for (int c = 0; c < 3; ++c) v[c] = hn::IfThenElse(gt, C[c][j], v[c]);
    }
    const MF flat = hn::Eq(diag, hn::Zero(df));
    for (int it = 0; it < 3; ++it) {
      VF w[3], m = hn::Zero(df);
      for (int p = 0; p < 3; ++p) {
        w[p] = hn::Add(hn::Add(hn::Mul(C[p][0], v[0]), hn::Mul(C[p][1], v[1])), hn::Mul(C[p][2], v[2]));
        m = hn::Max(m, hn::Abs(w[p]));
      }
      const MF moved = hn::Ne(m, hn::Zero(df));
      const VF inv = hn::Div(hn::Set(df, 1.0f), hn::IfThenElse(moved, m, hn::Set(df, 1.0f)));
      for (int p = 0; p < 3; ++p) v[p] = hn::IfThenElse(moved, hn::Mul(w[p], inv), v[p]);
    }
    VF tmin = hn::Set(df, HUGE_VALF), tmax = hn::Set(df, -HUGE_VALF), ta = hn::Zero(df);
    for (int i = 0; i < 16; ++i) {
      const VF t = hn::Add(hn::Add(hn::Mul(v[0], hn::Sub(y[i][0], mean[0])), hn::Mul(v[1], hn::Sub(y[i][1], mean[1]))),
                           hn::Mul(v[2], hn::Sub(y[i][2], mean[2])));
      const MF m = fm(member[i]);
      tmin = hn::IfThenElse(m, hn::Min(tmin, t), tmin);
      tmax = hn::IfThenElse(m, hn::Max(tmax, t), tmax);
      ta = hn::IfThenElse(fm(hn::Eq(anchor, hn::Set(d, i))), t, ta);
    }
    const VF vv = hn::Add(hn::Add(hn::Mul(v[0], v[0]), hn::Mul(v[1], v[1])), hn::Mul(v[2], v[2]));
    const VF safe_vv = hn::IfThenElse(flat, hn::Set(df, 1.0f), vv);
    VF s0 = hn::Div(tmin, safe_vv), s1 = hn::Div(tmax, safe_vv);
    const MF swap = hn::Gt(hn::Add(ta, ta), hn::Add(tmin, tmax));
    const VF t0 = hn::IfThenElse(swap, s1, s0);
    s1 = hn::IfThenElse(swap, s0, s1);
    s0 = t0;
    for (int c = 0; c < 3; ++c) {
      e[0][c] = hn::IfThenElse(flat, mean[c], hn::Add(mean[c], hn::Mul(s0, v[c])));
      e[1][c] = hn::IfThenElse(flat, mean[c], hn::Add(mean[c], hn::Mul(s1, v[c])));
    }
  }

  // As ref::lsq_ends: the mask of lanes with a determined solution (e
  // written there only).
  HWY_INLINE M lsq_ends(const M member[16], const V index[16], int bits, VF e[2][3]) const {
    const int L = (1 << bits) - 1;
    const std::uint8_t* w = bptc::weights(bits);
    V AA = hn::Zero(d), AB = AA, BB = AA;
    VF RA[3], RB[3];
    for (int c = 0; c < 3; ++c) RA[c] = RB[c] = hn::Zero(df);
    for (int i = 0; i < 16; ++i) {
      // The weight of the lane's index: a select chain over the table.
      V wb = hn::Zero(d);
      for (int j = 1; j <= L; ++j) wb = hn::IfThenElse(hn::Eq(index[i], hn::Set(d, j)), hn::Set(d, w[j]), wb);
      wb = hn::IfThenElseZero(member[i], wb);
      const V wa = hn::IfThenElseZero(member[i], hn::Sub(hn::Set(d, 64), wb));
      AA = hn::Add(AA, hn::Mul(wa, wa));
      AB = hn::Add(AB, hn::Mul(wa, wb));
      BB = hn::Add(BB, hn::Mul(wb, wb));
      const VF fa = f(wa), fb = f(wb);
      const MF m = fm(member[i]);
      for (int c = 0; c < 3; ++c) {
        RA[c] = hn::Add(RA[c], hn::IfThenElseZero(m, hn::Mul(fa, y[i][c])));
        RB[c] = hn::Add(RB[c], hn::IfThenElseZero(m, hn::Mul(fb, y[i][c])));
      }
    }
    const VF fAA = f(AA), fAB = f(AB), fBB = f(BB);
    const VF det = hn::Sub(hn::Mul(fAA, fBB), hn::Mul(fAB, fAB));
    const MF ok = hn::Gt(det, hn::Zero(df));
    const VF inv = hn::Div(hn::Set(df, 64.0f), hn::IfThenElse(ok, det, hn::Set(df, 1.0f)));
    for (int c = 0; c < 3; ++c) {
      e[0][c] = hn::IfThenElse(ok, hn::Mul(hn::Sub(hn::Mul(RA[c], fBB), hn::Mul(RB[c], fAB)), inv), e[0][c]);
      e[1][c] = hn::IfThenElse(ok, hn::Mul(hn::Sub(hn::Mul(RB[c], fAA), hn::Mul(RA[c], fAB)), inv), e[1][c]);
    }
    return hn::RebindMask(d, ok);
  }

  // As bc6h::unquantize.
  HWY_INLINE V unquantize(V q, int bits) const {
    if (!is_signed) {
      if (bits >= 15) return q;
      const V r = hn::ShiftRightSame(hn::Add(hn::ShiftLeft<15>(q), hn::Set(d, 0x4000)), bits - 1);
      const V lo = hn::IfThenZeroElse(hn::Eq(q, hn::Zero(d)), r);
      return hn::IfThenElse(hn::Eq(q, hn::Set(d, (1 << bits) - 1)), hn::Set(d, 0xFFFF), lo);
    }
    if (bits >= 16) return q;
    const V a = hn::Abs(q);
    V r = hn::ShiftRightSame(hn::Add(hn::ShiftLeft<15>(a), hn::Set(d, 0x4000)), bits - 1);
    r = hn::IfThenZeroElse(hn::Eq(a, hn::Zero(d)), r);
    r = hn::IfThenElse(hn::Gt(a, hn::Set(d, (1 << (bits - 1)) - 2)), hn::Set(d, 0x7FFF), r);
    return hn::IfThenElse(hn::Lt(q, hn::Zero(d)), hn::Neg(r), r);
  }

  // As bc6h::finish.
  HWY_INLINE V finish(V v) const {
    if (!is_signed) return hn::ShiftRight<6>(hn::Mul(v, hn::Set(d, 31)));
    const V r = hn::ShiftRight<5>(hn::Mul(hn::Abs(v), hn::Set(d, 31)));
    return hn::IfThenElse(hn::Lt(v, hn::Zero(d)), hn::Neg(r), r);
  }

  // As bc6h::quantize, of e * 64.
  HWY_INLINE V quantize(VF e, int bits) const {
    const VF u = hn::Mul(e, hn::Set(df, 64.0f));
    const int top = is_signed ? (1 << (bits - 1)) - 1 : (1 << bits) - 1;
    const VF m = is_signed ? hn::Abs(u) : u;
    const VF c = hn::Min(hn::Max(m, hn::Zero(df)), hn::Set(df, is_signed ? 32767.0f : 65535.0f));
    const VF scale = hn::Set(df, float(1 << (bits - 1)) * (1.0f / 32768.0f));
    V q = hn::ConvertTo(d, hn::Floor(hn::Mul(c, scale)));
    q = hn::Min(hn::Max(q, hn::Zero(d)), hn::Set(d, top));
    auto dist = [&](V code) { return hn::Abs(hn::Sub(f(unquantize(code, bits)), c)); };
    V pick = q;
    VF bd = dist(q);
    const V lo = hn::Sub(q, hn::Set(d, 1)), hi = hn::Add(q, hn::Set(d, 1));
    const VF dlo = dist(hn::Max(lo, hn::Zero(d)));
    const MF take_lo = hn::And(fm(hn::Gt(q, hn::Zero(d))), hn::Lt(dlo, bd));
    pick = hn::IfThenElse(hn::RebindMask(d, take_lo), lo, pick);
    bd = hn::IfThenElse(take_lo, dlo, bd);
    const VF dhi = dist(hn::Min(hi, hn::Set(d, top)));
    const MF take_hi = hn::And(fm(hn::Lt(q, hn::Set(d, top))), hn::Lt(dhi, bd));
    pick = hn::IfThenElse(hn::RebindMask(d, take_hi), hi, pick);
    if (!is_signed) return pick;
    return hn::IfThenElse(hn::RebindMask(d, hn::Lt(u, hn::Zero(df))), hn::Neg(pick), pick);
  }

  // As bc6h::limit_delta.
  HWY_INLINE V limit_delta(V q0, V qj, int endpoint_bits, int delta_bits) const {
    const V lo = hn::Set(d, -(1 << (delta_bits - 1))), hi = hn::Set(d, (1 << (delta_bits - 1)) - 1);
    const V diff = hn::Sub(qj, q0);
    const V half = hn::Set(d, 1 << (endpoint_bits - 1));
    const V wrapped = hn::Sub(hn::And(hn::Add(diff, half), hn::Set(d, (1 << endpoint_bits) - 1)), half);
    const M fits = hn::AndNot(hn::Or(hn::Lt(wrapped, lo), hn::Gt(wrapped, hi)), hn::FirstN(d, kBc6hBatch));
    return hn::IfThenElse(fits, qj, hn::Add(q0, hn::Min(hn::Max(diff, lo), hi)));
  }

  // As ref::quantize_ends.
  HWY_INLINE void quantize_ends(int k, const VF e[4][3], V code[4][3]) const {
    const bptc::Bc6hMode& Md = bptc::kBc6hModes[k];
    const int n = 2 * bc6h::regions(k);
    for (int j = 0; j < n; ++j)
      for (int c = 0; c < 3; ++c) code[j][c] = quantize(e[j][c], Md.endpoint_bits);
    if (Md.transformed)
      for (int j = 1; j < n; ++j)
        for (int c = 0; c < 3; ++c)
          code[j][c] = limit_delta(code[0][c], code[j][c], Md.endpoint_bits, Md.delta_bits[c]);
  }

  // As ref::assign; region1[i]: texel i is in region 1 (two regions).
  HWY_INLINE V assign(int k, const M region1[16], V anchor1, const V code[4][3], V index[16]) const {
    const bptc::Bc6hMode& Md = bptc::kBc6hModes[k];
    const int ns = bc6h::regions(k), bits = bc6h::index_bits(k), L = (1 << bits) - 1;
    const std::uint8_t* w = bptc::weights(bits);
    V pal[2][16][3];
    for (int s = 0; s < ns; ++s)
      for (int c = 0; c < 3; ++c) {
        const V u0 = unquantize(code[2 * s][c], Md.endpoint_bits),
                u1 = unquantize(code[2 * s + 1][c], Md.endpoint_bits);
        for (int j = 0; j <= L; ++j) {
          const V p =
              hn::Add(hn::Add(hn::Mul(hn::Set(d, 64 - w[j]), u0), hn::Mul(hn::Set(d, w[j]), u1)), hn::Set(d, 32));
          pal[s][j][c] = finish(hn::ShiftRight<6>(p));
        }
      }
    const V limit = hn::Set(d, bc6h::kErrorLimit);
    V error = hn::Zero(d);
    for (int i = 0; i < 16; ++i) {
      const M in1 = ns == 2 ? region1[i] : hn::FirstN(d, 0);
      const M anchor = i == 0 ? hn::FirstN(d, kBc6hBatch) : ns == 2 ? hn::Eq(anchor1, hn::Set(d, i)) : hn::FirstN(d, 0);
      const V top = hn::IfThenElse(anchor, hn::Set(d, L >> 1), hn::Set(d, L));
      V pick = hn::Zero(d), be = hn::Zero(d);
      for (int j = 0; j <= L; ++j) {
        V e = hn::Zero(d);
        for (int c = 0; c < 3; ++c) {
          const V p = ns == 2 ? hn::IfThenElse(in1, pal[1][j][c], pal[0][j][c]) : pal[0][j][c];
          const V dd = hn::Min(hn::Abs(hn::Sub(p, x[i][c])), limit);
          e = hn::Add(e, hn::Mul(dd, dd));
        }
        if (j == 0) {
          be = e;
          continue;
        }
        const M take = hn::AndNot(hn::Gt(hn::Set(d, j), top), hn::Lt(e, be));
        be = hn::IfThenElse(take, e, be);
        pick = hn::IfThenElse(take, hn::Set(d, j), pick);
      }
      index[i] = pick;
      error = hn::Add(error, be);
    }
    return error;
  }

  // As ref::try_mode; `allowed`: the lanes that try it.
  HWY_INLINE void try_mode(int k, V partition, const M region1[16], V anchor1, const VF ends[4][3], M allowed) {
    const int ns = bc6h::regions(k), bits = bc6h::index_bits(k);
    M member[2][16];
    for (int i = 0; i < 16; ++i) {
      member[0][i] = ns == 2 ? hn::Not(region1[i]) : hn::FirstN(d, kBc6hBatch);
      member[1][i] = ns == 2 ? region1[i] : hn::FirstN(d, 0);
    }
    CandidateV c;
    c.partition = ns == 2 ? partition : hn::Zero(d);
    for (auto& e : c.code)
      for (auto& v : e) v = hn::Zero(d);
    quantize_ends(k, ends, c.code);
    V error = assign(k, region1, anchor1, c.code, c.index);
    VF cur[4][3];
    for (int j = 0; j < 4; ++j)
      for (int ch = 0; ch < 3; ++ch) cur[j][ch] = ends[j][ch];
    M active = hn::And(allowed, hn::Gt(error, hn::Zero(d)));
    for (int pass = 0; pass < level.refine && !hn::AllFalse(d, active); ++pass) {
      VF next[4][3];
      for (int j = 0; j < 4; ++j)
        for (int ch = 0; ch < 3; ++ch) next[j][ch] = cur[j][ch];
      M any = hn::FirstN(d, 0);
      for (int s = 0; s < ns; ++s) any = hn::Or(lsq_ends(member[s], c.index, bits, &next[2 * s]), any);
      CandidateV n = c;
      quantize_ends(k, next, n.code);
      const V e = assign(k, region1, anchor1, n.code, n.index);
      const M better = hn::And(hn::And(active, any), hn::Lt(e, error));
      error = hn::IfThenElse(better, e, error);
      for (int j = 0; j < 4; ++j)
        for (int ch = 0; ch < 3; ++ch) {
          c.code[j][ch] = hn::IfThenElse(better, n.code[j][ch], c.code[j][ch]);
          cur[j][ch] = hn::IfThenElse(hn::RebindMask(df, better), next[j][ch], cur[j][ch]);
        }
      for (int i = 0; i < 16; ++i) c.index[i] = hn::IfThenElse(better, n.index[i], c.index[i]);
      active = hn::And(better, hn::Gt(error, hn::Zero(d)));
    }
    const M take = hn::And(allowed, hn::Lt(error, best_error));
    if (hn::AllFalse(d, take)) return;
    best_error = hn::IfThenElse(take, error, best_error);
    best_mode = hn::IfThenElse(take, hn::Set(d, k), best_mode);
    best.partition = hn::IfThenElse(take, c.partition, best.partition);
    for (int j = 0; j < 4; ++j)
      for (int ch = 0; ch < 3; ++ch) best.code[j][ch] = hn::IfThenElse(take, c.code[j][ch], best.code[j][ch]);
    for (int i = 0; i < 16; ++i) best.index[i] = hn::IfThenElse(take, c.index[i], best.index[i]);
  }

  // As ref::region_residual; the members the same in every lane.
  HWY_INLINE VF region_residual(unsigned members) const {
    int cnt = 0;
    VF S[3] = {hn::Zero(df), hn::Zero(df), hn::Zero(df)};
    for (int i = 0; i < 16; ++i) {
      if (!(members >> i & 1)) continue;
      ++cnt;
      for (int c = 0; c < 3; ++c) S[c] = hn::Add(S[c], y[i][c]);
    }
    VF mean[3];
    for (int c = 0; c < 3; ++c) mean[c] = hn::Div(S[c], hn::Set(df, float(cnt)));
    VF c00 = hn::Zero(df), c01 = c00, c02 = c00, c11 = c00, c12 = c00, c22 = c00;
    for (int i = 0; i < 16; ++i) {
      if (!(members >> i & 1)) continue;
      const VF d0 = hn::Sub(y[i][0], mean[0]), d1 = hn::Sub(y[i][1], mean[1]), d2 = hn::Sub(y[i][2], mean[2]);
      c00 = hn::Add(c00, hn::Mul(d0, d0));
      c01 = hn::Add(c01, hn::Mul(d0, d1));
      c02 = hn::Add(c02, hn::Mul(d0, d2));
      c11 = hn::Add(c11, hn::Mul(d1, d1));
      c12 = hn::Add(c12, hn::Mul(d1, d2));
      c22 = hn::Add(c22, hn::Mul(d2, d2));
    }
    return axis_residual(df, c00, c01, c02, c11, c12, c22);
  }

  static unsigned region_members(int partition, int s) {
    unsigned m = 0;
    for (int i = 0; i < 16; ++i) m |= unsigned(bptc::subset(bptc::kPartitions2[partition], i) == s) << i;
    return m;
  }

  // As ref::encode_block, the lanes together.
  HWY_INLINE void search() {
    const M all = hn::FirstN(d, kBc6hBatch), none = hn::FirstN(d, 0);
    const M varied = hn::Not(solid);
    M no_regions[16], every[16];
    for (int i = 0; i < 16; ++i) {
      no_regions[i] = none;
      every[i] = all;
    }
    // The one-region modes: those of the level for varied lanes, and mode
    // 13 for lanes of one colour.
    M allowed[14];
    bool any_one = false;
    for (int k = bc6h::kOneRegion; k < 14; ++k) {
      allowed[k] = hn::Or(level.modes >> k & 1 ? varied : none, k == 13 ? solid : none);
      any_one = any_one || !hn::AllFalse(d, allowed[k]);
    }
    if (any_one) {
      VF e[4][3];
      for (auto& end : e)
        for (auto& v : end) v = hn::Zero(df);
      line_ends(every, hn::Zero(d), e);
      for (int k = bc6h::kOneRegion; k < 14; ++k)
        if (!hn::AllFalse(d, allowed[k])) try_mode(k, hn::Zero(d), no_regions, hn::Zero(d), e, allowed[k]);
    }
    if (!(level.modes & ((1u << bc6h::kOneRegion) - 1)) || level.partitions <= 0 || hn::AllFalse(d, varied)) return;
    const int keep = std::min(level.partitions, 32);
    VF est[32];
    V ranked[32];
    for (int j = 0; j < keep; ++j) {
      est[j] = hn::Set(df, HUGE_VALF);
      ranked[j] = hn::Zero(d);
    }
    for (int p = 0; p < 32; ++p) {
      VF e = hn::Add(region_residual(region_members(p, 0)), region_residual(region_members(p, 1)));
      V q = hn::Set(d, p);
      for (int j = 0; j < keep; ++j) {
        const MF lt = hn::Lt(e, est[j]);
        const VF ne = hn::IfThenElse(lt, est[j], e);
        est[j] = hn::IfThenElse(lt, e, est[j]);
        e = ne;
        const M lti = hn::RebindMask(d, lt);
        const V nq = hn::IfThenElse(lti, ranked[j], q);
        ranked[j] = hn::IfThenElse(lti, q, ranked[j]);
        q = nq;
      }
    }
    const std::int32_t* parts = reinterpret_cast<const std::int32_t*>(bptc::kPartitions2);
    alignas(64) std::int32_t anchors[64];
    for (int p = 0; p < 64; ++p) anchors[p] = bptc::kAnchor2[p];
    for (int r = 0; r < keep; ++r) {
      const V p = ranked[r];
      const V bits = hn::GatherIndex(d, parts, p);
      const V anchor1 = hn::GatherIndex(d, anchors, p);
      M region1[16], region0[16];
      for (int i = 0; i < 16; ++i) {
        region1[i] = hn::Eq(hn::And(hn::ShiftRightSame(bits, 2 * i), hn::Set(d, 3)), hn::Set(d, 1));
        region0[i] = hn::Not(region1[i]);
      }
      VF e[4][3];
      line_ends(region0, hn::Zero(d), e);
      line_ends(region1, anchor1, e + 2);
      for (int k = 0; k < bc6h::kOneRegion; ++k)
        if (level.modes >> k & 1) try_mode(k, p, region1, anchor1, e, varied);
    }
  }

  // Lane k's choice, packed: every field stored once, then read per lane.
  HWY_INLINE void store(int k0, int count, std::uint8_t out[][16]) const {
    constexpr int N = kBc6hBatch;
    struct Fields {
      std::int32_t mode[N], partition[N], code[4][3][N], index[16][N];
    } t;
    hn::StoreU(best_mode, d, t.mode);
    hn::StoreU(best.partition, d, t.partition);
    for (int j = 0; j < 4; ++j)
      for (int c = 0; c < 3; ++c) hn::StoreU(best.code[j][c], d, t.code[j][c]);
    for (int i = 0; i < 16; ++i) hn::StoreU(best.index[i], d, t.index[i]);
    const int lanes = std::min(int(hn::Lanes(d)), count - k0);
    for (int k = 0; k < lanes; ++k) {
      bc6h::Choice c;
      c.mode = t.mode[k];
      c.partition = t.partition[k];
      for (int j = 0; j < 4; ++j)
        for (int ch = 0; ch < 3; ++ch) c.code[j][ch] = t.code[j][ch][k];
      for (int i = 0; i < 16; ++i) c.index[i] = std::uint8_t(t.index[i][k]);
      bc6h::pack_block(c, out[k0 + k]);
    }
  }
};

void Bc6hEncodeLanes(const std::int32_t texel[16][3][kBc6hBatch], int count, bool is_signed, const Bc6hLevel& level,
                     std::uint8_t out[][16]) {
  Bc6hBatch batch(level, is_signed);
  const int step = int(hn::Lanes(batch.d));
  for (int k0 = 0; k0 < count; k0 += step) {
    batch.load(texel, k0);
    batch.search();
    batch.store(k0, count, out);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace texproc
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace texproc {
HWY_EXPORT(Bc6hEncodeLanes);

void bc6h_encode_lanes(const std::int32_t texel[16][3][kBc6hBatch], int count, bool is_signed, const Bc6hLevel& level,
                       std::uint8_t out[][16]) {
  if (force_scalar()) return ref::bc6h_encode_lanes(texel, count, is_signed, level, out);
  HWY_DYNAMIC_DISPATCH(Bc6hEncodeLanes)(texel, count, is_signed, level, out);
}
}  // namespace texproc
#endif
