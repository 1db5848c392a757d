// The name of the Highway target runtime dispatch picks on this CPU
// (simd_switch.h): every kernel's HWY_DYNAMIC_DISPATCH picks the same one.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "core/simd_target_simd.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include <string>

#include "core/simd_switch.h"

HWY_BEFORE_NAMESPACE();
namespace texproc {
namespace HWY_NAMESPACE {
const char* TargetName() { return hwy::TargetName(HWY_TARGET); }
}  // namespace HWY_NAMESPACE
}  // namespace texproc
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace texproc {
HWY_EXPORT(TargetName);

namespace detail {
std::string dispatched_target_name() { return HWY_DYNAMIC_DISPATCH(TargetName)(); }
}  // namespace detail
}  // namespace texproc
#endif
