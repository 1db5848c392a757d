// texproc/runtime.h: threads and SIMD switches for the whole library.
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

// A batch of `count` items, `in_flight` at most at a time: work(i) runs in
// parallel for i = 0, 1, ... (started in order of i), and done(i) runs for
// each item one at a time in order of i, once it and every item before it
// have finished work. done returning false stops the batch: no item starts
// after that (those in flight finish and get done). Returns how many items
// were started (the rest were not run).
std::size_t for_each_in_order(std::size_t count, std::size_t in_flight, const std::function<void(std::size_t)>& work,
                              const std::function<bool(std::size_t)>& done);

// Forces the scalar reference kernels instead of the SIMD ones (also set by
// the environment variable TEXPROC_FORCE_SCALAR=1). Both give identical bytes.
void set_force_scalar(bool on);
bool force_scalar();
// The SIMD target the dispatched kernels use now ("scalar" when forced).
std::string simd_target_name();

}  // namespace texproc
