// BC1 cluster-fit splits: the Highway twin of the scalar reference in bc1_cluster.cpp (lanes
// over k). Same expressions, same order, no FMA: identical doubles.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "bc/bc1_cluster_simd.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include <algorithm>
#include <limits>

#include "bc/bc1_cluster.h"
#include "texproc/runtime.h"

HWY_BEFORE_NAMESPACE();
namespace texproc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void ClusterSplits(const double pre[17][3], double total_sq, int n, int i, int j, ClusterRow& out) {
  const hn::ScalableTag<double> d;
  const int lanes = int(hn::Lanes(d));
  const double s0 = i, s1 = j - i;
  int k = j;
  HWY_ALIGN double kk[HWY_MAX_BYTES / sizeof(double)];
  for (; k + lanes <= n + 1; k += lanes) {
    for (int l = 0; l < lanes; ++l) kk[l] = double(k + l);
    const auto kv = hn::Load(d, kk);
    const auto s2 = hn::Sub(kv, hn::Set(d, double(j)));
    const auto s3 = hn::Sub(hn::Set(d, double(n)), kv);
    const auto aa = hn::Add(hn::Add(hn::Set(d, s0), hn::Set(d, (4.0 / 9.0) * s1)), hn::Mul(hn::Set(d, 1.0 / 9.0), s2));
    const auto bb = hn::Add(hn::Add(s3, hn::Set(d, (1.0 / 9.0) * s1)), hn::Mul(hn::Set(d, 4.0 / 9.0), s2));
    const auto ab = hn::Mul(hn::Set(d, 2.0 / 9.0), hn::Add(hn::Set(d, s1), s2));
    const auto det = hn::Sub(hn::Mul(aa, bb), hn::Mul(ab, ab));
    const auto singular = hn::Lt(det, hn::Set(d, 1e-9));
    const auto inv = hn::Div(hn::Set(d, 1.0), det);
    auto err = hn::Set(d, total_sq);
    for (int c = 0; c < 3; ++c) {
      HWY_ALIGN double prek[HWY_MAX_BYTES / sizeof(double)];
      for (int l = 0; l < lanes; ++l) prek[l] = pre[k + l][c];
      const auto pk = hn::Load(d, prek);
      const double x1s = pre[j][c] - pre[i][c];
      const auto x1 = hn::Set(d, x1s);
      const auto x2 = hn::Sub(pk, hn::Set(d, pre[j][c]));
      const auto xa = hn::Add(hn::Set(d, pre[i][c] + (2.0 / 3.0) * x1s), hn::Mul(hn::Set(d, 1.0 / 3.0), x2));
      const auto xb = hn::Add(hn::Add(hn::Sub(hn::Set(d, pre[n][c]), pk), hn::Mul(hn::Set(d, 1.0 / 3.0), x1)),
                              hn::Mul(hn::Set(d, 2.0 / 3.0), x2));
      const auto a =
          hn::Min(hn::Max(hn::Mul(hn::Sub(hn::Mul(xa, bb), hn::Mul(xb, ab)), inv), hn::Zero(d)), hn::Set(d, 255.0));
      const auto b =
          hn::Min(hn::Max(hn::Mul(hn::Sub(hn::Mul(xb, aa), hn::Mul(xa, ab)), inv), hn::Zero(d)), hn::Set(d, 255.0));
      HWY_ALIGN double av[HWY_MAX_BYTES / sizeof(double)], bv[HWY_MAX_BYTES / sizeof(double)];
      hn::Store(a, d, av);
      hn::Store(b, d, bv);
      for (int l = 0; l < lanes; ++l) {
        out.a[k + l - j][c] = av[l];
        out.b[k + l - j][c] = bv[l];
      }
      const auto fit = hn::Mul(hn::Set(d, -2.0), hn::Add(hn::Mul(a, xa), hn::Mul(b, xb)));
      const auto quad =
          hn::Add(hn::Add(hn::Mul(hn::Mul(a, a), aa), hn::Mul(hn::Mul(hn::Mul(hn::Set(d, 2.0), a), b), ab)),
                  hn::Mul(hn::Mul(b, b), bb));
      err = hn::Add(err, hn::Add(fit, quad));
    }
    err = hn::IfThenElse(singular, hn::Set(d, std::numeric_limits<double>::infinity()), err);
    HWY_ALIGN double ev[HWY_MAX_BYTES / sizeof(double)];
    hn::Store(err, d, ev);
    for (int l = 0; l < lanes; ++l) out.err[k + l - j] = ev[l];
  }
  if (k <= n) ref::cluster_splits(pre, total_sq, n, i, j, out, k);  // the remaining k
}

}  // namespace HWY_NAMESPACE
}  // namespace texproc
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace texproc {
HWY_EXPORT(ClusterSplits);

void cluster_splits(const double pre[17][3], double total_sq, int n, int i, int j, ClusterRow& out) {
  if (force_scalar()) return ref::cluster_splits(pre, total_sq, n, i, j, out);
  HWY_DYNAMIC_DISPATCH(ClusterSplits)(pre, total_sq, n, i, j, out);
}
}  // namespace texproc
#endif
