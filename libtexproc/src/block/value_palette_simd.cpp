// Shared block primitive (BC4, BC5, BC3 alpha, EAC): 16 values scored against an 8-entry palette: the Highway twin of
// the scalar reference in value_palette.cpp (lanes over the 16 values). Same operations, no FMA: identical results.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "block/value_palette_simd.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include "block/value_palette.h"
#include "texproc/runtime.h"

HWY_BEFORE_NAMESPACE();
namespace texproc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void Bc4Nearest(const double t[16], const double pal[8], std::uint8_t codes[16], double errors[16]) {
  const hn::CappedTag<double, 16> d;
  const int lanes = int(hn::Lanes(d));
  HWY_ALIGN double code_out[16];
  for (int i = 0; i < 16; i += lanes) {
    const auto v = hn::LoadU(d, t + i);
    auto diff = hn::Sub(v, hn::Set(d, pal[0]));
    auto be = hn::Mul(diff, diff);
    auto best = hn::Zero(d);
    for (int k = 1; k < 8; ++k) {
      diff = hn::Sub(v, hn::Set(d, pal[k]));
      const auto e = hn::Mul(diff, diff);
      const auto better = hn::Lt(e, be);
      be = hn::IfThenElse(better, e, be);
      best = hn::IfThenElse(better, hn::Set(d, double(k)), best);
    }
    hn::StoreU(be, d, errors + i);
    hn::StoreU(best, d, code_out + i);
  }
  for (int i = 0; i < 16; ++i) codes[i] = std::uint8_t(code_out[i]);
}

}  // namespace HWY_NAMESPACE
}  // namespace texproc
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace texproc {
HWY_EXPORT(Bc4Nearest);

void value_palette_nearest(const double t[16], const double pal[8], std::uint8_t codes[16], double errors[16]) {
  if (force_scalar()) return ref::value_palette_nearest(t, pal, codes, errors);
  HWY_DYNAMIC_DISPATCH(Bc4Nearest)(t, pal, codes, errors);
}
}  // namespace texproc
#endif
