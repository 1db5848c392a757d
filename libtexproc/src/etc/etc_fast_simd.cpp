// ETC1 `fast`, a block per lane: the scalar reference (one block at a time,
// plainly) and its Highway twin; both fill the same per-block parameters,
// which one packer writes. See etc_fast.h.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "etc/etc_fast_simd.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include <algorithm>
#include <cstdlib>

#include "etc/etc_fast.h"
#include "etc/etc_tables.h"
#include "texproc/runtime.h"

#ifndef TEXPROC_ETC_FAST_REF
#define TEXPROC_ETC_FAST_REF
namespace texproc::etc {
namespace fast {

// The texels of each half block (row by row indices): left, right, top, bottom.
inline constexpr int kHalf[4][8] = {
    {0, 1, 4, 5, 8, 9, 12, 13}, {2, 3, 6, 7, 10, 11, 14, 15}, {0, 1, 2, 3, 4, 5, 6, 7}, {8, 9, 10, 11, 12, 13, 14, 15}};
// 96 (a + b) for each table: compared with the summed absolute deviation.
inline constexpr int kMid96[8] = {960, 2112, 3648, 5280, 7488, 9984, 13344, 22080};

// A block's choice: flip (halves 2, 3 instead of 0, 1), differential (5-bit
// bases) or individual (4-bit), per half its base, table and modifier
// index per texel (in kHalf order).
struct Params {
  int flip, differential;
  int q[2][3], table[2], idx[2][8];
};

// The block's 64 bits as the specification numbers them (bit 63 first).
inline void pack(const Params& p, std::uint8_t out[8]) {
  std::uint64_t v = 0;
  for (int c = 0; c < 3; ++c) {  // bits 63-40: a byte per channel
    const int byte = p.differential ? p.q[0][c] << 3 | ((p.q[1][c] - p.q[0][c]) & 7) : p.q[0][c] << 4 | p.q[1][c];
    v |= std::uint64_t(byte) << (56 - 8 * c);
  }
  v |= std::uint64_t(p.table[0] << 5 | p.table[1] << 2 | p.differential << 1 | p.flip) << 32;
  std::uint32_t msb = 0, lsb = 0;  // texel (x, y) at bit x * 4 + y of each
  for (int s = 0; s < 2; ++s)
    for (int i = 0; i < 8; ++i) {
      const int t = kHalf[2 * p.flip + s][i], k = (t % 4) * 4 + t / 4;
      msb |= std::uint32_t(p.idx[s][i] >> 1) << k;
      lsb |= std::uint32_t(p.idx[s][i] & 1) << k;
    }
  store_be64(v | std::uint64_t(msb) << 16 | lsb, out);
}

// The quantized mean of 8 values summing to `sum`: 5 or 4 bits.
inline int quantize_sum(int sum, int bits) {
  return int(float((bits == 5 ? 62 : 30) * sum + 2040) / 4080.0f);
}

}  // namespace fast

namespace ref {
namespace {

struct HalfFit {
  int err, q[3], table, idx[8];
};

HalfFit fit(const int rgb[16][3], int h, int bits, int t0) {
  HalfFit best{};
  best.err = -1;
  int sum[3] = {};
  for (int i = 0; i < 8; ++i)
    for (int c = 0; c < 3; ++c) sum[c] += rgb[fast::kHalf[h][i]][c];
  int base[3];
  for (int c = 0; c < 3; ++c) {
    best.q[c] = fast::quantize_sum(sum[c], bits);
    base[c] = bits == 5 ? extend5(best.q[c]) : extend4(best.q[c]);
  }
  // Each texel's distance from the base (squared) and its R + G + B
  // offset: the modifier m costs d2 - 2 m dl + 3 m^2 (unclamped), least at
  // the modifier nearest dl / 3.
  int d2[8], dl[8];
  for (int i = 0; i < 8; ++i) {
    const int* px = rgb[fast::kHalf[h][i]];
    const int dr = px[0] - base[0], dg = px[1] - base[1], db = px[2] - base[2];
    d2[i] = dr * dr + dg * dg + db * db;
    dl[i] = dr + dg + db;
  }
  for (int dt = -1; dt <= 1; ++dt) {
    const int t = std::clamp(t0 + dt, 0, 7), a = kModifiers[t][0], b = kModifiers[t][1];
    int err = 0, idx[8];
    for (int i = 0; i < 8; ++i) {
      const bool up = dl[i] >= 0, far = up ? 2 * dl[i] > 3 * (a + b) : 2 * dl[i] < -3 * (a + b);
      const int m = up ? (far ? b : a) : (far ? -b : -a);
      idx[i] = up ? (far ? 1 : 0) : (far ? 3 : 2);
      err += d2[i] + m * (3 * m - 2 * dl[i]);
    }
    if (best.err < 0 || err < best.err) {
      best.err = err, best.table = t;
      std::copy(idx, idx + 8, best.idx);
    }
  }
  return best;
}

}  // namespace

void etc1_fast_blocks(const std::uint32_t texel[16][kEtcBatch], int count, std::uint8_t out[][8]) {
  for (int k = 0; k < count; ++k) {
    int rgb[16][3];
    for (int i = 0; i < 16; ++i) {
      const std::uint32_t t = texel[i][k];
      rgb[i][0] = int(t & 255), rgb[i][1] = int(t >> 8 & 255), rgb[i][2] = int(t >> 16 & 255);
    }
    int t0[4];
    for (int h = 0; h < 4; ++h) {
      int total = 0, spread = 0;
      for (int i = 0; i < 8; ++i) total += rgb[fast::kHalf[h][i]][0] + rgb[fast::kHalf[h][i]][1] + rgb[fast::kHalf[h][i]][2];
      for (int i = 0; i < 8; ++i) {
        const int* px = rgb[fast::kHalf[h][i]];
        spread += std::abs(8 * (px[0] + px[1] + px[2]) - total);
      }
      t0[h] = 0;
      for (int t = 1; t < 8; ++t)
        if (std::abs(fast::kMid96[t] - spread) < std::abs(fast::kMid96[t0[h]] - spread)) t0[h] = t;
    }
    HalfFit f5[4], f4[4];
    for (int h = 0; h < 4; ++h) f5[h] = fit(rgb, h, 5, t0[h]);
    fast::Params best{};
    int best_err = -1;
    for (int flip = 0; flip < 2; ++flip) {
      const int a = 2 * flip, b = a + 1;
      bool fits = true;
      for (int c = 0; c < 3; ++c) fits &= f5[b].q[c] - f5[a].q[c] >= -4 && f5[b].q[c] - f5[a].q[c] <= 3;
      const HalfFit* pa = &f5[a];
      const HalfFit* pb = &f5[b];
      if (!fits) {
        f4[a] = fit(rgb, a, 4, t0[a]), f4[b] = fit(rgb, b, 4, t0[b]);
        pa = &f4[a], pb = &f4[b];
      }
      const int err = pa->err + pb->err;
      if (best_err >= 0 && err >= best_err) continue;
      best_err = err;
      best.flip = flip, best.differential = fits ? 1 : 0;
      for (int s = 0; s < 2; ++s) {
        const HalfFit& f = s ? *pb : *pa;
        std::copy(f.q, f.q + 3, best.q[s]);
        best.table[s] = f.table;
        std::copy(f.idx, f.idx + 8, best.idx[s]);
      }
    }
    fast::pack(best, out[k]);
  }
}

}  // namespace ref
}  // namespace texproc::etc
#endif

HWY_BEFORE_NAMESPACE();
namespace texproc::etc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void Etc1FastBlocks(const std::uint32_t texel[16][kEtcBatch], int count, std::uint8_t out[][8]) {
  using D = hn::CappedTag<std::int32_t, kEtcBatch>;
  const D d;
  const hn::Rebind<float, D> df;
  const hn::Rebind<std::uint32_t, D> du;
  using V = hn::Vec<D>;
  using M = hn::Mask<D>;
  const int lanes = int(hn::Lanes(d));
  struct Fit {
    V err, q[3], table, idx[8];
  };
  for (int k0 = 0; k0 < count; k0 += lanes) {
    V r[16], g[16], b[16];
    const V mask8 = hn::Set(d, 255);
    for (int i = 0; i < 16; ++i) {
      const V t = hn::BitCast(d, hn::LoadU(du, texel[i] + k0));
      r[i] = hn::And(t, mask8), g[i] = hn::And(hn::ShiftRight<8>(t), mask8), b[i] = hn::And(hn::ShiftRight<16>(t), mask8);
    }
    auto lookup = [&](V t, const int* table) {  // table[t] per lane
      V v = hn::Set(d, table[0]);
      for (int j = 1; j < 8; ++j) v = hn::IfThenElse(hn::Eq(t, hn::Set(d, j)), hn::Set(d, table[j]), v);
      return v;
    };
    int mod_a[8], mod_b[8];
    for (int j = 0; j < 8; ++j) mod_a[j] = kModifiers[j][0], mod_b[j] = kModifiers[j][1];
    V t0[4];
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
    auto fit = [&](int h, int bits, Fit& best) {
      V sum[3] = {hn::Zero(d), hn::Zero(d), hn::Zero(d)};
      for (int i = 0; i < 8; ++i) {
        const int p = fast::kHalf[h][i];
        sum[0] = hn::Add(sum[0], r[p]), sum[1] = hn::Add(sum[1], g[p]), sum[2] = hn::Add(sum[2], b[p]);
      }
      V base[3];
      for (int c = 0; c < 3; ++c) {
        const V num = hn::Add(hn::Mul(hn::Set(d, bits == 5 ? 62 : 30), sum[c]), hn::Set(d, 2040));
        best.q[c] = hn::ConvertTo(d, hn::Div(hn::ConvertTo(df, num), hn::Set(df, 4080.0f)));
        base[c] = bits == 5 ? hn::Or(hn::ShiftLeft<3>(best.q[c]), hn::ShiftRight<2>(best.q[c]))
                            : hn::Or(hn::ShiftLeft<4>(best.q[c]), best.q[c]);
      }
      const V zero = hn::Zero(d);
      V d2[8], dl[8];
      for (int i = 0; i < 8; ++i) {
        const int p = fast::kHalf[h][i];
        const V dr = hn::Sub(r[p], base[0]), dg = hn::Sub(g[p], base[1]), db = hn::Sub(b[p], base[2]);
        d2[i] = hn::Add(hn::Add(hn::Mul(dr, dr), hn::Mul(dg, dg)), hn::Mul(db, db));
        dl[i] = hn::Add(hn::Add(dr, dg), db);
      }
      for (int dt = -1; dt <= 1; ++dt) {
        const V t = hn::Min(hn::Max(hn::Add(t0[h], hn::Set(d, dt)), zero), hn::Set(d, 7));
        const V ma = lookup(t, mod_a), mb = lookup(t, mod_b);
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
    };
    Fit f5[4], f4[4];
    for (int h = 0; h < 4; ++h) fit(h, 5, f5[h]);
    M fits[2];
    for (int flip = 0; flip < 2; ++flip) {
      const int a = 2 * flip, bb = a + 1;
      fits[flip] = hn::Eq(hn::Zero(d), hn::Zero(d));
      for (int c = 0; c < 3; ++c) {
        const V delta = hn::Sub(f5[bb].q[c], f5[a].q[c]);
        fits[flip] = hn::And(fits[flip], hn::And(hn::Not(hn::Lt(delta, hn::Set(d, -4))), hn::Not(hn::Gt(delta, hn::Set(d, 3)))));
      }
    }
    // Individual mode only where a flip's delta does not fit (lanes that do
    // not need it ignore it).
    V err[2];
    Fit chosen[2][2];
    for (int flip = 0; flip < 2; ++flip) {
      const bool any4 = !hn::AllTrue(d, fits[flip]);
      for (int s = 0; s < 2; ++s) {
        const int h = 2 * flip + s;
        chosen[flip][s] = f5[h];
        if (!any4) continue;
        fit(h, 4, f4[h]);
        Fit& c = chosen[flip][s];
        const M m = fits[flip];
        c.err = hn::IfThenElse(m, f5[h].err, f4[h].err);
        c.table = hn::IfThenElse(m, f5[h].table, f4[h].table);
        for (int ch = 0; ch < 3; ++ch) c.q[ch] = hn::IfThenElse(m, f5[h].q[ch], f4[h].q[ch]);
        for (int i = 0; i < 8; ++i) c.idx[i] = hn::IfThenElse(m, f5[h].idx[i], f4[h].idx[i]);
      }
      err[flip] = hn::Add(chosen[flip][0].err, chosen[flip][1].err);
    }
    const M flip = hn::Lt(err[1], err[0]);
    HWY_ALIGN std::int32_t flip_o[kEtcBatch], diff_o[kEtcBatch], q_o[2][3][kEtcBatch], t_o[2][kEtcBatch], idx_o[2][8][kEtcBatch];
    hn::Store(hn::IfThenElseZero(flip, hn::Set(d, 1)), d, flip_o);
    const M differential = hn::Or(hn::And(flip, fits[1]), hn::AndNot(flip, fits[0]));
    hn::Store(hn::IfThenElseZero(differential, hn::Set(d, 1)), d, diff_o);
    for (int s = 0; s < 2; ++s) {
      const Fit& f0 = chosen[0][s];
      const Fit& f1 = chosen[1][s];
      for (int c = 0; c < 3; ++c) hn::Store(hn::IfThenElse(flip, f1.q[c], f0.q[c]), d, q_o[s][c]);
      hn::Store(hn::IfThenElse(flip, f1.table, f0.table), d, t_o[s]);
      for (int i = 0; i < 8; ++i) hn::Store(hn::IfThenElse(flip, f1.idx[i], f0.idx[i]), d, idx_o[s][i]);
    }
    for (int k = 0; k < lanes && k0 + k < count; ++k) {
      fast::Params p;
      p.flip = flip_o[k], p.differential = diff_o[k];
      for (int s = 0; s < 2; ++s) {
        for (int c = 0; c < 3; ++c) p.q[s][c] = q_o[s][c][k];
        p.table[s] = t_o[s][k];
        for (int i = 0; i < 8; ++i) p.idx[s][i] = idx_o[s][i][k];
      }
      fast::pack(p, out[k0 + k]);
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace texproc::etc
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace texproc::etc {
HWY_EXPORT(Etc1FastBlocks);

void etc1_fast_blocks(const std::uint32_t texel[16][kEtcBatch], int count, std::uint8_t out[][8]) {
  if (force_scalar()) return ref::etc1_fast_blocks(texel, count, out);
  HWY_DYNAMIC_DISPATCH(Etc1FastBlocks)(texel, count, out);
}
}  // namespace texproc::etc
#endif
