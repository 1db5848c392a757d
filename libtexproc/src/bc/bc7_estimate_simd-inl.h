// BC7's partition estimate, a block per lane, for bc7_lanes_simd.cpp
// (included once per Highway target, as Highway's -inl headers are): each
// subset's squared residual off its principal axis, from sums built as
// bc7_sum_plan.h says, and the partitions of least estimate kept in order.
// As ref::subset_residual and ref::rank_partitions in bc7_lanes.cpp.
#if defined(TEXPROC_BC7_ESTIMATE_SIMD_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef TEXPROC_BC7_ESTIMATE_SIMD_INL_H_
#undef TEXPROC_BC7_ESTIMATE_SIMD_INL_H_
#else
#define TEXPROC_BC7_ESTIMATE_SIMD_INL_H_
#endif

#include <hwy/highway.h>

#include <cmath>

#include "bc/axis_residual_simd-inl.h"
#include "block/block_lanes_simd-inl.h"
#include "bc/bc7_lanes.h"
#include "bc/bc7_sum_plan.h"

HWY_BEFORE_NAMESPACE();
namespace texproc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// As ref::subset_residual, from the sums as floats: every sum, product
// and difference is an integer below 2^24 (16 255^2 16 < 2^24), so exact
// in float arithmetic, fused or not: the reference's integers.
HWY_INLINE VF subset_residual(int cnt, const VF S[3], const VF Q[6]) {
  const DF df;
  static constexpr float kInverse[17] = {0.0f,      1.0f / 1,  1.0f / 2,  1.0f / 3,  1.0f / 4,  1.0f / 5,
                                         1.0f / 6,  1.0f / 7,  1.0f / 8,  1.0f / 9,  1.0f / 10, 1.0f / 11,
                                         1.0f / 12, 1.0f / 13, 1.0f / 14, 1.0f / 15, 1.0f / 16};
  const VF n = hn::Set(df, float(cnt));
  auto entry = [&](int q, int a, int b) { return hn::NegMulAdd(S[a], S[b], hn::Mul(n, Q[q])); };
  const VF c00 = entry(0, 0, 0), c01 = entry(1, 0, 1), c02 = entry(2, 0, 2), c11 = entry(3, 1, 1), c12 = entry(4, 1, 2),
           c22 = entry(5, 2, 2);
  return hn::Mul(axis_residual(df, c00, c01, c02, c11, c12, c22), hn::Set(df, kInverse[cnt]));
}

// As ref::Ranked, a list per lane.
struct RankedV {
  VF est[64];
  V partition[64];
  int k = 0;
};
HWY_INLINE void init(RankedV& r, int keep) {
  const DI d;
  const DF df;
  r.k = keep;
  for (int j = 0; j < keep; ++j) {
    r.est[j] = hn::Set(df, HUGE_VALF);
    r.partition[j] = hn::Zero(d);
  }
}
HWY_INLINE void insert(RankedV& r, VF e, V p) {
  for (int j = 0; j < r.k; ++j) {
    const auto lt = hn::Lt(e, r.est[j]);
    const VF ne = hn::IfThenElse(lt, r.est[j], e);
    r.est[j] = hn::IfThenElse(lt, e, r.est[j]);
    e = ne;
    const auto lti = hn::RebindMask(DI(), lt);
    const V np = hn::IfThenElse(lti, r.partition[j], p);
    r.partition[j] = hn::IfThenElse(lti, p, r.partition[j]);
    p = np;
  }
}

// As ref::rank_partitions. The sums of each subset but the last come
// from an earlier subset's (SumPlan): whole numbers below 2^24 in floats,
// so exact, the same as the reference's integer sums texel by texel. The two-subset pass keeps its residuals in
// `two` (slot 2 p + s); the three-subset pass takes those of the first
// `two_scanned` two-subset partitions, and its own, where a subset is one
// already seen (kResidualReuse): the same floats, fewer divisions.
HWY_INLINE void rank_partitions(const V (&x)[16][4], int subsets, int scanned, RankedV& all, RankedV* first16, VF* two,
                                int two_scanned) {
  const DI d;
  const DF df;
  const bc7::SumPlan& plan = subsets == 2 ? bc7::kSumPlan2 : bc7::kSumPlan3;
  VF xf[16][3], tS[3], tQ[6], prod[16][6];
  for (auto& v : tS) v = hn::Zero(df);
  for (auto& v : tQ) v = hn::Zero(df);
  for (int i = 0; i < 16; ++i) {
    VF* xi = xf[i];
    for (int c = 0; c < 3; ++c) xi[c] = hn::ConvertTo(df, x[i][c]);
    prod[i][0] = hn::Mul(xi[0], xi[0]);
    prod[i][1] = hn::Mul(xi[0], xi[1]);
    prod[i][2] = hn::Mul(xi[0], xi[2]);
    prod[i][3] = hn::Mul(xi[1], xi[1]);
    prod[i][4] = hn::Mul(xi[1], xi[2]);
    prod[i][5] = hn::Mul(xi[2], xi[2]);
    for (int c = 0; c < 3; ++c) tS[c] = hn::Add(tS[c], xi[c]);
    for (int q = 0; q < 6; ++q) tQ[q] = hn::Add(tQ[q], prod[i][q]);
  }
  const int last = subsets - 1;
  VF sums[2 * 64][9];  // slot 2 p + s: subset s of partition p, S then Q
  VF three[3 * 64];    // the three-subset pass's residuals, slot 3 p + s
  for (int part = 0; part < scanned; ++part) {
    int cnt[3];
    VF S[3][3], Q[3][6];
    for (int s = 0; s < last; ++s) {
      const bc7::SumStep& st = plan.step[part][s];
      VF* out = sums[2 * part + s];
      if (st.parent < 0)
        for (int c = 0; c < 9; ++c) out[c] = hn::Zero(df);
      else
        for (int c = 0; c < 9; ++c) out[c] = sums[st.parent][c];
      for (unsigned m = st.add; m; m &= m - 1) {
        const int i = __builtin_ctz(m);
        for (int c = 0; c < 3; ++c) out[c] = hn::Add(out[c], xf[i][c]);
        for (int q = 0; q < 6; ++q) out[3 + q] = hn::Add(out[3 + q], prod[i][q]);
      }
      for (unsigned m = st.sub; m; m &= m - 1) {
        const int i = __builtin_ctz(m);
        for (int c = 0; c < 3; ++c) out[c] = hn::Sub(out[c], xf[i][c]);
        for (int q = 0; q < 6; ++q) out[3 + q] = hn::Sub(out[3 + q], prod[i][q]);
      }
      cnt[s] = st.count;
      for (int c = 0; c < 3; ++c) S[s][c] = out[c];
      for (int q = 0; q < 6; ++q) Q[s][q] = out[3 + q];
    }
    cnt[last] = 16;
    for (int c = 0; c < 3; ++c) S[last][c] = tS[c];
    for (int q = 0; q < 6; ++q) Q[last][q] = tQ[q];
    for (int s = 0; s < last; ++s) {
      cnt[last] -= cnt[s];
      for (int c = 0; c < 3; ++c) S[last][c] = hn::Sub(S[last][c], S[s][c]);
      for (int q = 0; q < 6; ++q) Q[last][q] = hn::Sub(Q[last][q], Q[s][q]);
    }
    VF est = hn::Zero(df);
    for (int s = 0; s < subsets; ++s) {
      if (cnt[s] == 0) continue;  // an empty subset adds 0 (the reference's residual of no texels)
      VF r;
      if (subsets == 2) {
        r = two[2 * part + s] = subset_residual(cnt[s], S[s], Q[s]);
      } else {
        const int from2 = bc7::kResidualReuse.two[part][s], from3 = bc7::kResidualReuse.three[part][s];
        if (from2 >= 0 && from2 / 2 < two_scanned)
          r = two[from2];
        else if (from3 >= 0)
          r = three[from3];
        else
          r = subset_residual(cnt[s], S[s], Q[s]);
        three[3 * part + s] = r;
      }
      est = hn::Add(est, r);
    }
    insert(all, est, hn::Set(d, part));
    if (first16 && part < 16) insert(*first16, est, hn::Set(d, part));
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace texproc
HWY_AFTER_NAMESPACE();

#endif
