// The process-wide switch between SIMD kernels and their scalar references.
#include <atomic>
#include <cstdlib>
#include <cstring>

#include "core/simd_switch.h"
#include "texproc/runtime.h"

namespace texproc {
namespace {
std::atomic<bool>& flag() {
  static std::atomic<bool> f = [] {
    const char* env = std::getenv("TEXPROC_FORCE_SCALAR");
    return env && *env && std::strcmp(env, "0") != 0;
  }();
  return f;
}
}  // namespace

void set_force_scalar(bool on) { flag().store(on); }
bool force_scalar() { return flag().load(std::memory_order_relaxed); }

std::string simd_target_name() { return force_scalar() ? "scalar" : detail::dispatched_target_name(); }

}  // namespace texproc
