// The switch between SIMD kernels and their scalar references (ScalarKernels).
#include <atomic>
#include <cstdlib>
#include <cstring>

#include "core/simd_switch.h"
#include "texproc/runtime.h"

namespace texproc {
namespace {
// How many ScalarKernels objects live, plus one while TEXPROC_FORCE_SCALAR is set.
std::atomic<int>& holders() {
  static std::atomic<int> n = [] {
    const char* env = std::getenv("TEXPROC_FORCE_SCALAR");
    return env && *env && std::strcmp(env, "0") != 0 ? 1 : 0;
  }();
  return n;
}
}  // namespace

ScalarKernels::ScalarKernels() { holders().fetch_add(1); }
ScalarKernels::~ScalarKernels() { holders().fetch_sub(1); }
bool force_scalar() { return holders().load(std::memory_order_relaxed) > 0; }

std::string simd_target_name() { return force_scalar() ? "scalar" : detail::dispatched_target_name(); }

}  // namespace texproc
