#include "publish_queue.hpp"

#include <pthread.h>

#include <cstdio>
#include <exception>

namespace car_ros {

PublishQueue::PublishQueue(size_t max_bytes, size_t max_jobs, std::function<void(size_t)> after_job)
    : max_bytes_(max_bytes),
      max_jobs_(max_jobs < 1 ? 1 : max_jobs),
      after_job_(std::move(after_job)),
      thread_([this] { loop(); }) {}

PublishQueue::~PublishQueue() {
  {
    std::lock_guard<std::mutex> l(m_);
    stop_ = true;
  }
  work_.notify_one();
  thread_.join();
}

void PublishQueue::post(std::function<void()> job, size_t bytes) {
  std::unique_lock<std::mutex> l(m_);
  // full: wait for the thread (an oversized job waits for an empty queue, then goes alone)
  auto full = [&] {
    if (q_.empty() && !running_) return false;
    // the thread's batch counts until it is done: max_jobs waiting + the one running, as one at a time
    return q_.size() + batch_jobs_ > max_jobs_ || bytes_ + bytes > max_bytes_;
  };
  if (full()) {
    ++waiters_;
    // held jobs may be what fills the queue: the thread must be running to make room
    if (idle_) work_.notify_one();
    room_.wait(l, [&] { return !full(); });
    --waiters_;
  }
  q_.emplace_back(std::move(job), bytes);
  bytes_ += bytes;
  if (held_) {
    unwoken_ = true;
    return;
  }
  // wake the thread only when it sleeps: a busy thread finds the job on its own
  wake_thread(l);
}

void PublishQueue::wake_thread(std::unique_lock<std::mutex>& l) {
  unwoken_ = false;
  const bool wake = idle_;
  l.unlock();
  if (wake) work_.notify_one();
}

void PublishQueue::hold() {
  std::lock_guard<std::mutex> l(m_);
  held_ = true;
}

void PublishQueue::release(std::chrono::steady_clock::duration gap) {
  std::unique_lock<std::mutex> l(m_);
  held_ = false;
  if (!unwoken_) return;
  if (gap > std::chrono::steady_clock::duration::zero()) {
    const auto now = std::chrono::steady_clock::now();
    if (now - last_wake_ < gap) return;
    last_wake_ = now;
  }
  wake_thread(l);
}

void PublishQueue::flush() {
  std::unique_lock<std::mutex> l(m_);
  if (q_.empty() && !running_) return;
  ++waiters_;
  unwoken_ = false;
  if (idle_) work_.notify_one();  // held jobs
  room_.wait(l, [&] { return q_.empty() && !running_; });
  --waiters_;
}

size_t PublishQueue::done() const {
  std::lock_guard<std::mutex> l(m_);
  return done_;
}

void PublishQueue::loop() {
  // named for top -H, perf and gdb (15 characters at most)
  pthread_setname_np(pthread_self(), "car_publish");
  std::unique_lock<std::mutex> l(m_);
  // what was queued when the thread looked, run outside the lock: one lock round per batch, not per job
  std::deque<std::pair<std::function<void()>, size_t>> batch;
  for (;;) {
    if (q_.empty()) {
      if (stop_) return;
      idle_ = true;
      work_.wait(l, [&] { return !q_.empty() || stop_; });
      idle_ = false;
      continue;
    }
    batch.swap(q_);
    batch_jobs_ = batch.size();
    running_ = true;
    l.unlock();
    size_t bytes = 0;
    const size_t n = batch.size();
    for (auto& job : batch) {
      try {
        job.first();
        if (after_job_) after_job_(job.second);
      } catch (const std::exception& e) {
        // a publisher that fails (roscpp shutting down) must not end the thread or the node
        std::fprintf(stderr, "car: publishing failed: %s\n", e.what());
      }
      bytes += job.second;
    }
    // the jobs' captures (messages, publishers) are released outside the lock
    batch.clear();
    l.lock();
    running_ = false;
    batch_jobs_ = 0;
    bytes_ -= bytes;
    done_ += n;
    if (waiters_ > 0) room_.notify_all();
  }
}

}  // namespace car_ros
