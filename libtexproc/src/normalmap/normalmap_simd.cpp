// SIMD twins of the normal-map row kernels (Highway, dispatched per call).
// Same operation order as the references, no FMA: identical bytes.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "normalmap/normalmap_simd.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include "normalmap/normalmap_kernels.h"
#include "texproc/runtime.h"

HWY_BEFORE_NAMESPACE();
namespace texproc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void ConvolveRow(const float* in, const float* w, int taps, int n, float* out) {
  const hn::ScalableTag<float> d;
  const int lanes = int(hn::Lanes(d));
  int x = 0;
  for (; x + lanes <= n; x += lanes) {
    auto acc = hn::Zero(d);
    for (int k = 0; k < taps; ++k) acc = hn::Add(acc, hn::Mul(hn::Set(d, w[k]), hn::LoadU(d, in + x + k)));
    hn::StoreU(acc, d, out + x);
  }
  if (x < n) ref::convolve_row(in + x, w, taps, n - x, out + x);
}

void NormalsFromGradients(const float* gx, const float* gy, int n, float sx, float sy, float* nx, float* ny,
                          float* nz) {
  const hn::ScalableTag<float> d;
  const int lanes = int(hn::Lanes(d));
  const auto vsx = hn::Set(d, sx), vsy = hn::Set(d, sy), one = hn::Set(d, 1.0f);
  int x = 0;
  for (; x + lanes <= n; x += lanes) {
    const auto a = hn::Mul(vsx, hn::LoadU(d, gx + x));
    const auto b = hn::Mul(vsy, hn::LoadU(d, gy + x));
    const auto len = hn::Sqrt(hn::Add(hn::Add(hn::Mul(a, a), hn::Mul(b, b)), one));
    hn::StoreU(hn::Div(a, len), d, nx + x);
    hn::StoreU(hn::Div(b, len), d, ny + x);
    hn::StoreU(hn::Div(one, len), d, nz + x);
  }
  if (x < n) ref::normals_from_gradients(gx + x, gy + x, n - x, sx, sy, nx + x, ny + x, nz + x);
}

}  // namespace HWY_NAMESPACE
}  // namespace texproc
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace texproc {
HWY_EXPORT(ConvolveRow);
HWY_EXPORT(NormalsFromGradients);

void convolve_row(const float* in, const float* w, int taps, int n, float* out) {
  if (force_scalar()) return ref::convolve_row(in, w, taps, n, out);
  HWY_DYNAMIC_DISPATCH(ConvolveRow)(in, w, taps, n, out);
}

void normals_from_gradients(const float* gx, const float* gy, int n, float sx, float sy, float* nx, float* ny,
                            float* nz) {
  if (force_scalar()) return ref::normals_from_gradients(gx, gy, n, sx, sy, nx, ny, nz);
  HWY_DYNAMIC_DISPATCH(NormalsFromGradients)(gx, gy, n, sx, sy, nx, ny, nz);
}
}  // namespace texproc
#endif
