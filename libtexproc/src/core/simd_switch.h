#pragma once
#include <string>

namespace texproc::detail {
// Name of the Highway target HWY_DYNAMIC_DISPATCH picks on this CPU.
std::string dispatched_target_name();
}  // namespace texproc::detail
