// The RGB block primitives: the Highway twins of the scalar references in rgb_block.cpp (lanes
// over the 16 texels, 32-bit lanes; integer sums, and one float expression
// evaluated per texel in the same order: identical results).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "block/rgb_block_simd.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include <algorithm>

#include "block/rgb_block.h"
#include "texproc/runtime.h"

HWY_BEFORE_NAMESPACE();
namespace texproc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
namespace {

using D = hn::CappedTag<std::int32_t, 16>;
using V = hn::Vec<D>;

HWY_INLINE std::int32_t lane_total(D d, V v) { return hn::GetLane(hn::SumOfLanes(d, v)); }

}  // namespace

void Bc1Moments_(const RgbBlock& tx, RgbMoments& m) {
  const D d;
  const int lanes = int(hn::Lanes(d));
  V n = hn::Zero(d), sr = n, sg = n, sb = n, rr = n, rg = n, rb = n, gg = n, gb = n, bb = n;
  for (int i = 0; i < 16; i += lanes) {
    const auto opaque = hn::Eq(hn::LoadU(d, tx.transparent + i), hn::Zero(d));
    const V r = hn::IfThenElseZero(opaque, hn::LoadU(d, tx.r + i)),
            g = hn::IfThenElseZero(opaque, hn::LoadU(d, tx.g + i)),
            b = hn::IfThenElseZero(opaque, hn::LoadU(d, tx.b + i));
    n = hn::Add(n, hn::IfThenElseZero(opaque, hn::Set(d, 1)));
    sr = hn::Add(sr, r);
    sg = hn::Add(sg, g);
    sb = hn::Add(sb, b);
    rr = hn::Add(rr, hn::Mul(r, r));
    rg = hn::Add(rg, hn::Mul(r, g));
    rb = hn::Add(rb, hn::Mul(r, b));
    gg = hn::Add(gg, hn::Mul(g, g));
    gb = hn::Add(gb, hn::Mul(g, b));
    bb = hn::Add(bb, hn::Mul(b, b));
  }
  m.n = lane_total(d, n);
  m.sum[0] = lane_total(d, sr);
  m.sum[1] = lane_total(d, sg);
  m.sum[2] = lane_total(d, sb);
  m.sq[0] = lane_total(d, rr);
  m.sq[1] = lane_total(d, rg);
  m.sq[2] = lane_total(d, rb);
  m.sq[3] = lane_total(d, gg);
  m.sq[4] = lane_total(d, gb);
  m.sq[5] = lane_total(d, bb);
}

void Bc1ProjectRange(const RgbBlock& tx, const float axis[3], float& lo, float& hi) {
  const D d;
  const hn::Rebind<float, D> df;
  const int lanes = int(hn::Lanes(d));
  const auto ax = hn::Set(df, axis[0]), ay = hn::Set(df, axis[1]), az = hn::Set(df, axis[2]);
  auto vlo = hn::Set(df, 1e30f), vhi = hn::Set(df, -1e30f);
  for (int i = 0; i < 16; i += lanes) {
    const auto opaque = hn::RebindMask(df, hn::Eq(hn::LoadU(d, tx.transparent + i), hn::Zero(d)));
    const auto p = hn::Add(hn::Add(hn::Mul(hn::ConvertTo(df, hn::LoadU(d, tx.r + i)), ax),
                                   hn::Mul(hn::ConvertTo(df, hn::LoadU(d, tx.g + i)), ay)),
                           hn::Mul(hn::ConvertTo(df, hn::LoadU(d, tx.b + i)), az));
    vlo = hn::Min(vlo, hn::IfThenElse(opaque, p, vlo));
    vhi = hn::Max(vhi, hn::IfThenElse(opaque, p, vhi));
  }
  lo = hn::GetLane(hn::MinOfLanes(df, vlo));
  hi = hn::GetLane(hn::MaxOfLanes(df, vhi));
}

std::int32_t Bc1Nearest(const RgbBlock& tx, const int pal[4][3], int candidates, std::uint8_t codes[16]) {
  const D d;
  const int lanes = int(hn::Lanes(d));
  HWY_ALIGN std::int32_t code_out[16];
  V total = hn::Zero(d);
  for (int i = 0; i < 16; i += lanes) {
    const V r = hn::LoadU(d, tx.r + i), g = hn::LoadU(d, tx.g + i), b = hn::LoadU(d, tx.b + i);
    auto error_of = [&](int k) {
      const V dr = hn::Sub(r, hn::Set(d, pal[k][0])), dg = hn::Sub(g, hn::Set(d, pal[k][1])),
              db = hn::Sub(b, hn::Set(d, pal[k][2]));
      return hn::Add(hn::Add(hn::Mul(dr, dr), hn::Mul(dg, dg)), hn::Mul(db, db));
    };
    V be = error_of(0);
    V best = hn::Zero(d);
    for (int k = 1; k < candidates; ++k) {
      const V e = error_of(k);
      const auto better = hn::Lt(e, be);
      be = hn::IfThenElse(better, e, be);
      best = hn::IfThenElse(better, hn::Set(d, k), best);
    }
    const auto transparent = hn::Ne(hn::LoadU(d, tx.transparent + i), hn::Zero(d));
    total = hn::Add(total, hn::IfThenZeroElse(transparent, be));
    hn::StoreU(hn::IfThenElse(transparent, hn::Set(d, 3), best), d, code_out + i);
  }
  for (int i = 0; i < 16; ++i) codes[i] = std::uint8_t(code_out[i]);
  return lane_total(d, total);
}

void Bc1LsSums_(const RgbBlock& tx, const std::uint8_t codes[16], const int weight[4], int den, RgbLsSums& s) {
  const D d;
  const int lanes = int(hn::Lanes(d));
  HWY_ALIGN std::int32_t code32[16];
  for (int i = 0; i < 16; ++i) code32[i] = codes[i];
  V aa = hn::Zero(d), ab = aa, bb = aa, ar = aa, ag = aa, ab_ = aa, br = aa, bg = aa, bbl = aa;
  const V vden = hn::Set(d, den);
  for (int i = 0; i < 16; i += lanes) {
    const V c = hn::LoadU(d, code32 + i);
    V w = hn::Set(d, weight[3]);
    w = hn::IfThenElse(hn::Eq(c, hn::Set(d, 2)), hn::Set(d, weight[2]), w);
    w = hn::IfThenElse(hn::Eq(c, hn::Set(d, 1)), hn::Set(d, weight[1]), w);
    w = hn::IfThenElse(hn::Eq(c, hn::Zero(d)), hn::Set(d, weight[0]), w);
    const auto in = hn::And(hn::Eq(hn::LoadU(d, tx.transparent + i), hn::Zero(d)), hn::Not(hn::Lt(w, hn::Zero(d))));
    w = hn::IfThenElseZero(in, w);
    const V u = hn::IfThenElseZero(in, hn::Sub(vden, w));
    const V r = hn::LoadU(d, tx.r + i), g = hn::LoadU(d, tx.g + i), b = hn::LoadU(d, tx.b + i);
    aa = hn::Add(aa, hn::Mul(u, u));
    ab = hn::Add(ab, hn::Mul(u, w));
    bb = hn::Add(bb, hn::Mul(w, w));
    ar = hn::Add(ar, hn::Mul(u, r));
    ag = hn::Add(ag, hn::Mul(u, g));
    ab_ = hn::Add(ab_, hn::Mul(u, b));
    br = hn::Add(br, hn::Mul(w, r));
    bg = hn::Add(bg, hn::Mul(w, g));
    bbl = hn::Add(bbl, hn::Mul(w, b));
  }
  s.aa = lane_total(d, aa);
  s.ab = lane_total(d, ab);
  s.bb = lane_total(d, bb);
  s.at[0] = lane_total(d, ar);
  s.at[1] = lane_total(d, ag);
  s.at[2] = lane_total(d, ab_);
  s.bt[0] = lane_total(d, br);
  s.bt[1] = lane_total(d, bg);
  s.bt[2] = lane_total(d, bbl);
}

}  // namespace HWY_NAMESPACE
}  // namespace texproc
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace texproc {
HWY_EXPORT(Bc1Moments_);
HWY_EXPORT(Bc1ProjectRange);
HWY_EXPORT(Bc1Nearest);
HWY_EXPORT(Bc1LsSums_);

RgbBlockKernels rgb_block_kernels() {
  if (force_scalar()) return {&ref::rgb_moments, &ref::rgb_project_range, &ref::rgb_palette_nearest, &ref::rgb_ls_sums};
  return {&HWY_DYNAMIC_DISPATCH(Bc1Moments_), &HWY_DYNAMIC_DISPATCH(Bc1ProjectRange), &HWY_DYNAMIC_DISPATCH(Bc1Nearest),
          &HWY_DYNAMIC_DISPATCH(Bc1LsSums_)};
}

void rgb_moments(const RgbBlock& tx, RgbMoments& m) {
  if (force_scalar()) return ref::rgb_moments(tx, m);
  HWY_DYNAMIC_DISPATCH(Bc1Moments_)(tx, m);
}
void rgb_project_range(const RgbBlock& tx, const float axis[3], float& lo, float& hi) {
  if (force_scalar()) return ref::rgb_project_range(tx, axis, lo, hi);
  HWY_DYNAMIC_DISPATCH(Bc1ProjectRange)(tx, axis, lo, hi);
}
std::int32_t rgb_palette_nearest(const RgbBlock& tx, const int pal[4][3], int candidates, std::uint8_t codes[16]) {
  if (force_scalar()) return ref::rgb_palette_nearest(tx, pal, candidates, codes);
  return HWY_DYNAMIC_DISPATCH(Bc1Nearest)(tx, pal, candidates, codes);
}
void rgb_ls_sums(const RgbBlock& tx, const std::uint8_t codes[16], const int weight[4], int den, RgbLsSums& s) {
  if (force_scalar()) return ref::rgb_ls_sums(tx, codes, weight, den, s);
  HWY_DYNAMIC_DISPATCH(Bc1LsSums_)(tx, codes, weight, den, s);
}
}  // namespace texproc
#endif
