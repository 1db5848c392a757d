// BC4 `fast`, `normal` and `high`, a block per lane: the Highway twin of the scalar
// reference in bc4_lanes.cpp (one block at a time, plainly). Both evaluate the same expressions in the
// same order; see bc4_lanes.h.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "bc/bc4_lanes_simd.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include <algorithm>
#include <cmath>

#include "bc/bc4_lanes.h"
#include "bc/bc4_lanes_shared.h"
#include "block/block_lanes_simd-inl.h"
#include "texproc/runtime.h"

HWY_BEFORE_NAMESPACE();
namespace texproc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
// Not in an anonymous namespace, as the other kernels' helpers are: with
// internal linkage GCC 12 inlines the batch's stages differently and BC4
// `high` ran 14% slower (BC1's lanes: 20-26%; bench/compare_builds.py, 7
// rounds interleaved). The one name here, Bc4Batch, is no other file's.

// The lanes' blocks through the search, stage by stage (the scalar
// reference in bc4_lanes.cpp does the same per block): load, start (the
// range and its narrow and six-value candidates), then per mode refine (the
// least-squares iterations), window_at and variants; codes. The best pair so
// far is (r0, r1) with its `error`.
struct Bc4Batch {
  const DF df;
  const DI d;
  const float lo_c, hi_c;
  const VF lo_code, hi_code, half, one, seven, five, inner_lo, inner_hi;
  const V lo_i, hi_i;
  VF t[16], t7[16], t5[16], ends5[16];
  VF mn, mx, mn6, mx6;
  V lo, hi, lo6, hi6;  // the range rounded outwards; the inner values' range (six-value mode)
  M spread;            // hi > lo
  V r0, r1;
  VF error;

  HWY_ATTR explicit Bc4Batch(bool snorm)
      : lo_c(snorm ? -127.0f : 0.0f),
        hi_c(snorm ? 127.0f : 255.0f),
        lo_code(hn::Set(df, lo_c)),
        hi_code(hn::Set(df, hi_c)),
        half(hn::Set(df, 0.5f)),
        one(hn::Set(df, 1.0f)),
        seven(hn::Set(df, 7.0f)),
        five(hn::Set(df, 5.0f)),
        inner_lo(hn::Add(lo_code, half)),
        inner_hi(hn::Sub(hi_code, half)),
        lo_i(hn::Set(d, snorm ? -127 : 0)),
        hi_i(hn::Set(d, snorm ? 127 : 255)) {}

  HWY_INLINE void load(const float v[16][kBc4Batch], int k0) {
    mn = hi_code;
    mx = lo_code;
    mn6 = hi_code;
    mx6 = lo_code;
    for (int i = 0; i < 16; ++i) {
      t[i] = hn::Min(hn::Max(hn::LoadU(df, v[i] + k0), lo_code), hi_code);
      t7[i] = hn::Mul(seven, t[i]);
      t5[i] = hn::Mul(five, t[i]);
      const VF dl = hn::Sub(t5[i], hn::Set(df, 5.0f * lo_c)), dh = hn::Sub(t5[i], hn::Set(df, 5.0f * hi_c));
      ends5[i] = hn::Min(hn::Mul(dl, dl), hn::Mul(dh, dh));
      mn = hn::Min(mn, t[i]);
      mx = hn::Max(mx, t[i]);
      const auto in = hn::And(hn::Gt(t[i], inner_lo), hn::Lt(t[i], inner_hi));
      mn6 = hn::IfThenElse(in, hn::Min(mn6, t[i]), mn6);
      mx6 = hn::IfThenElse(in, hn::Max(mx6, t[i]), mx6);
    }
  }

  // As ref::error8 and ref::error6, per lane; lanes outside the mode
  // (`valid` false) score a harmless pair and are ignored by the caller.
  HWY_INLINE VF error8(V a0, V a1, M valid, V* pos) const {
    const VF f0 = hn::ConvertTo(df, a0),
             span = hn::IfThenElse(hn::RebindMask(df, valid), hn::ConvertTo(df, hn::Sub(a0, a1)), one);
    const VF kk = hn::Div(seven, span), a = hn::Mul(seven, f0);
    VF e = hn::Zero(df);
    for (int i = 0; i < 16; ++i) {
      const VF j = hn::Min(hn::Max(hn::Round(hn::Mul(hn::Sub(f0, t[i]), kk)), hn::Zero(df)), seven);
      const VF dd = hn::Add(hn::Sub(t7[i], a), hn::Mul(span, j));
      e = hn::Add(e, hn::Mul(dd, dd));
      if (pos) pos[i] = hn::ConvertTo(d, j);
    }
    return hn::Div(e, hn::Set(df, 49.0f));
  }
  HWY_INLINE VF error6(V a0, V a1, V* pos) const {
    const VF f0 = hn::ConvertTo(df, a0), span = hn::ConvertTo(df, hn::Sub(a1, a0));
    const auto wide = hn::Gt(span, hn::Zero(df));
    const VF kk = hn::IfThenElseZero(wide, hn::Div(five, hn::IfThenElse(wide, span, one))), a = hn::Mul(five, f0);
    VF e = hn::Zero(df);
    for (int i = 0; i < 16; ++i) {
      const VF j = hn::Min(hn::Max(hn::Round(hn::Mul(hn::Sub(t[i], f0), kk)), hn::Zero(df)), five);
      const VF dd = hn::Sub(hn::Sub(t5[i], a), hn::Mul(span, j));
      const VF d2 = hn::Mul(dd, dd);
      e = hn::Add(e, hn::Min(d2, ends5[i]));
      if (pos) pos[i] = hn::IfThenElse(hn::RebindMask(d, hn::Lt(ends5[i], d2)), hn::Set(d, -1), hn::ConvertTo(d, j));
    }
    return hn::Div(e, hn::Set(df, 25.0f));
  }
  HWY_INLINE VF error_of(int mode, V a, V b, M valid, V* pos) const {
    return mode == 0 ? error8(a, b, valid, pos) : error6(a, b, pos);
  }
  HWY_INLINE void take_where(M m, V a, V b, VF e) {
    r0 = hn::IfThenElse(m, a, r0);
    r1 = hn::IfThenElse(m, b, r1);
    error = hn::IfThenElse(hn::RebindMask(df, m), e, error);
  }

  // The range (equal ends: one value, exact in the six-value mode); the
  // palette of whole code steps over a narrow range; the six-value mode over
  // the inner values.
  HWY_INLINE void start() {
    lo = hn::ConvertTo(d, hn::Floor(mn));
    hi = hn::ConvertTo(d, hn::Ceil(mx));
    spread = hn::Gt(hi, lo);
    r0 = hn::IfThenElse(spread, hi, lo);
    r1 = lo;
    error = hn::IfThenElseZero(hn::RebindMask(df, spread), error8(r0, r1, spread, nullptr));
    const V seven_i = hn::Set(d, 7);
    const M narrow = hn::And(spread, hn::Lt(hn::Sub(hi, lo), seven_i));
    if (!hn::AllFalse(d, narrow)) {  // as the reference: whole code steps over a narrow range
      const V b = hn::Min(lo, hn::Sub(hi_i, seven_i)), a = hn::Add(b, seven_i);
      const VF e7 = error8(a, b, narrow, nullptr);
      take_where(hn::And(narrow, hn::RebindMask(d, hn::Lt(e7, error))), a, b, e7);
    }
    const M inner = hn::RebindMask(d, hn::Le(mn6, mx6));
    lo6 = hn::IfThenElse(inner, hn::ConvertTo(d, hn::Floor(mn6)), lo);
    hi6 = hn::IfThenElse(inner, hn::ConvertTo(d, hn::Ceil(mx6)), hi);
    const M try6 = hn::And(inner, hn::Or(hn::Ne(lo6, lo), hn::Ne(hi6, hi)));
    if (!hn::AllFalse(d, try6)) {
      const VF e6 = error6(lo6, hi6, nullptr);
      take_where(hn::And(try6, hn::RebindMask(d, hn::Lt(e6, error))), lo6, hi6, e6);
    }
  }

  // As ref::ls_endpoints, per lane: `valid` loses the lanes without a
  // solution and, in the eight-value mode, those whose fit left it.
  HWY_INLINE void ls_endpoints(V aa, V ab, V bb, VF at, VF bt, VF fsteps, int mode, M& valid, V& ia, V& ib) const {
    const V det = hn::Sub(hn::Mul(aa, bb), hn::Mul(ab, ab));
    valid = hn::And(valid, hn::Ne(det, hn::Zero(d)));
    const VF fdet = hn::ConvertTo(df, hn::IfThenElse(valid, det, hn::Set(d, 1)));
    const VF fa =
        hn::Div(hn::Mul(fsteps, hn::Sub(hn::Mul(at, hn::ConvertTo(df, bb)), hn::Mul(bt, hn::ConvertTo(df, ab)))), fdet);
    const VF fb =
        hn::Div(hn::Mul(fsteps, hn::Sub(hn::Mul(bt, hn::ConvertTo(df, aa)), hn::Mul(at, hn::ConvertTo(df, ab)))), fdet);
    ia = hn::Min(hn::Max(hn::ConvertTo(d, hn::Floor(hn::Add(fa, half))), lo_i), hi_i);
    ib = hn::Min(hn::Max(hn::ConvertTo(d, hn::Floor(hn::Add(fb, half))), lo_i), hi_i);
    if (mode == 0) {
      valid = hn::And(valid, hn::Gt(ia, ib));
    } else {
      const V lo_end = hn::Min(ia, ib), hi_end = hn::Max(ia, ib);
      ia = lo_end;
      ib = hi_end;
    }
  }

  // In `mode` (0: eight values from the range, 1: six from the inner
  // range): least-squares endpoints for the codes, then codes for the
  // endpoints, twice while that helps; (m0, m1) the result. Taken where it
  // beats the best so far.
  HWY_INLINE void refine(int mode, M mode_ok, V& m0, V& m1) {
    const int steps_i = mode == 0 ? 7 : 5;
    const V steps = hn::Set(d, steps_i);
    const VF fsteps = hn::Set(df, float(steps_i));
    V pos[16];
    m0 = mode == 0 ? hi : lo6;
    m1 = mode == 0 ? lo : hn::Max(lo6, hi6);
    VF me = error_of(mode, m0, m1, mode_ok, pos);
    M active = mode_ok;
    for (int iter = 0; iter < 2; ++iter) {
      V aa = hn::Zero(d), ab = aa, bb = aa;
      VF at = hn::Zero(df), bt = at;
      for (int i = 0; i < 16; ++i) {
        const M in = hn::Not(hn::Lt(pos[i], hn::Zero(d)));
        const V u = hn::IfThenElseZero(in, hn::Sub(steps, pos[i])), w = hn::IfThenElseZero(in, pos[i]);
        aa = hn::Add(aa, hn::Mul(u, u));
        ab = hn::Add(ab, hn::Mul(u, w));
        bb = hn::Add(bb, hn::Mul(w, w));
        at = hn::Add(at, hn::IfThenElseZero(hn::RebindMask(df, in), hn::Mul(hn::ConvertTo(df, u), t[i])));
        bt = hn::Add(bt, hn::IfThenElseZero(hn::RebindMask(df, in), hn::Mul(hn::ConvertTo(df, w), t[i])));
      }
      V ia, ib, cp[16];
      ls_endpoints(aa, ab, bb, at, bt, fsteps, mode, active, ia, ib);
      if (hn::AllFalse(d, active)) break;
      const VF ce = error_of(mode, ia, ib, active, cp);
      active = hn::And(active, hn::RebindMask(d, hn::Lt(ce, me)));
      m0 = hn::IfThenElse(active, ia, m0);
      m1 = hn::IfThenElse(active, ib, m1);
      me = hn::IfThenElse(hn::RebindMask(df, active), ce, me);
      for (int i = 0; i < 16; ++i) pos[i] = hn::IfThenElse(active, cp[i], pos[i]);
    }
    take_where(hn::And(mode_ok, hn::RebindMask(d, hn::Lt(me, error))), m0, m1, me);
  }

  // Every pair within +-w of (c0, c1) in `mode` (w = 0: the pair itself).
  HWY_INLINE void window_at(int mode, V c0, V c1, int w, M ok) {
    for (int da = -w; da <= w; ++da)
      for (int db = -w; db <= w; ++db) {
        if (w > 0 && da == 0 && db == 0) continue;  // the centre, scored already
        const V a = hn::Add(c0, hn::Set(d, da)), b = hn::Add(c1, hn::Set(d, db));
        M valid = hn::And(ok, mode == 0 ? hn::Gt(a, b) : hn::Not(hn::Gt(a, b)));
        valid = hn::And(valid, hn::And(hn::Not(hn::Lt(a, lo_i)), hn::Not(hn::Gt(a, hi_i))));
        valid = hn::And(valid, hn::And(hn::Not(hn::Lt(b, lo_i)), hn::Not(hn::Gt(b, hi_i))));
        if (hn::AllFalse(d, valid)) continue;
        const VF ce = error_of(mode, a, b, valid, nullptr);
        take_where(hn::And(valid, hn::RebindMask(d, hn::Lt(ce, error))), a, b, ce);
      }
  }

  // `high`: partition variants in `mode` from its starting endpoints (see
  // the reference), each position set's least-squares pair scored.
  HWY_INLINE void variants(int mode, M mode_ok, const Bc4LaneSearch& level) {
    const int steps_i = mode == 0 ? 7 : 5;
    const V steps = hn::Set(d, steps_i);
    const VF fsteps = hn::Set(df, float(steps_i));
    const VF a0 = hn::ConvertTo(df, mode == 0 ? hi : lo6), a1 = hn::ConvertTo(df, mode == 0 ? lo : hi6);
    const auto distinct = hn::Ne(a0, a1);
    const M lane_ok = hn::And(mode_ok, hn::RebindMask(d, distinct));
    if (hn::AllFalse(d, lane_ok)) return;
    const VF span = hn::IfThenElse(distinct, hn::Sub(a0, a1), one);
    VF base[16], sum_t = hn::Zero(df);
    hn::Mask<DF> in[16];
    V n_in = hn::Zero(d);
    for (int i = 0; i < 16; ++i) {
      base[i] = hn::Mul(hn::Div(hn::Sub(a0, t[i]), span), fsteps);
      in[i] = mode == 0 ? hn::Eq(t[i], t[i]) : hn::And(hn::Gt(t[i], inner_lo), hn::Lt(t[i], inner_hi));
      sum_t = hn::Add(sum_t, hn::IfThenElseZero(in[i], t[i]));
      n_in = hn::Add(n_in, hn::IfThenElseZero(hn::RebindMask(d, in[i]), hn::Set(d, 1)));
    }
    const VF top = hn::Set(df, float(steps_i));
    for (int o = -level.variant_offsets; o <= level.variant_offsets; ++o)
      for (int sv = -level.variant_stretches; sv <= level.variant_stretches; ++sv) {
        const VF stretch = hn::Set(df, ref::variant_stretch(sv)),
                 shift = hn::Set(df, ref::variant_shift(o, sv, steps_i));
        VF sp = hn::Zero(df), spp = sp, spt = sp;
        for (int i = 0; i < 16; ++i) {
          const VF p = hn::IfThenElseZero(
              in[i], hn::Min(hn::Max(hn::Floor(hn::Add(hn::Mul(base[i], stretch), shift)), hn::Zero(df)), top));
          sp = hn::Add(sp, p);
          spp = hn::Add(spp, hn::Mul(p, p));
          spt = hn::Add(spt, hn::Mul(p, t[i]));
        }
        const V isp = hn::ConvertTo(d, sp), ispp = hn::ConvertTo(d, spp);
        const V aa =
            hn::Add(hn::Sub(hn::Mul(n_in, hn::Set(d, steps_i * steps_i)), hn::Mul(hn::Set(d, 2 * steps_i), isp)), ispp);
        const V ab = hn::Sub(hn::Mul(steps, isp), ispp);
        M valid = lane_ok;
        V ia, ib;
        ls_endpoints(aa, ab, ispp, hn::Sub(hn::Mul(fsteps, sum_t), spt), spt, fsteps, mode, valid, ia, ib);
        if (hn::AllFalse(d, valid)) continue;
        window_at(mode, ia, ib, 0, valid);
      }
  }

  // The codes of the chosen endpoints, as their error counted them, packed
  // 3 bits each into the low and high eight texels' words.
  HWY_INLINE void codes(V& bits_lo, V& bits_hi) const {
    const M eight = hn::Gt(r0, r1);
    V pos8[16], pos6[16], code[16];
    error8(r0, r1, eight, pos8);
    error6(r0, r1, pos6);
    for (int i = 0; i < 16; ++i) {
      const V p = hn::IfThenElse(eight, pos8[i], pos6[i]), top = hn::IfThenElse(eight, hn::Set(d, 7), hn::Set(d, 5));
      V c = hn::IfThenElse(hn::Eq(p, hn::Zero(d)), hn::Zero(d),
                           hn::IfThenElse(hn::Eq(p, top), hn::Set(d, 1), hn::Add(p, hn::Set(d, 1))));
      const VF dl = hn::Sub(t[i], lo_code), dh = hn::Sub(t[i], hi_code);
      const V end =
          hn::IfThenElse(hn::RebindMask(d, hn::Lt(hn::Mul(dh, dh), hn::Mul(dl, dl))), hn::Set(d, 7), hn::Set(d, 6));
      code[i] = hn::IfThenElse(hn::Lt(p, hn::Zero(d)), end, c);
    }
    bits_lo = hn::Zero(d);
    bits_hi = hn::Zero(d);
    for (int i = 0; i < 8; ++i) {
      bits_lo = hn::Or(bits_lo, hn::ShiftLeftSame(code[i], 3 * i));
      bits_hi = hn::Or(bits_hi, hn::ShiftLeftSame(code[i + 8], 3 * i));
    }
  }
};

void Bc4EncodeLanes(const float v[16][kBc4Batch], int count, bool snorm, const Bc4LaneSearch& level,
                    std::uint8_t out[][8]) {
  const int lanes = int(hn::Lanes(DF()));
  Bc4Batch batch(snorm);
  for (int k0 = 0; k0 < count; k0 += lanes) {
    batch.load(v, k0);
    batch.start();
    const DI d;
    const M need = hn::RebindMask(d, hn::Gt(batch.error, hn::Zero(batch.df)));
    if (level.refine && !hn::AllFalse(d, need)) {
      for (int mode = 0; mode < 2; ++mode) {
        const M mode_ok = mode == 0 ? hn::And(need, batch.spread) : need;
        if (hn::AllFalse(d, mode_ok)) continue;
        V m0, m1;
        batch.refine(mode, mode_ok, m0, m1);
        batch.window_at(mode, m0, m1, level.window, mode_ok);
        if (level.variants) batch.variants(mode, mode_ok, level);
      }
    }
    V bits_lo, bits_hi;
    batch.codes(bits_lo, bits_hi);
    HWY_ALIGN std::int32_t e0[kBc4Batch], e1[kBc4Batch], blo[kBc4Batch], bhi[kBc4Batch];
    hn::Store(batch.r0, d, e0);
    hn::Store(batch.r1, d, e1);
    hn::Store(bits_lo, d, blo);
    hn::Store(bits_hi, d, bhi);
    for (int k = 0; k < lanes && k0 + k < count; ++k) {
      std::uint8_t* o = out[k0 + k];
      o[0] = std::uint8_t(e0[k] & 255);
      o[1] = std::uint8_t(e1[k] & 255);
      o[2] = std::uint8_t(blo[k]);
      o[3] = std::uint8_t(blo[k] >> 8);
      o[4] = std::uint8_t(blo[k] >> 16);
      o[5] = std::uint8_t(bhi[k]);
      o[6] = std::uint8_t(bhi[k] >> 8);
      o[7] = std::uint8_t(bhi[k] >> 16);
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace texproc
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace texproc {
HWY_EXPORT(Bc4EncodeLanes);

void bc4_encode_lanes(const float v[16][kBc4Batch], int count, bool snorm, const Bc4LaneSearch& level,
                      std::uint8_t out[][8]) {
  if (force_scalar()) return ref::bc4_encode_lanes(v, count, snorm, level, out);
  HWY_DYNAMIC_DISPATCH(Bc4EncodeLanes)(v, count, snorm, level, out);
}
}  // namespace texproc
#endif
