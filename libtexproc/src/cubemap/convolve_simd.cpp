// SIMD twin of the lobe convolution (convolve.h): sixteen partial sums held
// in 16 / N vectors of N lanes, so every target adds in the reference's order.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "cubemap/convolve_simd.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include "cubemap/convolve.h"
#include "texproc/runtime.h"

HWY_BEFORE_NAMESPACE();
namespace texproc::cube {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

#if HWY_TARGET == HWY_SCALAR
void Convolve(const ConvolveSource& src, const float* nx, const float* ny, const float* nz, std::size_t count,
              float ggx_alpha, float* out) {
  ref::convolve_lobe(src, nx, ny, nz, count, ggx_alpha, out);
}
#else
namespace {
template <bool kGgx>
void convolve_lanes(const ConvolveSource& src, const float* nx, const float* ny, const float* nz, std::size_t count,
                    float ggx_alpha, float* out) {
  const hn::CappedTag<float, 16> d;
  constexpr std::size_t kMaxVecs = 16;
  const std::size_t N = hn::Lanes(d), vecs = 16 / N;
  const float a2 = ggx_alpha * ggx_alpha;
  const auto h = hn::Set(d, (a2 - 1.0f) * 0.5f), one = hn::Set(d, 1.0f), zero = hn::Zero(d);
  for (std::size_t o = 0; o < count; ++o) {
    const auto vx = hn::Set(d, nx[o]), vy = hn::Set(d, ny[o]), vz = hn::Set(d, nz[o]);
    hn::Vec<decltype(d)> ar[kMaxVecs], ag[kMaxVecs], ab[kMaxVecs], aw[kMaxVecs];
    for (std::size_t v = 0; v < vecs; ++v) ar[v] = ag[v] = ab[v] = aw[v] = zero;
    for (std::size_t base = 0; base < src.count; base += 16) {
      for (std::size_t v = 0; v < vecs; ++v) {
        const std::size_t t = base + v * N;
        const auto c = hn::Add(hn::Add(hn::Mul(vx, hn::LoadU(d, src.x + t)), hn::Mul(vy, hn::LoadU(d, src.y + t))),
                               hn::Mul(vz, hn::LoadU(d, src.z + t)));
        auto w = hn::Mul(hn::Max(c, zero), hn::LoadU(d, src.w + t));
        if constexpr (kGgx) {
          const auto q = hn::Add(hn::Mul(hn::Add(one, c), h), one);
          w = hn::Div(w, hn::Mul(q, q));
        }
        ar[v] = hn::Add(ar[v], hn::Mul(w, hn::LoadU(d, src.r + t)));
        ag[v] = hn::Add(ag[v], hn::Mul(w, hn::LoadU(d, src.g + t)));
        ab[v] = hn::Add(ab[v], hn::Mul(w, hn::LoadU(d, src.b + t)));
        aw[v] = hn::Add(aw[v], w);
      }
    }
    HWY_ALIGN float acc[4][16];
    for (std::size_t v = 0; v < vecs; ++v) {
      hn::StoreU(ar[v], d, acc[0] + v * N);
      hn::StoreU(ag[v], d, acc[1] + v * N);
      hn::StoreU(ab[v], d, acc[2] + v * N);
      hn::StoreU(aw[v], d, acc[3] + v * N);
    }
    finish_convolution(acc, out + 3 * o);
  }
}
}  // namespace

void Convolve(const ConvolveSource& src, const float* nx, const float* ny, const float* nz, std::size_t count,
              float ggx_alpha, float* out) {
  if (ggx_alpha >= 0.0f) return convolve_lanes<true>(src, nx, ny, nz, count, ggx_alpha, out);
  convolve_lanes<false>(src, nx, ny, nz, count, ggx_alpha, out);
}
#endif

}  // namespace HWY_NAMESPACE
}  // namespace texproc::cube
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace texproc::cube {
HWY_EXPORT(Convolve);

void convolve_lobe(const ConvolveSource& src, const float* nx, const float* ny, const float* nz, std::size_t count,
                   float ggx_alpha, float* out) {
  if (force_scalar()) return ref::convolve_lobe(src, nx, ny, nz, count, ggx_alpha, out);
  HWY_DYNAMIC_DISPATCH(Convolve)(src, nx, ny, nz, count, ggx_alpha, out);
}
}  // namespace texproc::cube
#endif
