// texproc/runtime.h: how many threads libtexproc uses, and its SIMD kernels.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>

namespace texproc {

// Limits libtexproc's worker threads to `threads` while the object lives
// (0 means all hardware threads). Output never depends on the limit: work is
// split into fixed blocks whatever the thread count.
class ThreadLimit {
 public:
  explicit ThreadLimit(int threads);
  ~ThreadLimit();
  ThreadLimit(const ThreadLimit&) = delete;
  ThreadLimit& operator=(const ThreadLimit&) = delete;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Hardware threads available to this process.
int hardware_threads();
// Threads libtexproc's work may use now: hardware_threads() under the
// innermost ThreadLimit.
int thread_limit();

// Calls fn(begin, end) for the blocks [0, b), [b, 2b), ... of [0, rows), in
// parallel. Blocks are fixed by `block_rows`, never by the thread count, so
// a kernel that writes only its own rows gives the same bytes on any number
// of threads. Exceptions thrown by fn are rethrown (the first one).
void for_each_row_block(int rows, int block_rows, const std::function<void(int, int)>& fn);
// The same, and `progress` (where set) hears the fraction of rows done after
// each block of rows: one call at a time, from whichever thread finished the
// block, the fractions rising to 1.
void for_each_row_block(int rows, int block_rows, const std::function<void(int, int)>& fn,
                        const std::function<void(double)>& progress);

// While an object lives, libtexproc's dispatched kernels run their scalar
// references instead of the SIMD ones, on every thread; both give identical
// bytes, so this is for tests and for measuring what SIMD gains. Objects
// nest and may be made on any thread. The environment variable
// TEXPROC_FORCE_SCALAR=1 holds one for the life of the process.
class ScalarKernels {
 public:
  ScalarKernels();
  ~ScalarKernels();
  ScalarKernels(const ScalarKernels&) = delete;
  ScalarKernels& operator=(const ScalarKernels&) = delete;
};
// Whether a ScalarKernels object (or the environment) holds now.
bool force_scalar();
// The SIMD target the dispatched kernels use now ("scalar" when forced).
std::string simd_target_name();

}  // namespace texproc
