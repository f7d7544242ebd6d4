// The node's publishing thread (src/ros/publish_queue.hpp): order, flush, the bound, the drain at the end.
#include <gtest/gtest.h>

#include <sys/syscall.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include "publish_queue.hpp"

using car_ros::PublishQueue;

namespace {

// The calling thread's kernel id (for its /proc/self/task entry).
pid_t this_tid() { return static_cast<pid_t>(syscall(SYS_gettid)); }

// The scheduler state of thread `tid` of this process (proc(5): R running, S sleeping, ...), '?' once it is gone.
char thread_state(pid_t tid) {
  std::ifstream f("/proc/self/task/" + std::to_string(tid) + "/stat");
  const std::string s((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  const auto p = s.rfind(')');  // the state follows the command name in parentheses
  return p == std::string::npos || p + 2 >= s.size() ? '?' : s[p + 2];
}

// Polls done() until it holds; wall time bounds a hang only (60 s), and running out fails naming `what`.
template <class Done>
::testing::AssertionResult wait_until(const char* what, Done done) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return ::testing::AssertionFailure() << what << ": not within 60 s";
    std::this_thread::yield();
  }
  return ::testing::AssertionSuccess();
}

}  // namespace

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
  std::atomic<pid_t> tid{0};
  std::thread poster([&] {
    tid = this_tid();
    q.post([&] { ++ran; }, 1);
    posted = true;
  });
  // the event, not a while: the poster either returns or goes to sleep in post(). Nothing else in post() sleeps
  // here (the queue's thread spins in the blocked job without the queue's lock), so asleep means waiting for room.
  EXPECT_TRUE(wait_until("the poster returned or asleep in post()",
                         [&] { return posted || (tid != 0 && thread_state(tid) == 'S'); }));
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
  std::atomic<pid_t> tid{0};
  std::thread poster([&] {
    tid = this_tid();
    q.post([] {}, 600);
    posted = true;
  });
  // as above: returned, or asleep in post() waiting for room
  EXPECT_TRUE(wait_until("the poster returned or asleep in post()",
                         [&] { return posted || (tid != 0 && thread_state(tid) == 'S'); }));
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
  std::atomic<pid_t> worker{0};
  q.post([&] { worker = this_tid(); }, 8);
  q.flush();
  q.hold();
  for (int i = 0; i < 3; ++i) q.post([&] { ++ran; }, 8);
  // the event, not a while: the queue's thread asleep after the posts. Had a post woken it, it would be runnable
  // from that post on (a wake-up makes it so at once) until it had run the jobs and slept again.
  EXPECT_TRUE(wait_until("the queue's thread ran the held jobs or asleep",
                         [&] { return ran > 0 || thread_state(worker) == 'S'; }));
  EXPECT_EQ(ran.load(), 0);
  q.release();
  while (q.done() < 4) std::this_thread::yield();
  EXPECT_EQ(ran.load(), 3);
}

// release(gap) within `gap` of the last wake-up leaves the jobs held; wake() sends them.
TEST(PublishQueue, ReleaseWithinTheGapKeepsJobsUntilWake) {
  PublishQueue q(1 << 20, 64);
  std::atomic<int> ran{0};
  std::atomic<pid_t> worker{0};
  q.hold();
  q.post([&] {
    worker = this_tid();
    ++ran;
  }, 8);
  q.release(std::chrono::hours(1));  // the first release wakes (no wake-up yet within the hour)
  while (q.done() < 1) std::this_thread::yield();
  q.hold();
  q.post([&] { ++ran; }, 8);
  q.release(std::chrono::hours(1));  // an hour has not passed: held
  // as above: the queue's thread asleep (not woken by the release) or it ran the job
  EXPECT_TRUE(wait_until("the queue's thread ran the held job or asleep",
                         [&] { return ran > 1 || thread_state(worker) == 'S'; }));
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
