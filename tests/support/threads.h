// Running a computation under a thread limit: the tests compare 1 and 2
// threads everywhere (output must not depend on the count).
#pragma once

#include <utility>

#include "texproc/runtime.h"

namespace texproc::test {

template <typename F>
auto with_threads(int threads, F&& f) {
  ThreadLimit limit(threads);
  return std::forward<F>(f)();
}

}  // namespace texproc::test
