// BC4 `fast`, `normal` and `high`, a block per lane: the scalar reference
// (one block at a time, plainly) and its Highway twin. Both evaluate the same expressions in the
// same order; see bc4_lanes.h.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "bc/bc4_lanes_simd.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include <algorithm>
#include <cmath>

#include "bc/bc4_lanes.h"
#include "texproc/runtime.h"

#ifndef TEXPROC_BC4_LANES_REF
#define TEXPROC_BC4_LANES_REF
namespace texproc::ref {
namespace {

// Codes and squared error of endpoints r0, r1 (r0 > r1: eight values, by
// rounding the position from r0; else six values by rounding from r0, or
// the code range's ends where nearer).
float evaluate(const float t[16], int r0, int r1, float lo_code, float hi_code, int codes[16]) {
  float error = 0.0f;
  const float f0 = float(r0), f1 = float(r1);
  for (int i = 0; i < 16; ++i) {
    if (r0 > r1) {
      const int j = std::clamp(int((f0 - t[i]) * 7.0f / (f0 - f1) + 0.5f), 0, 7);
      const float d = t[i] - (f0 * float(7 - j) + f1 * float(j)) / 7.0f;
      error += d * d;
      codes[i] = j == 0 ? 0 : j == 7 ? 1 : j + 1;
    } else {
      const int j = r1 > r0 ? std::clamp(int((t[i] - f0) * 5.0f / (f1 - f0) + 0.5f), 0, 5) : 0;
      const float d = t[i] - (f0 * float(5 - j) + f1 * float(j)) / 5.0f;
      const float dl = t[i] - lo_code, dh = t[i] - hi_code;
      float best = d * d;
      int code = j == 0 ? 0 : j == 5 ? 1 : j + 1;
      if (dl * dl < best) best = dl * dl, code = 6;
      if (dh * dh < best) best = dh * dh, code = 7;
      error += best;
      codes[i] = code;
    }
  }
  return error;
}

// `high`'s partition variants: the values placed on the mode's grid
// between its starting endpoints, the grid shifted by `offset` steps of
// 0.15 and stretched by `stretch` steps of 10% about its middle, then a
// least-squares fit for those positions.
constexpr int kVariantOffsets = 4, kVariantStretches = 2;
inline float variant_stretch(int stretch) { return 1.0f + 0.1f * float(stretch); }
inline float variant_shift(int offset, int stretch, int steps) {
  return 0.5f + 0.15f * float(offset) - 0.1f * float(stretch) * float(steps) * 0.5f;
}

// Least-squares endpoints for the sums of a position set (u = steps - pos
// and pos weigh the two endpoints), rounded and clamped to [lo, hi]; the
// six-value mode's (mode 1) in ascending order. False where there is no
// solution, or where the eight-value mode's (mode 0) fit left that mode.
inline bool ls_endpoints(int aa, int ab, int bb, float at, float bt, int steps, int mode, int lo, int hi, int& ia, int& ib) {
  const int det = aa * bb - ab * ab;
  if (det == 0) return false;
  const float fa = float(steps) * (at * float(bb) - bt * float(ab)) / float(det);
  const float fb = float(steps) * (bt * float(aa) - at * float(ab)) / float(det);
  ia = std::clamp(int(std::floor(fa + 0.5f)), lo, hi), ib = std::clamp(int(std::floor(fb + 0.5f)), lo, hi);
  if (mode == 1 && ia > ib) std::swap(ia, ib);
  return mode == 1 || ia > ib;
}

}  // namespace

void bc4_encode_lanes(const float v[16][kBc4Batch], int count, bool snorm, int level, std::uint8_t out[][8]) {
  const float lo_code = snorm ? -127.0f : 0.0f, hi_code = snorm ? 127.0f : 255.0f;
  const int lo_int = int(lo_code), hi_int = int(hi_code);
  for (int k = 0; k < count; ++k) {
    float t[16], mn = hi_code, mx = lo_code, mn6 = hi_code, mx6 = lo_code;
    for (int i = 0; i < 16; ++i) {
      t[i] = std::min(std::max(v[i][k], lo_code), hi_code);
      mn = std::min(mn, t[i]), mx = std::max(mx, t[i]);
      if (t[i] > lo_code + 0.5f && t[i] < hi_code - 0.5f) mn6 = std::min(mn6, t[i]), mx6 = std::max(mx6, t[i]);
    }
    const int lo = int(std::floor(mn)), hi = int(std::ceil(mx));
    int r0 = hi > lo ? hi : lo, r1 = lo, codes[16];
    float error = evaluate(t, r0, r1, lo_code, hi_code, codes);
    if (mn6 <= mx6) {
      const int lo6 = int(std::floor(mn6)), hi6 = int(std::ceil(mx6));
      if (lo6 != lo || hi6 != hi) {
        int codes6[16];
        const float error6 = evaluate(t, lo6, hi6, lo_code, hi_code, codes6);
        if (error6 < error) {
          error = error6, r0 = lo6, r1 = hi6;
          std::copy(codes6, codes6 + 16, codes);
        }
      }
    }
    if (level >= 1 && error > 0.0f) {
      const int window = level >= 2 ? 2 : 1;
      const bool inner = mn6 <= mx6;
      const int lo6 = inner ? int(std::floor(mn6)) : lo, hi6 = inner ? int(std::ceil(mx6)) : hi;
      for (int mode = 0; mode < 2; ++mode) {  // 0: eight values, 1: six
        if (mode == 0 && hi <= lo) continue;
        int m0 = mode == 0 ? hi : lo6, m1 = mode == 0 ? lo : std::max(lo6, hi6), mc[16];
        float me = evaluate(t, m0, m1, lo_code, hi_code, mc);
        for (int iter = 0; iter < 2; ++iter) {
          // Least-squares endpoints for these codes (positions in steps of
          // 1/7 or 1/5 from r0; the six-value mode's fixed ends left out).
          const bool eight = m0 > m1;
          const int steps = eight ? 7 : 5;
          int aa = 0, ab = 0, bb = 0;
          float at = 0.0f, bt = 0.0f;
          for (int i = 0; i < 16; ++i) {
            const int code = mc[i];
            if (!eight && code >= 6) continue;
            const int pos = code == 0 ? 0 : code == 1 ? steps : code - 1, u = steps - pos;
            aa += u * u, ab += u * pos, bb += pos * pos;
            at += float(u) * t[i], bt += float(pos) * t[i];
          }
          int ia, ib;
          if (!ls_endpoints(aa, ab, bb, at, bt, steps, mode, lo_int, hi_int, ia, ib)) break;
          int cc[16];
          const float ce = evaluate(t, ia, ib, lo_code, hi_code, cc);
          if (ce >= me) break;
          m0 = ia, m1 = ib, me = ce;
          std::copy(cc, cc + 16, mc);
        }
        if (me < error) {
          error = me, r0 = m0, r1 = m1;
          std::copy(mc, mc + 16, codes);
        }
        // The window around the refined endpoints (+-1, `high` +-2), in the
        // same mode.
        auto window_at = [&](int c0, int c1, int w) {
          for (int a = c0 - w; a <= c0 + w; ++a)
            for (int b = c1 - w; b <= c1 + w; ++b) {
              if ((mode == 0) != (a > b) || a < lo_int || a > hi_int || b < lo_int || b > hi_int) continue;
              int cc[16];
              const float ce = evaluate(t, a, b, lo_code, hi_code, cc);
              if (ce < error) {
                error = ce, r0 = a, r1 = b;
                std::copy(cc, cc + 16, codes);
              }
            }
        };
        window_at(m0, m1, window);
        if (level < 2) continue;
        // `high`: partition variants from the starting endpoints.
        const int steps = mode == 0 ? 7 : 5;
        const float a0 = float(mode == 0 ? hi : lo6), a1 = float(mode == 0 ? lo : hi6);
        if (a0 == a1) continue;
        for (int o = -kVariantOffsets; o <= kVariantOffsets; ++o)
          for (int sv = -kVariantStretches; sv <= kVariantStretches; ++sv) {
            const float stretch = variant_stretch(sv), shift = variant_shift(o, sv, steps);
            int aa = 0, ab = 0, bb = 0;
            float at = 0.0f, bt = 0.0f;
            for (int i = 0; i < 16; ++i) {
              if (mode == 1 && (t[i] <= lo_code + 0.5f || t[i] >= hi_code - 0.5f)) continue;  // the free ends
              const int pos = std::clamp(int(std::floor((a0 - t[i]) / (a0 - a1) * float(steps) * stretch + shift)), 0, steps);
              const int u = steps - pos;
              aa += u * u, ab += u * pos, bb += pos * pos;
              at += float(u) * t[i], bt += float(pos) * t[i];
            }
            int ia, ib;
            if (ls_endpoints(aa, ab, bb, at, bt, steps, mode, lo_int, hi_int, ia, ib)) window_at(ia, ib, 0);
          }
      }
    }
    out[k][0] = std::uint8_t(r0 & 255), out[k][1] = std::uint8_t(r1 & 255);  // SNORM: two's complement
    std::uint64_t bits = 0;
    for (int i = 0; i < 16; ++i) bits |= std::uint64_t(codes[i]) << (3 * i);
    for (int b = 0; b < 6; ++b) out[k][2 + b] = std::uint8_t(bits >> (8 * b));
  }
}

}  // namespace texproc::ref
#endif

HWY_BEFORE_NAMESPACE();
namespace texproc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void Bc4EncodeLanes(const float v[16][kBc4Batch], int count, bool snorm, int level, std::uint8_t out[][8]) {
  using D = hn::CappedTag<float, kBc4Batch>;
  const D df;
  const hn::RebindToSigned<D> d;
  using VF = hn::Vec<D>;
  using V = hn::Vec<decltype(d)>;
  const int lanes = int(hn::Lanes(df));
  const VF lo_code = hn::Set(df, snorm ? -127.0f : 0.0f), hi_code = hn::Set(df, snorm ? 127.0f : 255.0f);
  const VF half = hn::Set(df, 0.5f);
  for (int k0 = 0; k0 < count; k0 += lanes) {
    VF t[16];
    VF mn = hi_code, mx = lo_code, mn6 = hi_code, mx6 = lo_code;
    const VF inner_lo = hn::Add(lo_code, half), inner_hi = hn::Sub(hi_code, half);
    for (int i = 0; i < 16; ++i) {
      t[i] = hn::Min(hn::Max(hn::LoadU(df, v[i] + k0), lo_code), hi_code);
      mn = hn::Min(mn, t[i]), mx = hn::Max(mx, t[i]);
      const auto inner = hn::And(hn::Gt(t[i], inner_lo), hn::Lt(t[i], inner_hi));
      mn6 = hn::IfThenElse(inner, hn::Min(mn6, t[i]), mn6), mx6 = hn::IfThenElse(inner, hn::Max(mx6, t[i]), mx6);
    }
    const V lo = hn::ConvertTo(d, hn::Floor(mn)), hi = hn::ConvertTo(d, hn::Ceil(mx));
    // kind 8: every lane in the eight-value mode (r0 > r1), 6: every lane in
    // the six-value mode, 0: either, by lane.
    auto evaluate = [&](V r0, V r1, V codes[16], int kind = 0) {
      const VF f0 = hn::ConvertTo(df, r0), f1 = hn::ConvertTo(df, r1);
      const auto eight = hn::Gt(r0, r1);
      const auto eight_f = hn::RebindMask(df, eight);
      const auto wide6 = hn::RebindMask(df, hn::Gt(r1, r0));
      const VF one = hn::Set(df, 1.0f);
      const VF span8 = hn::IfThenElse(eight_f, hn::Sub(f0, f1), one), span6 = hn::IfThenElse(wide6, hn::Sub(f1, f0), one);
      VF error = hn::Zero(df);
      for (int i = 0; i < 16; ++i) {
        VF e8 = hn::Zero(df), e6 = hn::Zero(df);
        V c8 = hn::Zero(d), c6 = hn::Zero(d);
        if (kind != 6) {  // eight values
          const V j8 = hn::Min(hn::Max(hn::ConvertTo(d, hn::Add(hn::Div(hn::Mul(hn::Sub(f0, t[i]), hn::Set(df, 7.0f)), span8), half)),
                                       hn::Zero(d)), hn::Set(d, 7));
          const VF fj8 = hn::ConvertTo(df, j8);
          const VF d8 = hn::Sub(t[i], hn::Div(hn::Add(hn::Mul(f0, hn::Sub(hn::Set(df, 7.0f), fj8)), hn::Mul(f1, fj8)), hn::Set(df, 7.0f)));
          e8 = hn::Mul(d8, d8);
          c8 = hn::IfThenElse(hn::Eq(j8, hn::Zero(d)), hn::Zero(d),
                              hn::IfThenElse(hn::Eq(j8, hn::Set(d, 7)), hn::Set(d, 1), hn::Add(j8, hn::Set(d, 1))));
        }
        if (kind != 8) {  // six values and the range's ends
          const V j6 = hn::IfThenElseZero(
              hn::RebindMask(d, wide6),
              hn::Min(hn::Max(hn::ConvertTo(d, hn::Add(hn::Div(hn::Mul(hn::Sub(t[i], f0), hn::Set(df, 5.0f)), span6), half)),
                              hn::Zero(d)), hn::Set(d, 5)));
          const VF fj6 = hn::ConvertTo(df, j6);
          const VF d6 = hn::Sub(t[i], hn::Div(hn::Add(hn::Mul(f0, hn::Sub(hn::Set(df, 5.0f), fj6)), hn::Mul(f1, fj6)), hn::Set(df, 5.0f)));
          const VF dl = hn::Sub(t[i], lo_code), dh = hn::Sub(t[i], hi_code);
          e6 = hn::Mul(d6, d6);
          c6 = hn::IfThenElse(hn::Eq(j6, hn::Zero(d)), hn::Zero(d),
                              hn::IfThenElse(hn::Eq(j6, hn::Set(d, 5)), hn::Set(d, 1), hn::Add(j6, hn::Set(d, 1))));
          const VF el = hn::Mul(dl, dl), eh = hn::Mul(dh, dh);
          const auto use_lo = hn::Lt(el, e6);
          e6 = hn::IfThenElse(use_lo, el, e6);
          c6 = hn::IfThenElse(hn::RebindMask(d, use_lo), hn::Set(d, 6), c6);
          const auto use_hi = hn::Lt(eh, e6);
          e6 = hn::IfThenElse(use_hi, eh, e6);
          c6 = hn::IfThenElse(hn::RebindMask(d, use_hi), hn::Set(d, 7), c6);
        }
        if (kind == 8) {
          error = hn::Add(error, e8), codes[i] = c8;
        } else if (kind == 6) {
          error = hn::Add(error, e6), codes[i] = c6;
        } else {
          error = hn::Add(error, hn::IfThenElse(eight_f, e8, e6));
          codes[i] = hn::IfThenElse(eight, c8, c6);
        }
      }
      return error;
    };
    V r0 = hn::IfThenElse(hn::Gt(hi, lo), hi, lo), r1 = lo, codes[16];
    VF error = evaluate(r0, r1, codes);
    const V lo6 = hn::ConvertTo(d, hn::Floor(mn6)), hi6 = hn::ConvertTo(d, hn::Ceil(mx6));
    const auto try6 = hn::And(hn::RebindMask(d, hn::Le(mn6, mx6)), hn::Or(hn::Ne(lo6, lo), hn::Ne(hi6, hi)));
    if (!hn::AllFalse(d, try6)) {
      // Lanes not trying it evaluate a harmless pair and ignore the result.
      const V a = hn::IfThenElse(try6, lo6, lo), b = hn::IfThenElse(try6, hi6, hi);
      V codes6[16];
      const VF error6 = evaluate(a, b, codes6);
      const auto take = hn::And(try6, hn::RebindMask(d, hn::Lt(error6, error)));
      r0 = hn::IfThenElse(take, a, r0), r1 = hn::IfThenElse(take, b, r1);
      error = hn::IfThenElse(hn::RebindMask(df, take), error6, error);
      for (int i = 0; i < 16; ++i) codes[i] = hn::IfThenElse(take, codes6[i], codes[i]);
    }
    const auto need = hn::RebindMask(d, hn::Gt(error, hn::Zero(df)));
    if (level >= 1 && !hn::AllFalse(d, need)) {
      const int window = level >= 2 ? 2 : 1;
      const V lo_i = hn::Set(d, snorm ? -127 : 0), hi_i = hn::Set(d, snorm ? 127 : 255);
      const auto inner = hn::RebindMask(d, hn::Le(mn6, mx6));
      const V lo6v = hn::IfThenElse(inner, lo6, lo), hi6v = hn::IfThenElse(inner, hi6, hi);
      // As ref::ls_endpoints, per lane: `valid` loses the lanes without a
      // solution and, in the eight-value mode, those whose fit left it.
      auto ls_endpoints = [&](V aa, V ab, V bb, VF at, VF bt, VF fsteps, int mode, hn::Mask<decltype(d)>& valid, V& ia, V& ib) {
        const V det = hn::Sub(hn::Mul(aa, bb), hn::Mul(ab, ab));
        valid = hn::And(valid, hn::Ne(det, hn::Zero(d)));
        const VF fdet = hn::ConvertTo(df, hn::IfThenElse(valid, det, hn::Set(d, 1)));
        const VF fa = hn::Div(hn::Mul(fsteps, hn::Sub(hn::Mul(at, hn::ConvertTo(df, bb)), hn::Mul(bt, hn::ConvertTo(df, ab)))), fdet);
        const VF fb = hn::Div(hn::Mul(fsteps, hn::Sub(hn::Mul(bt, hn::ConvertTo(df, aa)), hn::Mul(at, hn::ConvertTo(df, ab)))), fdet);
        ia = hn::Min(hn::Max(hn::ConvertTo(d, hn::Floor(hn::Add(fa, half))), lo_i), hi_i);
        ib = hn::Min(hn::Max(hn::ConvertTo(d, hn::Floor(hn::Add(fb, half))), lo_i), hi_i);
        if (mode == 0) {
          valid = hn::And(valid, hn::Gt(ia, ib));
        } else {
          const V lo_end = hn::Min(ia, ib), hi_end = hn::Max(ia, ib);
          ia = lo_end, ib = hi_end;
        }
      };
      auto take_where = [&](hn::Mask<decltype(d)> m, V a, V b, VF e, const V cc[16]) {
        r0 = hn::IfThenElse(m, a, r0), r1 = hn::IfThenElse(m, b, r1);
        error = hn::IfThenElse(hn::RebindMask(df, m), e, error);
        for (int i = 0; i < 16; ++i) codes[i] = hn::IfThenElse(m, cc[i], codes[i]);
      };
      for (int mode = 0; mode < 2; ++mode) {
        const int kind = mode == 0 ? 8 : 6;
        const auto mode_ok = mode == 0 ? hn::And(need, hn::Gt(hi, lo)) : need;
        if (hn::AllFalse(d, mode_ok)) continue;
        V m0 = mode == 0 ? hi : lo6v, m1 = mode == 0 ? lo : hn::Max(lo6v, hi6v), mc[16];
        VF me = evaluate(m0, m1, mc, kind);
        auto active = mode_ok;
        for (int iter = 0; iter < 2; ++iter) {
          const V steps = hn::Set(d, mode == 0 ? 7 : 5);
          V aa = hn::Zero(d), ab = aa, bb = aa;
          VF at = hn::Zero(df), bt = at;
          for (int i = 0; i < 16; ++i) {
            const V code = mc[i];
            const V pos = hn::IfThenElse(hn::Eq(code, hn::Zero(d)), hn::Zero(d),
                                         hn::IfThenElse(hn::Eq(code, hn::Set(d, 1)), steps, hn::Sub(code, hn::Set(d, 1))));
            const auto in = mode == 0 ? hn::Eq(code, code) : hn::Lt(code, hn::Set(d, 6));
            const V u = hn::IfThenElseZero(in, hn::Sub(steps, pos)), w = hn::IfThenElseZero(in, pos);
            aa = hn::Add(aa, hn::Mul(u, u)), ab = hn::Add(ab, hn::Mul(u, w)), bb = hn::Add(bb, hn::Mul(w, w));
            at = hn::Add(at, hn::IfThenElseZero(hn::RebindMask(df, in), hn::Mul(hn::ConvertTo(df, u), t[i])));
            bt = hn::Add(bt, hn::IfThenElseZero(hn::RebindMask(df, in), hn::Mul(hn::ConvertTo(df, w), t[i])));
          }
          V ia, ib;
          ls_endpoints(aa, ab, bb, at, bt, hn::ConvertTo(df, steps), mode, active, ia, ib);
          if (hn::AllFalse(d, active)) break;
          V cc[16];
          const VF ce = evaluate(ia, ib, cc, kind);
          active = hn::And(active, hn::RebindMask(d, hn::Lt(ce, me)));
          m0 = hn::IfThenElse(active, ia, m0), m1 = hn::IfThenElse(active, ib, m1);
          me = hn::IfThenElse(hn::RebindMask(df, active), ce, me);
          for (int i = 0; i < 16; ++i) mc[i] = hn::IfThenElse(active, cc[i], mc[i]);
        }
        take_where(hn::And(mode_ok, hn::RebindMask(d, hn::Lt(me, error))), m0, m1, me, mc);
        auto window_at = [&](V c0, V c1, int w) {
          for (int da = -w; da <= w; ++da)
            for (int db = -w; db <= w; ++db) {
              const V a = hn::Add(c0, hn::Set(d, da)), b = hn::Add(c1, hn::Set(d, db));
              auto valid = hn::And(mode_ok, mode == 0 ? hn::Gt(a, b) : hn::Not(hn::Gt(a, b)));
              valid = hn::And(valid, hn::And(hn::Not(hn::Lt(a, lo_i)), hn::Not(hn::Gt(a, hi_i))));
              valid = hn::And(valid, hn::And(hn::Not(hn::Lt(b, lo_i)), hn::Not(hn::Gt(b, hi_i))));
              if (hn::AllFalse(d, valid)) continue;
              V cc[16];
              const VF ce = evaluate(a, b, cc, kind);
              take_where(hn::And(valid, hn::RebindMask(d, hn::Lt(ce, error))), a, b, ce, cc);
            }
        };
        window_at(m0, m1, window);
        if (level < 2) continue;
        // `high`: partition variants from the starting endpoints (see the reference).
        const int steps_i = mode == 0 ? 7 : 5;
        const VF a0 = hn::ConvertTo(df, mode == 0 ? hi : lo6v), a1 = hn::ConvertTo(df, mode == 0 ? lo : hi6v);
        const auto distinct = hn::Ne(a0, a1);
        const auto lane_ok = hn::And(mode_ok, hn::RebindMask(d, distinct));
        if (hn::AllFalse(d, lane_ok)) continue;
        const VF span = hn::IfThenElse(distinct, hn::Sub(a0, a1), hn::Set(df, 1.0f)), fsteps = hn::Set(df, float(steps_i));
        const V steps = hn::Set(d, steps_i);
        for (int o = -ref::kVariantOffsets; o <= ref::kVariantOffsets; ++o)
          for (int sv = -ref::kVariantStretches; sv <= ref::kVariantStretches; ++sv) {
            const VF stretch = hn::Set(df, ref::variant_stretch(sv)), shift = hn::Set(df, ref::variant_shift(o, sv, steps_i));
            V aa = hn::Zero(d), ab = aa, bb = aa;
            VF at = hn::Zero(df), bt = at;
            for (int i = 0; i < 16; ++i) {
              const auto in = mode == 0 ? hn::Eq(lo_i, lo_i) : hn::RebindMask(d, hn::And(hn::Gt(t[i], inner_lo), hn::Lt(t[i], inner_hi)));
              const VF x = hn::Add(hn::Mul(hn::Mul(hn::Div(hn::Sub(a0, t[i]), span), fsteps), stretch), shift);
              const V pos = hn::IfThenElseZero(in, hn::Min(hn::Max(hn::ConvertTo(d, hn::Floor(x)), hn::Zero(d)), steps));
              const V u = hn::IfThenElseZero(in, hn::Sub(steps, pos));
              aa = hn::Add(aa, hn::Mul(u, u)), ab = hn::Add(ab, hn::Mul(u, pos)), bb = hn::Add(bb, hn::Mul(pos, pos));
              at = hn::Add(at, hn::IfThenElseZero(hn::RebindMask(df, in), hn::Mul(hn::ConvertTo(df, u), t[i])));
              bt = hn::Add(bt, hn::IfThenElseZero(hn::RebindMask(df, in), hn::Mul(hn::ConvertTo(df, pos), t[i])));
            }
            auto valid = lane_ok;
            V ia, ib;
            ls_endpoints(aa, ab, bb, at, bt, fsteps, mode, valid, ia, ib);
            if (hn::AllFalse(d, valid)) continue;
            V cc[16];
            const VF ce = evaluate(ia, ib, cc, kind);
            take_where(hn::And(valid, hn::RebindMask(d, hn::Lt(ce, error))), ia, ib, ce, cc);
          }
      }
    }
    V bits_lo = hn::Zero(d), bits_hi = hn::Zero(d);
    for (int i = 0; i < 8; ++i) {
      bits_lo = hn::Or(bits_lo, hn::ShiftLeftSame(codes[i], 3 * i));
      bits_hi = hn::Or(bits_hi, hn::ShiftLeftSame(codes[i + 8], 3 * i));
    }
    HWY_ALIGN std::int32_t e0[kBc4Batch], e1[kBc4Batch], blo[kBc4Batch], bhi[kBc4Batch];
    hn::Store(r0, d, e0), hn::Store(r1, d, e1), hn::Store(bits_lo, d, blo), hn::Store(bits_hi, d, bhi);
    for (int k = 0; k < lanes && k0 + k < count; ++k) {
      std::uint8_t* o = out[k0 + k];
      o[0] = std::uint8_t(e0[k] & 255), o[1] = std::uint8_t(e1[k] & 255);
      o[2] = std::uint8_t(blo[k]), o[3] = std::uint8_t(blo[k] >> 8), o[4] = std::uint8_t(blo[k] >> 16);
      o[5] = std::uint8_t(bhi[k]), o[6] = std::uint8_t(bhi[k] >> 8), o[7] = std::uint8_t(bhi[k] >> 16);
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace texproc
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace texproc {
HWY_EXPORT(Bc4EncodeLanes);

void bc4_encode_lanes(const float v[16][kBc4Batch], int count, bool snorm, int level, std::uint8_t out[][8]) {
  if (force_scalar()) return ref::bc4_encode_lanes(v, count, snorm, level, out);
  HWY_DYNAMIC_DISPATCH(Bc4EncodeLanes)(v, count, snorm, level, out);
}
}  // namespace texproc
#endif
