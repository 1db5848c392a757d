// ETC1 in lanes: what the Highway twins of etc_lanes.cpp's `fast`
// (etc_lanes_simd.cpp) and `normal`/`high` (etc_search_lanes_simd.cpp)
// share: a block per lane, loading, the modifier tables, exact evaluation,
// packing. Included by both per target (Highway's -inl.h convention).
#if defined(TEXPROC_ETC_LANES_SIMD_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef TEXPROC_ETC_LANES_SIMD_INL_H_
#undef TEXPROC_ETC_LANES_SIMD_INL_H_
#else
#define TEXPROC_ETC_LANES_SIMD_INL_H_
#endif

#include <hwy/highway.h>

#include <algorithm>
#include <cstdint>

#include "block/block_lanes_simd-inl.h"
#include "etc/etc_lanes.h"
#include "etc/etc_lanes_shared.h"
#include "etc/etc_tables.h"

HWY_BEFORE_NAMESPACE();
namespace texproc::etc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
namespace {

// The batch's types and lane arithmetic (block/block_lanes_simd-inl.h).
using namespace texproc::HWY_NAMESPACE;

// A half block's fit, per lane: its error, base, table and modifier indices.
struct Fit {
  V err, q[3], table, idx[8];
};

// The texels of blocks k0, k0 + 1, ... as channel planes.
HWY_INLINE void load_texels(const std::uint32_t texel[16][kEtcBatch], int k0, V r[16], V g[16], V b[16]) {
  const DI d;
  const hn::Rebind<std::uint32_t, DI> du;
  const V mask8 = hn::Set(d, 255);
  for (int i = 0; i < 16; ++i) {
    const V t = hn::BitCast(d, hn::LoadU(du, texel[i] + k0));
    r[i] = hn::And(t, mask8);
    g[i] = hn::And(hn::ShiftRight<8>(t), mask8);
    b[i] = hn::And(hn::ShiftRight<16>(t), mask8);
  }
}

// The table's modifier a (column 0) or b (column 1) for each lane's table t.
HWY_INLINE V modifier_of(V t, int column) {
  const DI d;
  V v = hn::Set(d, kModifiers[0][column]);
  for (int j = 1; j < 8; ++j) v = hn::IfThenElse(hn::Eq(t, hn::Set(d, j)), hn::Set(d, kModifiers[j][column]), v);
  return v;
}

// A 5- or 4-bit base channel extended to 8 bits.
HWY_INLINE V extend(V q, int bits) {
  return bits == 5 ? hn::Or(hn::ShiftLeft<3>(q), hn::ShiftRight<2>(q)) : hn::Or(hn::ShiftLeft<4>(q), q);
}

// As ref::eval_exact, but for bases given extended to 8 bits (q is left
// to the caller): tables t for the half whose texels are r, g, b[half[0..7]].
HWY_INLINE Fit eval_exact_lanes(const V r[16], const V g[16], const V b[16], const int half[8], const V base[3], V t) {
  const DI d;
  const V zero = hn::Zero(d), top8 = hn::Set(d, 255);
  Fit f;
  f.table = t;
  const V ma = modifier_of(t, 0), mb = modifier_of(t, 1);
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
HWY_INLINE void pack_blocks(V flip, V differential, const Fit& a, const Fit& b, int k0, int count,
                            std::uint8_t out[][8]) {
  const DI d;
  const hn::Rebind<std::uint32_t, DI> du;
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

HWY_INLINE void select_fit(M m, const Fit& from, Fit& to) {
  to.err = hn::IfThenElse(m, from.err, to.err);
  to.table = hn::IfThenElse(m, from.table, to.table);
  for (int c = 0; c < 3; ++c) to.q[c] = hn::IfThenElse(m, from.q[c], to.q[c]);
  for (int i = 0; i < 8; ++i) to.idx[i] = hn::IfThenElse(m, from.idx[i], to.idx[i]);
}

// Lanes where bases `to` are within the differential delta's reach of
// `from` (to - from in [-4, 3] in every channel).
HWY_INLINE M reach_of(const V from[3], const V to[3]) {
  const DI d;
  M ok = hn::Eq(hn::Zero(d), hn::Zero(d));
  for (int c = 0; c < 3; ++c) {
    const V delta = hn::Sub(to[c], from[c]);
    ok = hn::And(ok, hn::And(hn::Not(hn::Lt(delta, hn::Set(d, -4))), hn::Not(hn::Gt(delta, hn::Set(d, 3)))));
  }
  return ok;
}

}  // namespace

}  // namespace HWY_NAMESPACE
}  // namespace texproc::etc
HWY_AFTER_NAMESPACE();

#endif  // TEXPROC_ETC_LANES_SIMD_INL_H_
