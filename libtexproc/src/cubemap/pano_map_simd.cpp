// SIMD twin of the face-row mapping (pano_map.h): one texel a lane.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "cubemap/pano_map_simd.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include "cubemap/pano_map.h"
#include "texproc/runtime.h"

HWY_BEFORE_NAMESPACE();
namespace texproc::cube {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

#if HWY_TARGET == HWY_SCALAR
void MapRow(const float axes[9], int n, int j, int width, int height, const FaceRowMap& out) {
  ref::map_face_row(axes, n, j, width, height, out);
}
#else
namespace {
template <class D, class V = hn::Vec<D> >
HWY_INLINE V atan2_lanes(D d, V y, V x) {
  const V ax = hn::Abs(x), ay = hn::Abs(y), zero = hn::Zero(d);
  const V mx = hn::Max(hn::Max(ax, ay), hn::Set(d, 1e-30f)), mn = hn::Min(ax, ay);
  V t = hn::Div(mn, mx);
  const auto big = hn::Gt(t, hn::Set(d, 0.414213562f));
  const V one = hn::Set(d, 1.0f);
  t = hn::IfThenElse(big, hn::Div(hn::Sub(t, one), hn::Add(t, one)), t);
  const V base = hn::IfThenElseZero(big, hn::Set(d, 3.14159265358979f / 4));
  const V z = hn::Mul(t, t);
  V p = hn::Sub(hn::Mul(hn::Set(d, 0.0805374449538f), z), hn::Set(d, 0.138776856032f));
  p = hn::Add(hn::Mul(p, z), hn::Set(d, 0.199777106478f));
  p = hn::Sub(hn::Mul(p, z), hn::Set(d, 0.333329491539f));
  p = hn::Add(hn::Mul(hn::Mul(p, z), t), t);
  V a = hn::Add(base, p);
  a = hn::IfThenElse(hn::Gt(ay, ax), hn::Sub(hn::Set(d, 3.14159265358979f / 2), a), a);
  a = hn::IfThenElse(hn::Lt(x, zero), hn::Sub(hn::Set(d, 3.14159265358979f), a), a);
  return hn::IfThenElse(hn::Lt(y, zero), hn::Neg(a), a);
}

}  // namespace

void MapRow(const float axes[9], int n, int j, int width, int height, const FaceRowMap& out) {
  const hn::ScalableTag<float> d;
  const int N = int(hn::Lanes(d));
  const float kPi = 3.14159265358979f;
  const float step = 2.0f / float(n), offset = 1.0f / float(n) - 1.0f;
  const float v = float(j) * step + offset;
  const float sx = float(width) / (2 * kPi), sy = float(height) / kPi;
  const auto vstep = hn::Set(d, step), voff = hn::Set(d, offset), vsx = hn::Set(d, sx), vsy = hn::Set(d, sy);
  const auto vpi = hn::Set(d, kPi), vhalf = hn::Set(d, kPi / 2), tiny = hn::Set(d, 1e-30f);
  HWY_ALIGN float idx[64];
  for (int k = 0; k < N; ++k) idx[k] = float(k);
  const auto lane = hn::Load(d, idx);
  HWY_ALIGN float tmp[7][64];
  for (int i0 = 0; i0 < n; i0 += N) {
    const auto u = hn::Add(hn::Mul(hn::Add(lane, hn::Set(d, float(i0))), vstep), voff);
    hn::Vec<decltype(d)> dv[3];
    for (int k = 0; k < 3; ++k) {
      dv[k] = hn::Add(hn::Add(hn::Set(d, axes[k]), hn::Mul(u, hn::Set(d, axes[3 + k]))), hn::Set(d, v * axes[6 + k]));
    }
    const auto rho2 = hn::Max(hn::Add(hn::Mul(dv[0], dv[0]), hn::Mul(dv[2], dv[2])), tiny);
    const auto rho = hn::Sqrt(rho2), r2 = hn::Add(rho2, hn::Mul(dv[1], dv[1]));
    const auto phi = atan2_lanes(d, dv[0], hn::Neg(dv[2])), lambda = atan2_lanes(d, dv[1], rho);
    hn::Store(hn::Mul(hn::Add(phi, vpi), vsx), d, tmp[0]);
    hn::Store(hn::Mul(hn::Sub(vhalf, lambda), vsy), d, tmp[1]);
    hn::Store(hn::Div(rho, hn::Sqrt(r2)), d, tmp[6]);
    for (int s = 0; s < 2; ++s) {
      const float* e = axes + 3 + 3 * s;
      const auto e0 = hn::Set(d, e[0]), e1 = hn::Set(d, e[1]), e2 = hn::Set(d, e[2]);
      const auto dphi = hn::Div(hn::Sub(hn::Mul(e2, dv[0]), hn::Mul(e0, dv[2])), rho2);
      const auto drho = hn::Div(hn::Add(hn::Mul(dv[0], e0), hn::Mul(dv[2], e2)), rho);
      const auto dlam = hn::Div(hn::Sub(hn::Mul(rho, e1), hn::Mul(dv[1], drho)), r2);
      hn::Store(hn::Mul(hn::Mul(dphi, vsx), vstep), d, tmp[2 + 2 * s]);
      hn::Store(hn::Neg(hn::Mul(hn::Mul(dlam, vsy), vstep)), d, tmp[3 + 2 * s]);
    }
    const int count = n - i0 < N ? n - i0 : N;
    float* dst[7] = {out.px, out.py, out.ax, out.ay, out.bx, out.by, out.cosl};
    for (int k = 0; k < 7; ++k)
      for (int l = 0; l < count; ++l) dst[k][i0 + l] = tmp[k][l];
  }
}
#endif

}  // namespace HWY_NAMESPACE
}  // namespace texproc::cube
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace texproc::cube {
HWY_EXPORT(MapRow);

void map_face_row(const float axes[9], int n, int j, int width, int height, const FaceRowMap& out) {
  if (force_scalar()) return ref::map_face_row(axes, n, j, width, height, out);
  HWY_DYNAMIC_DISPATCH(MapRow)(axes, n, j, width, height, out);
}
}  // namespace texproc::cube
#endif
