// Threads over oneTBB: the only file besides the kernels that includes TBB.
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <algorithm>

#include <atomic>
#include <mutex>

#include "texproc/runtime.h"
#include "texproc/tools.h"

namespace texproc {

struct ThreadLimit::Impl {
  std::unique_ptr<tbb::global_control> control;
};

ThreadLimit::ThreadLimit(int threads) : impl_(std::make_unique<Impl>()) {
  if (threads > 0) {
    impl_->control =
        std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  }
}
ThreadLimit::~ThreadLimit() = default;

int hardware_threads() { return tbb::info::default_concurrency(); }

int thread_limit() {
  const auto allowed = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  const int arena = tbb::this_task_arena::max_concurrency();
  return int(std::min<std::size_t>(allowed, std::size_t(arena)));
}

void for_each_row_block(int rows, int block_rows, const std::function<void(int, int)>& fn) {
  if (rows <= 0) return;
  if (block_rows < 1) block_rows = 1;
  const int blocks = (rows + block_rows - 1) / block_rows;
  if (blocks == 1) {
    fn(0, rows);
    return;
  }
  tbb::parallel_for(
      tbb::blocked_range<int>(0, blocks, 1),
      [&](const tbb::blocked_range<int>& r) {
        for (int b = r.begin(); b < r.end(); ++b) {
          const int begin = b * block_rows;
          const int end = begin + block_rows < rows ? begin + block_rows : rows;
          fn(begin, end);
        }
      },
      tbb::simple_partitioner());
}

void for_each_row_block(int rows, int block_rows, const std::function<void(int, int)>& fn,
                        const std::function<void(double)>& progress) {
  if (!progress) return for_each_row_block(rows, block_rows, fn);
  std::mutex mutex;
  int done = 0;
  for_each_row_block(rows, block_rows, [&](int begin, int end) {
    fn(begin, end);
    std::lock_guard lock(mutex);
    done += end - begin;
    progress(double(done) / double(rows));
  });
}

std::size_t for_each_in_order(std::size_t count, std::size_t in_flight, const std::function<void(std::size_t)>& work,
                              const std::function<bool(std::size_t)>& done) {
  std::size_t next = 0;
  std::atomic<bool> stop{false};  // set by the last stage, read by the first (they may run at once)
  tbb::parallel_pipeline(
      std::max<std::size_t>(1, in_flight),
      tbb::make_filter<void, std::size_t>(tbb::filter_mode::serial_in_order, [&](tbb::flow_control& fc) -> std::size_t {
        if (next == count || stop) {
          fc.stop();
          return 0;
        }
        return next++;
      }) & tbb::make_filter<std::size_t, std::size_t>(tbb::filter_mode::parallel, [&](std::size_t i) {
        work(i);
        return i;
      }) & tbb::make_filter<std::size_t, void>(tbb::filter_mode::serial_in_order, [&](std::size_t i) {
        if (!done(i)) stop = true;
      }));
  return next;
}

}  // namespace texproc
