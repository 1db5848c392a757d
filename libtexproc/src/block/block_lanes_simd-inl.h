// The vocabulary of the block codecs' SIMD code (BC1, BC4/BC5, BC6H, BC7,
// ETC, EAC), per Highway target (included once per target, as Highway's
// -inl headers are): a batch of kBlockBatch blocks, a block per lane, as
// 32-bit integer, float and unsigned lanes, and the lane arithmetic more
// than one kernel uses. Each kernel file includes this instead of naming
// its own types; names here and in the kernels are snake_case, PascalCase
// being left to the functions Highway exports.
#if defined(TEXPROC_BLOCK_LANES_SIMD_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef TEXPROC_BLOCK_LANES_SIMD_INL_H_
#undef TEXPROC_BLOCK_LANES_SIMD_INL_H_
#else
#define TEXPROC_BLOCK_LANES_SIMD_INL_H_
#endif

#include <hwy/highway.h>

#include <cstdint>

#include "core/block_batch.h"

HWY_BEFORE_NAMESPACE();
namespace texproc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// A block a lane: the tags and vectors of a batch.
using DI = hn::CappedTag<std::int32_t, kBlockBatch>;
using DF = hn::Rebind<float, DI>;
using DU = hn::Rebind<std::uint32_t, DI>;
using V = hn::Vec<DI>;
using VF = hn::Vec<DF>;
using VU = hn::Vec<DU>;
using M = hn::Mask<DI>;
using MF = hn::Mask<DF>;

HWY_INLINE VF as_float(V v) { return hn::ConvertTo(DF(), v); }

#if HWY_TARGET != HWY_SCALAR
// Each lane's two 16-bit halves as signed integers, a_lo b_lo + a_hi b_hi:
// one 16-bit multiply-add a lane (vpmaddwd on x86).
HWY_INLINE V dot16(V a, V b) {
  const DI d;
  const hn::Repartition<std::int16_t, DI> d16;
  V odd = hn::Zero(d);
  const V even = hn::ReorderWidenMulAccumulate(d, hn::BitCast(d16, a), hn::BitCast(d16, b), hn::Zero(d), odd);
  return hn::RearrangeToOddPlusEven(even, odd);
}
#else
// HWY_SCALAR: the same sum, the halves sign-extended by shifts.
HWY_INLINE V dot16(V a, V b) {
  const V a_lo = hn::ShiftRight<16>(hn::ShiftLeft<16>(a)), b_lo = hn::ShiftRight<16>(hn::ShiftLeft<16>(b));
  return hn::Add(hn::Mul(a_lo, b_lo), hn::Mul(hn::ShiftRight<16>(a), hn::ShiftRight<16>(b)));
}
#endif

// a b for a in [0, 32767] and b in [-32768, 32767]: dot16 (half the cost
// of a 32-bit product), a's upper half zero so the upper halves add
// nothing; the same integer as hn::Mul.
// (HWY_SCALAR's one lane has no 16-bit halves: the 32-bit product.)
HWY_INLINE V mul16(V a, V b) {
#if HWY_TARGET == HWY_SCALAR
  return hn::Mul(a, b);
#else
  return dot16(a, b);
#endif
}

// round(v) to the nearest integer, ties to even, for v in [0, hi] with hi
// below 2^22, as hn::ConvertTo(hn::Round(...)) gives: the sum with 1.5 2^23
// rounds (as every float sum, to nearest even) to a whole number, whose
// low mantissa bits are the integer.
HWY_INLINE V round_clamped(VF v, float hi) {
  const DI d;
  const DF df;
  const VF c = hn::Min(hn::Max(v, hn::Zero(df)), hn::Set(df, hi));
  return hn::Sub(hn::BitCast(d, hn::Add(c, hn::Set(df, 12582912.0f))), hn::Set(d, 0x4B400000));
}

// Two channels a lane, lo in the low 16 bits and hi in the high (each in
// [-32768, 32767]): for dot16 and 16-bit lane arithmetic.
HWY_INLINE V pair16(V lo, V hi) {
  const DI d;
  return hn::Or(hn::And(lo, hn::Set(d, 0xFFFF)), hn::ShiftLeft<16>(hi));
}

}  // namespace HWY_NAMESPACE
}  // namespace texproc
HWY_AFTER_NAMESPACE();

#endif  // TEXPROC_BLOCK_LANES_SIMD_INL_H_
