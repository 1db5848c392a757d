// SIMD twins of the RGBA summed-area-table row: one 128-bit vector per texel
// (the four channels' running sums), whatever the target's width.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "sat/sat_rows_simd.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include "sat/sat_rows.h"
#include "texproc/runtime.h"

HWY_BEFORE_NAMESPACE();
namespace texproc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

#if HWY_TARGET == HWY_SCALAR
void Row8(const std::uint8_t* in, int width, const std::uint32_t* prev, std::uint32_t* cur) {
  ref::sat_row_rgba8_u32(in, width, prev, cur);
}
void Row16(const std::uint16_t* in, int width, const std::uint32_t* prev, std::uint32_t* cur) {
  ref::sat_row_rgba16_u32(in, width, prev, cur);
}
#else
namespace {
template <typename In>
HWY_INLINE void sat_row(const In* in, int width, const std::uint32_t* prev, std::uint32_t* cur) {
  const hn::FixedTag<std::uint32_t, 4> d;
  const hn::Rebind<In, decltype(d)> din;
  auto run = hn::Zero(d);
  for (int x = 0; x < width; ++x) {
    run = hn::Add(run, hn::PromoteTo(d, hn::LoadU(din, in + 4 * x)));
    hn::StoreU(hn::Add(hn::LoadU(d, prev + 4 * x), run), d, cur + 4 * x);
  }
}
}  // namespace

void Row8(const std::uint8_t* in, int width, const std::uint32_t* prev, std::uint32_t* cur) {
  sat_row(in, width, prev, cur);
}
void Row16(const std::uint16_t* in, int width, const std::uint32_t* prev, std::uint32_t* cur) {
  sat_row(in, width, prev, cur);
}
#endif

}  // namespace HWY_NAMESPACE
}  // namespace texproc
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace texproc {
HWY_EXPORT(Row8);
HWY_EXPORT(Row16);

void sat_row_rgba8_u32(const std::uint8_t* in, int width, const std::uint32_t* prev, std::uint32_t* cur) {
  if (force_scalar()) return ref::sat_row_rgba8_u32(in, width, prev, cur);
  HWY_DYNAMIC_DISPATCH(Row8)(in, width, prev, cur);
}
void sat_row_rgba16_u32(const std::uint16_t* in, int width, const std::uint32_t* prev, std::uint32_t* cur) {
  if (force_scalar()) return ref::sat_row_rgba16_u32(in, width, prev, cur);
  HWY_DYNAMIC_DISPATCH(Row16)(in, width, prev, cur);
}
}  // namespace texproc
#endif
