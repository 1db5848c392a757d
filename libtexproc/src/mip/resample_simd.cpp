// SIMD twins of the resampling passes (Highway, dispatched per call). They sum
// in the scalar reference's order with separate multiply and add, so they give
// the same bytes (tests/unit/test_resample.cpp checks it for every target).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "mip/resample_simd.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include "core/simd_switch.h"
#include "mip/resample.h"
#include "texproc/runtime.h"

HWY_BEFORE_NAMESPACE();
namespace texproc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void VerticalPass(const float* const* rows, const float* weights, int taps, int n, float* out) {
  const hn::ScalableTag<float> d;
  const int lanes = int(hn::Lanes(d));
  int x = 0;
  for (; x + 2 * lanes <= n; x += 2 * lanes) {
    auto acc0 = hn::Zero(d), acc1 = hn::Zero(d);
    for (int k = 0; k < taps; ++k) {
      const auto w = hn::Set(d, weights[k]);
      acc0 = hn::Add(acc0, hn::Mul(w, hn::LoadU(d, rows[k] + x)));
      acc1 = hn::Add(acc1, hn::Mul(w, hn::LoadU(d, rows[k] + x + lanes)));
    }
    hn::StoreU(acc0, d, out + x);
    hn::StoreU(acc1, d, out + x + lanes);
  }
  for (; x < n; ++x) {
    float acc = 0.0f;
    for (int k = 0; k < taps; ++k) acc = acc + weights[k] * rows[k][x];
    out[x] = acc;
  }
}

void HorizontalPass(const float* src, int channels, const int* first, const float* weights, int taps, int out_width,
                    float* out) {
  const hn::CappedTag<float, 4> d;
  if (channels != 4 || hn::Lanes(d) != 4) {
    ref::horizontal_pass(src, channels, first, weights, taps, out_width, out);
    return;
  }
  for (int i = 0; i < out_width; ++i) {
    const float* s = src + std::ptrdiff_t(first[i]) * 4;
    const float* w = weights + std::size_t(i) * taps;
    auto acc = hn::Zero(d);
    for (int k = 0; k < taps; ++k) acc = hn::Add(acc, hn::Mul(hn::Set(d, w[k]), hn::LoadU(d, s + 4 * k)));
    hn::StoreU(acc, d, out + 4 * i);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace texproc
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace texproc {
HWY_EXPORT(VerticalPass);
HWY_EXPORT(HorizontalPass);

void vertical_pass(const float* const* rows, const float* weights, int taps, int n, float* out) {
  if (force_scalar()) return ref::vertical_pass(rows, weights, taps, n, out);
  HWY_DYNAMIC_DISPATCH(VerticalPass)(rows, weights, taps, n, out);
}

void horizontal_pass(const float* src, int channels, const int* first, const float* weights, int taps, int out_width,
                     float* out) {
  if (force_scalar()) return ref::horizontal_pass(src, channels, first, weights, taps, out_width, out);
  HWY_DYNAMIC_DISPATCH(HorizontalPass)(src, channels, first, weights, taps, out_width, out);
}

}  // namespace texproc
#endif
