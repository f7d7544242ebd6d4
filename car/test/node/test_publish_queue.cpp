// The node's publishing thread (src/ros/publish_queue.hpp): order, flush, the bound, the drain at the end.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "publish_queue.hpp"

using car_ros::PublishQueue;

// Jobs run in the order they were posted (one topic's messages keep their order, and so do the topics').
TEST(PublishQueue, RunsJobsInPostOrder) {
  std::vector<int> seen;
  {
    PublishQueue q(1 << 20, 64);
    for (int i = 0; i < 1000; ++i) q.post([&seen, i] { seen.push_back(i); }, 8);
    q.flush();
    ASSERT_EQ(seen.size(), 1000u);
  }
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(seen[i], i);
}

// flush() returns only after every earlier job has run, the one running included.
TEST(PublishQueue, FlushWaitsForTheRunningJob) {
  PublishQueue q(1 << 20, 64);
  std::atomic<bool> started{false}, finished{false};
  q.post([&] {
    started = true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    finished = true;
  }, 8);
  while (!started) std::this_thread::yield();
  q.flush();
  EXPECT_TRUE(finished.load());
  EXPECT_EQ(q.done(), 1u);
}

// At most max_jobs wait: the poster waits while the queue is full, so at most 4 queued + 1 running.
TEST(PublishQueue, PostWaitsWhileTheQueueHoldsMaxJobs) {
  PublishQueue q(1 << 20, 4);
  std::atomic<int> ran{0};
  std::atomic<bool> release{false};
  q.post([&] {
    while (!release) std::this_thread::yield();
    ++ran;
  }, 1);
  for (int i = 0; i < 4; ++i) q.post([&] { ++ran; }, 1);
  std::atomic<bool> posted{false};
  std::thread poster([&] {
    q.post([&] { ++ran; }, 1);
    posted = true;
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_FALSE(posted.load());  // 4 queued behind the blocked job: the sixth waits
  release = true;
  poster.join();
  q.flush();
  EXPECT_EQ(ran.load(), 6);
}

// At most max_bytes wait: a 600-byte message behind 500 queued bytes waits under a 1000-byte bound.
TEST(PublishQueue, PostWaitsWhileTheQueueHoldsMaxBytes) {
  PublishQueue q(1000, 64);
  std::atomic<bool> release{false};
  q.post([&] { while (!release) std::this_thread::yield(); }, 500);
  std::atomic<bool> posted{false};
  std::thread poster([&] {
    q.post([] {}, 600);
    posted = true;
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_FALSE(posted.load());
  release = true;
  poster.join();
  q.flush();
  EXPECT_EQ(q.done(), 2u);
}

// A message larger than the bound goes alone once the queue is empty (it is not refused, and nothing hangs).
TEST(PublishQueue, OversizedJobRunsAlone) {
  PublishQueue q(100, 64);
  int ran = 0;
  q.post([&] { ++ran; }, 10'000'000);
  q.post([&] { ++ran; }, 10'000'000);
  q.flush();
  EXPECT_EQ(ran, 2);
}

// Destroying the queue runs what is still queued (the node's last messages are sent before its publishers go).
TEST(PublishQueue, DestructorRunsQueuedJobs) {
  std::atomic<int> ran{0};
  {
    PublishQueue q(1 << 20, 1024);
    for (int i = 0; i < 100; ++i) q.post([&] { ++ran; }, 8);
  }
  EXPECT_EQ(ran.load(), 100);
}

// A job that throws is reported and the thread goes on with the next one.
TEST(PublishQueue, ThrowingJobDoesNotStopTheThread) {
  PublishQueue q(1 << 20, 16);
  int ran = 0;
  q.post([] { throw std::runtime_error("publisher gone"); }, 8);
  q.post([&] { ++ran; }, 8);
  q.flush();
  EXPECT_EQ(ran, 1);
}

// Jobs posted between hold() and release() wait for release(): the thread is woken once for all of them.
TEST(PublishQueue, HeldJobsWaitForRelease) {
  PublishQueue q(1 << 20, 64);
  std::atomic<int> ran{0};
  // a busy thread takes whatever is queued: let it go idle first (flush returns once it waits for work)
  q.post([] {}, 8);
  q.flush();
  q.hold();
  for (int i = 0; i < 3; ++i) q.post([&] { ++ran; }, 8);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_EQ(ran.load(), 0);
  q.release();
  while (q.done() < 4) std::this_thread::yield();
  EXPECT_EQ(ran.load(), 3);
}

// release(gap) within `gap` of the last wake-up leaves the jobs held; wake() sends them.
TEST(PublishQueue, ReleaseWithinTheGapKeepsJobsUntilWake) {
  PublishQueue q(1 << 20, 64);
  std::atomic<int> ran{0};
  q.hold();
  q.post([&] { ++ran; }, 8);
  q.release(std::chrono::hours(1));  // the first release wakes (no wake-up yet within the hour)
  while (q.done() < 1) std::this_thread::yield();
  q.hold();
  q.post([&] { ++ran; }, 8);
  q.release(std::chrono::hours(1));  // an hour has not passed: held
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_EQ(ran.load(), 1);
  q.wake();
  while (q.done() < 2) std::this_thread::yield();
  EXPECT_EQ(ran.load(), 2);
}

// flush() sends held jobs too (a callback never waits on a job nobody woke the thread for).
TEST(PublishQueue, FlushSendsHeldJobs) {
  PublishQueue q(1 << 20, 64);
  int ran = 0;
  q.hold();
  q.post([&] { ++ran; }, 8);
  q.flush();
  EXPECT_EQ(ran, 1);
  q.release();
}

// Held jobs that fill the queue wake the thread: post() does not wait forever on a thread nobody woke.
TEST(PublishQueue, HeldJobsFillingTheQueueWakeTheThread) {
  PublishQueue q(1 << 20, 4);
  std::atomic<int> ran{0};
  q.hold();
  for (int i = 0; i < 100; ++i) q.post([&] { ++ran; }, 8);
  q.release();
  q.flush();
  EXPECT_EQ(ran.load(), 100);
}
