// Checking that SIMD twins give their scalar reference's bytes: the scalar
// result (TEXPROC_FORCE_SCALAR's switch) against every Highway target this
// CPU supports.
#pragma once

#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <string>

#include "texproc/runtime.h"

namespace texproc::test {

template <typename F>
void expect_same_on_every_target(F&& compute, const std::string& what) {
  const auto scalar = [&] {
    ScalarKernels scalar_only;
    return compute();
  }();
  for (int64_t target : hwy::SupportedAndGeneratedTargets()) {
    hwy::SetSupportedTargetsForTest(target);
    EXPECT_EQ(compute(), scalar) << what << " " << hwy::TargetName(target);
  }
  hwy::SetSupportedTargetsForTest(0);
}

}  // namespace texproc::test
