// EAC in lanes: the scalar reference (one block at a time, plainly) and its
// Highway twin; both fill the same per-block parameters, which one packer
// writes. See eac_lanes.h.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "etc/eac_lanes_simd.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include <algorithm>
#include <cmath>

#include "etc/eac_lanes.h"
#include "etc/etc_tables.h"
#include "texproc/runtime.h"

#ifndef TEXPROC_EAC_LANES_REF
#define TEXPROC_EAC_LANES_REF
namespace texproc::etc {
namespace eac {

// The modifier indices of every table in ascending order of modifier (the
// tables list -a, -b, -c, -d, then e < f < g < h, with a < b < c < d).
inline constexpr int kAscending[8] = {3, 2, 1, 0, 4, 5, 6, 7};

// A kind's ranges and units: values in [lo_end, hi_end]; a decoded value is
// base * unit + offset + modifier * multiplier * unit (multiplier 0: the
// modifier unscaled, for 8-bit alpha nothing), clamped.
struct Kind {
  float lo_end, hi_end, unit, offset;
  int base_lo, base_hi, unit_i, offset_i, zero_step;
};
inline Kind kind_of(EacKind k) {
  switch (k) {
    case EacKind::alpha8: return {0.0f, 255.0f, 1.0f, 0.0f, 0, 255, 1, 0, 0};
    case EacKind::r11: return {0.0f, 2047.0f, 8.0f, 4.0f, 0, 255, 8, 4, 1};
    case EacKind::r11_signed: return {-1023.0f, 1023.0f, 8.0f, 0.0f, -127, 127, 8, 0, 1};
  }
  return {};
}

// The search window by level: multipliers m0 - mult_below .. m0 + mult_above,
// bases b0 +- base_r.
inline int mult_below(int level) { return level < 2 ? 0 : 1; }
inline int mult_above(int level) { return level == 0 ? 0 : level == 1 ? 1 : 2; }
inline int base_radius(int level) { return level == 0 ? 0 : level == 1 ? 2 : 5; }

// The palette of (base, mult, table) in ascending order of modifier, as
// floats clamped to the kind's range.
inline void palette(const Kind& K, int base, int mult, int table, float pal[8]) {
  for (int j = 0; j < 8; ++j) {
    const int m = kEacModifiers[table][kAscending[j]];
    const int value = base * K.unit_i + K.offset_i + (mult == 0 ? m * K.zero_step : m * mult * K.unit_i);
    pal[j] = std::min(std::max(float(value), K.lo_end), K.hi_end);
  }
}

// Each value's place in the ascending palette: how many midpoints between
// neighbours it lies above (the nearest entry; the lower of two at a tie).
inline int place(float t, const float pal[8]) {
  int s = 0;
  for (int j = 0; j < 7; ++j) s += t > (pal[j] + pal[j + 1]) * 0.5f ? 1 : 0;
  return s;
}

// The squared error of (base, mult, table) for the 16 clamped values.
inline float candidate_error(const Kind& K, const float t[16], int base, int mult, int table) {
  float pal[8];
  palette(K, base, mult, table, pal);
  float err = 0.0f;
  for (int i = 0; i < 16; ++i) {
    const float d = t[i] - pal[place(t[i], pal)];
    err += d * d;
  }
  return err;
}

// The chosen block's codes (values clamped as the search had them): worked
// out once, after the search has scored its candidates by error alone.
inline void codes_of(const Kind& K, const float t[16], int base, int mult, int table, int codes[16]) {
  float pal[8];
  palette(K, base, mult, table, pal);
  for (int i = 0; i < 16; ++i) codes[i] = kAscending[place(t[i], pal)];
}

// 8-bit alpha over a range of at most 5: table 13's modifiers -3..2 at
// multiplier 1 hold six consecutive levels, so such a block is lossless with
// its base 3 above the least value (at most 253). The search's centred
// multiplier rounds to 0 there, a flat palette, so it is tried on its own.
inline constexpr int kNarrowTable = 13;
inline int narrow_base(float lo) { return std::min(int(lo) + 3, 253); }

inline void pack(int base, int mult, int table, const int codes[16], std::uint8_t out[8]) {
  std::uint64_t v = std::uint64_t(base & 255) << 56 | std::uint64_t(mult) << 52 | std::uint64_t(table) << 48;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) v |= std::uint64_t(codes[y * 4 + x]) << (45 - 3 * (x * 4 + y));
  store_be64(v, out);
}

}  // namespace eac

namespace ref {

void eac_encode_lanes(const float v[16][kEacBatch], int count, EacKind kind, int level, std::uint8_t out[][8], float error[]) {
  const eac::Kind K = eac::kind_of(kind);
  for (int k = 0; k < count; ++k) {
    float t[16], lo = K.hi_end, hi = K.lo_end;
    for (int i = 0; i < 16; ++i) {
      t[i] = std::min(std::max(v[i][k], K.lo_end), K.hi_end);
      lo = std::min(lo, t[i]), hi = std::max(hi, t[i]);
    }
    const float centre = (lo + hi) * 0.5f;
    float best = -1.0f;
    int best_base = 0, best_mult = 0, best_table = 0;
    for (int table = 0; table < 16; ++table) {
      const int mn = kEacModifiers[table][3], mx = kEacModifiers[table][7];
      const int m0 = int(std::floor((hi - lo) / (float(mx - mn) * K.unit) + 0.5f));
      for (int mult = m0 - eac::mult_below(level); mult <= m0 + eac::mult_above(level); ++mult) {
        if (mult < 0 || mult > 15) continue;
        const float step = mult == 0 ? float(K.zero_step) : float(mult) * K.unit;
        const float bf = (centre - K.offset - float(mn + mx) * 0.5f * step) / K.unit;
        const int b0 = std::clamp(int(std::floor(bf + 0.5f)), K.base_lo, K.base_hi);
        for (int base = b0 - eac::base_radius(level); base <= b0 + eac::base_radius(level); ++base) {
          if (base < K.base_lo || base > K.base_hi) continue;
          const float err = eac::candidate_error(K, t, base, mult, table);
          if (best < 0.0f || err < best) best = err, best_base = base, best_mult = mult, best_table = table;
        }
      }
    }
    if (kind == EacKind::alpha8 && hi > lo && hi - lo <= 5.0f) {
      const int base = eac::narrow_base(lo);
      const float err = eac::candidate_error(K, t, base, 1, eac::kNarrowTable);
      if (err < best) best = err, best_base = base, best_mult = 1, best_table = eac::kNarrowTable;
    }
    int codes[16];
    eac::codes_of(K, t, best_base, best_mult, best_table, codes);
    eac::pack(best_base, best_mult, best_table, codes, out[k]);
    error[k] = best;
  }
}

}  // namespace ref
}  // namespace texproc::etc
#endif

HWY_BEFORE_NAMESPACE();
namespace texproc::etc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void EacEncodeLanes(const float v[16][kEacBatch], int count, EacKind kind, int level, std::uint8_t out[][8], float error[]) {
  using DF = hn::CappedTag<float, kEacBatch>;
  const DF df;
  const hn::RebindToSigned<DF> d;
  using VF = hn::Vec<DF>;
  using V = hn::Vec<decltype(d)>;
  const int lanes = int(hn::Lanes(df));
  const eac::Kind K = eac::kind_of(kind);
  const VF lo_end = hn::Set(df, K.lo_end), hi_end = hn::Set(df, K.hi_end), half = hn::Set(df, 0.5f);
  for (int k0 = 0; k0 < count; k0 += lanes) {
    VF t[16], lo = hi_end, hi = lo_end;
    for (int i = 0; i < 16; ++i) {
      t[i] = hn::Min(hn::Max(hn::LoadU(df, v[i] + k0), lo_end), hi_end);
      lo = hn::Min(lo, t[i]), hi = hn::Max(hi, t[i]);
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
      const V m0 = hn::ConvertTo(d, hn::Floor(hn::Add(hn::Div(hn::Sub(hi, lo), hn::Set(df, float(mx - mn) * K.unit)), half)));
      for (int dm = -eac::mult_below(level); dm <= eac::mult_above(level); ++dm) {
        const V mult = hn::Add(m0, hn::Set(d, dm));
        auto valid = hn::And(hn::Not(hn::Lt(mult, hn::Zero(d))), hn::Not(hn::Gt(mult, hn::Set(d, 15))));
        if (hn::AllFalse(d, valid)) continue;
        const auto zero_mult = hn::Eq(mult, hn::Zero(d));
        const VF step = hn::IfThenElse(hn::RebindMask(df, zero_mult), hn::Set(df, float(K.zero_step)),
                                       hn::Mul(hn::ConvertTo(df, mult), hn::Set(df, K.unit)));
        const VF bf = hn::Div(hn::Sub(hn::Sub(centre, hn::Set(df, K.offset)), hn::Mul(hn::Set(df, float(mn + mx) * 0.5f), step)),
                              hn::Set(df, K.unit));
        const V b0 = hn::Min(hn::Max(hn::ConvertTo(d, hn::Floor(hn::Add(bf, half))), hn::Set(d, K.base_lo)), hn::Set(d, K.base_hi));
        // Per modifier: what it adds (multiplier 0: the modifier unscaled).
        const V scale = hn::IfThenElse(zero_mult, hn::Set(d, K.zero_step), hn::Mul(mult, hn::Set(d, K.unit_i)));
        for (int db = -eac::base_radius(level); db <= eac::base_radius(level); ++db) {
          const V base = hn::Add(b0, hn::Set(d, db));
          const auto ok = hn::And(valid, hn::And(hn::Not(hn::Lt(base, hn::Set(d, K.base_lo))), hn::Not(hn::Gt(base, hn::Set(d, K.base_hi)))));
          if (hn::AllFalse(d, ok)) continue;
          const V at = hn::Add(hn::Mul(base, hn::Set(d, K.unit_i)), hn::Set(d, K.offset_i));
          const VF err = candidate_error(at, scale, table);
          take_where(hn::And(ok, hn::RebindMask(d, hn::Or(hn::Lt(best, hn::Zero(df)), hn::Lt(err, best)))), err, base, mult, table);
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
    hn::Store(best_base, d, base_o), hn::Store(best_mult, d, mult_o), hn::Store(best_table, d, table_o);
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

void eac_encode_lanes(const float v[16][kEacBatch], int count, EacKind kind, int level, std::uint8_t out[][8], float error[]) {
  if (force_scalar()) return ref::eac_encode_lanes(v, count, kind, level, out, error);
  HWY_DYNAMIC_DISPATCH(EacEncodeLanes)(v, count, kind, level, out, error);
}
}  // namespace texproc::etc
#endif
