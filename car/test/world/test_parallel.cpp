// car's parallel loop (include/car_sim/parallel.hpp): every item once, nesting, exceptions, thread counts.
#include <gtest/gtest.h>
#include <omp.h>

#include <atomic>
#include <stdexcept>
#include <thread>
#include <vector>

#include "car_sim/parallel.hpp"

using namespace car_sim;

// 10 000 items on two threads: each runs exactly once.
TEST(ParallelFor, EveryItemRunsExactlyOnce) {
  std::vector<std::atomic<int>> count(10000);
  for (auto& c : count) c = 0;
  const int threads = omp_get_max_threads();
  omp_set_num_threads(2);
  for (int round = 0; round < 50; ++round) parallel_for(10000, [&](int i) { count[i].fetch_add(1); });
  omp_set_num_threads(threads);
  for (int i = 0; i < 10000; ++i) ASSERT_EQ(count[i].load(), 50) << i;
}

// A loop inside an item runs serially on that item's thread and completes: 8 x 100 = 800 inner items.
TEST(ParallelFor, NestedLoopsRunSeriallyAndComplete) {
  std::atomic<int> total{0};
  parallel_for(8, [&](int) { parallel_for(100, [&](int) { total.fetch_add(1); }); });
  EXPECT_EQ(total.load(), 800);
}

// Two threads looping at once: one of them gets the pool, the other runs serially; both complete (2 x 500 x 40).
TEST(ParallelFor, TwoCallersAtOnceBothComplete) {
  std::atomic<int> total{0};
  auto many = [&] {
    for (int r = 0; r < 40; ++r) parallel_for(500, [&](int) { total.fetch_add(1); });
  };
  std::thread a(many), b(many);
  a.join();
  b.join();
  EXPECT_EQ(total.load(), 40000);
}

// An item's exception reaches the caller once the loop is over; the pool keeps working afterwards.
TEST(ParallelFor, AnItemsExceptionIsRethrownAfterTheLoop) {
  std::atomic<int> ran{0};
  EXPECT_THROW(parallel_for(1000,
                            [&](int i) {
                              ran.fetch_add(1);
                              if (i == 500) throw std::runtime_error("item 500");
                            }),
               std::runtime_error);
  EXPECT_EQ(ran.load(), 1000);
  std::atomic<int> after{0};
  parallel_for(100, [&](int) { after.fetch_add(1); });
  EXPECT_EQ(after.load(), 100);
}

// No items: fn is never called.
TEST(ParallelFor, ZeroItemsCallNothing) {
  bool called = false;
  parallel_for(0, [&](int) { called = true; });
  EXPECT_FALSE(called);
}

// The thread index of an item is 0 (the caller) up to parallel_threads() - 1, and the caller's own items read 0.
TEST(ParallelFor, ThreadIndicesAreWithinTheThreadCount) {
  const int threads = omp_get_max_threads();
  omp_set_num_threads(2);
  std::vector<int> index(5000, -1);
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<bool> caller_not_zero{false};
  parallel_for_threads(5000, [&](int i, int t) {
    index[i] = t;
    if (std::this_thread::get_id() == caller && t != 0) caller_not_zero = true;
  });
  omp_set_num_threads(threads);
  for (int i = 0; i < 5000; ++i) ASSERT_TRUE(index[i] == 0 || index[i] == 1) << i << ": " << index[i];
  EXPECT_FALSE(caller_not_zero.load());
}
