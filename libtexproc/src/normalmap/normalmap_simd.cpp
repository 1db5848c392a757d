// SIMD twins of the normal-map row kernels (Highway, dispatched per call).
// Same operation order as the references, no FMA: identical bytes.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "normalmap/normalmap_simd.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include "normalmap/normalmap_rows.h"
#include "texproc/runtime.h"

HWY_BEFORE_NAMESPACE();
namespace texproc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void VerticalPass2(const float* const* rows, const float* wa, const float* wb, int taps, int n, float* a, float* b) {
  const hn::ScalableTag<float> d;
  const int lanes = int(hn::Lanes(d));
  int x = 0;
  for (; x + lanes <= n; x += lanes) {
    auto acc_a = hn::Zero(d), acc_b = hn::Zero(d);
    for (int k = 0; k < taps; ++k) {
      const auto v = hn::LoadU(d, rows[k] + x);
      acc_a = hn::Add(acc_a, hn::Mul(hn::Set(d, wa[k]), v));
      acc_b = hn::Add(acc_b, hn::Mul(hn::Set(d, wb[k]), v));
    }
    hn::StoreU(acc_a, d, a + x);
    hn::StoreU(acc_b, d, b + x);
  }
  if (x < n) {
    const float* shifted[16];
    for (int k = 0; k < taps; ++k) shifted[k] = rows[k] + x;
    ref::vertical_pass2(shifted, wa, wb, taps, n - x, a + x, b + x);
  }
}

void ConvolveRows2(const float* ina, const float* wa, const float* inb, const float* wb, int taps, int n, float* a,
                   float* b) {
  const hn::ScalableTag<float> d;
  const int lanes = int(hn::Lanes(d));
  int x = 0;
  for (; x + lanes <= n; x += lanes) {
    auto acc_a = hn::Zero(d), acc_b = hn::Zero(d);
    for (int k = 0; k < taps; ++k) {
      acc_a = hn::Add(acc_a, hn::Mul(hn::Set(d, wa[k]), hn::LoadU(d, ina + x + k)));
      acc_b = hn::Add(acc_b, hn::Mul(hn::Set(d, wb[k]), hn::LoadU(d, inb + x + k)));
    }
    hn::StoreU(acc_a, d, a + x);
    hn::StoreU(acc_b, d, b + x);
  }
  if (x < n) ref::convolve_rows2(ina + x, wa, inb + x, wb, taps, n - x, a + x, b + x);
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
    const auto inv = hn::Div(one, hn::Sqrt(hn::Add(hn::Add(hn::Mul(a, a), hn::Mul(b, b)), one)));
    hn::StoreU(hn::Mul(a, inv), d, nx + x);
    hn::StoreU(hn::Mul(b, inv), d, ny + x);
    hn::StoreU(inv, d, nz + x);
  }
  if (x < n) ref::normals_from_gradients(gx + x, gy + x, n - x, sx, sy, nx + x, ny + x, nz + x);
}

namespace {

template <class D, class V>
HWY_INLINE auto quantize_u8(D d, V v, V scale_half) {
  // (v * 0.5 + 0.5) * 255 + 0.5, clamped, truncated: as the reference.
  const auto half = hn::Set(d, 0.5f);
  auto e = hn::Add(hn::Mul(hn::Add(hn::Mul(v, half), half), scale_half), half);
  e = hn::Min(hn::Max(e, hn::Zero(d)), hn::Set(d, 255.0f));
  const hn::RebindToSigned<D> di;
  const hn::Rebind<uint8_t, D> du8;
  return hn::DemoteTo(du8, hn::ConvertTo(di, e));
}

template <class D, class V>
HWY_INLINE auto quantize_height_u8(D d, V h) {
  auto e = hn::Add(hn::Mul(h, hn::Set(d, 255.0f)), hn::Set(d, 0.5f));
  e = hn::Min(hn::Max(e, hn::Zero(d)), hn::Set(d, 255.0f));
  const hn::RebindToSigned<D> di;
  const hn::Rebind<uint8_t, D> du8;
  return hn::DemoteTo(du8, hn::ConvertTo(di, e));
}

}  // namespace

void GradientsToU8(const float* gx, const float* gy, const float* h, int n, float sx, float sy, int channels,
                   std::uint8_t* out) {
  const hn::ScalableTag<float> d;
  const hn::Rebind<uint8_t, decltype(d)> du8;
  const int lanes = int(hn::Lanes(d));
  const auto vsx = hn::Set(d, sx), vsy = hn::Set(d, sy), one = hn::Set(d, 1.0f), k255 = hn::Set(d, 255.0f);
  int x = 0;
  for (; x + lanes <= n; x += lanes) {
    const auto a = hn::Mul(vsx, hn::LoadU(d, gx + x));
    const auto b = hn::Mul(vsy, hn::LoadU(d, gy + x));
    const auto inv = hn::Div(one, hn::Sqrt(hn::Add(hn::Add(hn::Mul(a, a), hn::Mul(b, b)), one)));
    const auto r = quantize_u8(d, hn::Mul(a, inv), k255);
    const auto g = quantize_u8(d, hn::Mul(b, inv), k255);
    if (channels == 2) {
      hn::StoreInterleaved2(r, g, du8, out + 2 * x);
      continue;
    }
    const auto bl = quantize_u8(d, inv, k255);
    if (channels == 3) {
      hn::StoreInterleaved3(r, g, bl, du8, out + 3 * x);
    } else {
      hn::StoreInterleaved4(r, g, bl, quantize_height_u8(d, hn::LoadU(d, h + x)), du8, out + 4 * x);
    }
  }
  if (x < n) ref::gradients_to_u8(gx + x, gy + x, h + x, n - x, sx, sy, channels, out + channels * x);
}

}  // namespace HWY_NAMESPACE
}  // namespace texproc
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace texproc {
HWY_EXPORT(VerticalPass2);
HWY_EXPORT(ConvolveRows2);

void vertical_pass2(const float* const* rows, const float* wa, const float* wb, int taps, int n, float* a, float* b) {
  if (force_scalar()) return ref::vertical_pass2(rows, wa, wb, taps, n, a, b);
  HWY_DYNAMIC_DISPATCH(VerticalPass2)(rows, wa, wb, taps, n, a, b);
}

void convolve_rows2(const float* ina, const float* wa, const float* inb, const float* wb, int taps, int n, float* a,
                    float* b) {
  if (force_scalar()) return ref::convolve_rows2(ina, wa, inb, wb, taps, n, a, b);
  HWY_DYNAMIC_DISPATCH(ConvolveRows2)(ina, wa, inb, wb, taps, n, a, b);
}
HWY_EXPORT(NormalsFromGradients);
HWY_EXPORT(GradientsToU8);

void gradients_to_u8(const float* gx, const float* gy, const float* h, int n, float sx, float sy, int channels,
                     std::uint8_t* out) {
  if (force_scalar()) return ref::gradients_to_u8(gx, gy, h, n, sx, sy, channels, out);
  HWY_DYNAMIC_DISPATCH(GradientsToU8)(gx, gy, h, n, sx, sy, channels, out);
}

void normals_from_gradients(const float* gx, const float* gy, int n, float sx, float sy, float* nx, float* ny,
                            float* nz) {
  if (force_scalar()) return ref::normals_from_gradients(gx, gy, n, sx, sy, nx, ny, nz);
  HWY_DYNAMIC_DISPATCH(NormalsFromGradients)(gx, gy, n, sx, sy, nx, ny, nz);
}
}  // namespace texproc
#endif
