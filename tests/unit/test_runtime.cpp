// The library's runtime: thread limits and the in-order batch runner the CLI
// runs its files with.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>
#include <vector>

#include "support/threads.h"
#include "texproc/runtime.h"
#include "texproc/tools.h"

using namespace texproc;

TEST(Runtime, ThreadLimitIsWhatWorkMayUse) {
  const int all = thread_limit();
  EXPECT_GE(all, 1);
  EXPECT_LE(all, hardware_threads());
  {
    ThreadLimit one(1);
    EXPECT_EQ(thread_limit(), 1);
  }
  EXPECT_EQ(thread_limit(), all);
}

// done(i) comes in order of i, after work(i), whatever order work finishes in;
// no more than in_flight items work at once.
TEST(Runtime, ForEachInOrderReportsInOrderWithABoundInFlight) {
  for (std::size_t in_flight : {1u, 2u, 5u}) {
    std::mutex m;
    std::vector<std::size_t> done_order;
    std::vector<bool> worked(20, false);
    std::atomic<int> running{0}, most{0};
    const std::size_t started = for_each_in_order(
        20, in_flight,
        [&](std::size_t i) {
          const int now = ++running;
          int seen = most.load();
          while (now > seen && !most.compare_exchange_weak(seen, now)) {
          }
          // Later items finish first now and then: done must still be in order.
          std::this_thread::sleep_for(std::chrono::microseconds(i % 3 == 0 ? 900 : 100));
          {
            std::lock_guard lock(m);
            worked[i] = true;
          }
          --running;
        },
        [&](std::size_t i) {
          std::lock_guard lock(m);
          EXPECT_TRUE(worked[i]);
          done_order.push_back(i);
          return true;
        });
    EXPECT_EQ(started, 20u);
    ASSERT_EQ(done_order.size(), 20u);
    for (std::size_t i = 0; i < 20; ++i) EXPECT_EQ(done_order[i], i);
    EXPECT_LE(std::size_t(most.load()), in_flight);
  }
}

// done returning false stops the batch: nothing starts after it, what was in
// flight finishes and is reported, and the count says how many started.
TEST(Runtime, ForEachInOrderStopsWhenDoneSaysSo) {
  std::vector<int> worked(50, 0);
  std::vector<std::size_t> done_order;
  const std::size_t started = for_each_in_order(
      50, 2, [&](std::size_t i) { worked[i] = 1; },
      [&](std::size_t i) {
        done_order.push_back(i);
        return i != 3;
      });
  EXPECT_GE(started, 4u);
  EXPECT_LE(started, 6u);  // the stop and at most in_flight beyond it
  for (std::size_t i = 0; i < 50; ++i) EXPECT_EQ(worked[i], i < started ? 1 : 0) << i;
  EXPECT_EQ(done_order.size(), started);
  EXPECT_EQ(for_each_in_order(
                0, 4, [](std::size_t) {}, [](std::size_t) { return true; }),
            0u);
}
