#include "publish_queue.hpp"

#include <cstdio>
#include <exception>

namespace car_ros {

PublishQueue::PublishQueue(size_t max_bytes, size_t max_jobs)
    : max_bytes_(max_bytes), max_jobs_(max_jobs < 1 ? 1 : max_jobs), thread_([this] { loop(); }) {}

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
    return q_.size() >= max_jobs_ || bytes_ + bytes > max_bytes_;
  };
  if (full()) {
    ++waiters_;
    room_.wait(l, [&] { return !full(); });
    --waiters_;
  }
  q_.emplace_back(std::move(job), bytes);
  bytes_ += bytes;
  // wake the thread only when it sleeps: a busy thread finds the job on its own
  const bool wake = idle_;
  l.unlock();
  if (wake) work_.notify_one();
}

void PublishQueue::flush() {
  std::unique_lock<std::mutex> l(m_);
  if (q_.empty() && !running_) return;
  ++waiters_;
  room_.wait(l, [&] { return q_.empty() && !running_; });
  --waiters_;
}

size_t PublishQueue::done() const {
  std::lock_guard<std::mutex> l(m_);
  return done_;
}

void PublishQueue::loop() {
  std::unique_lock<std::mutex> l(m_);
  for (;;) {
    if (q_.empty()) {
      if (stop_) return;
      idle_ = true;
      work_.wait(l, [&] { return !q_.empty() || stop_; });
      idle_ = false;
      continue;
    }
    auto job = std::move(q_.front());
    q_.pop_front();
    running_ = true;
    // a place in the queue is free now (the bytes only when the job is done)
    if (waiters_ > 0) room_.notify_all();
    l.unlock();
    try {
      job.first();
    } catch (const std::exception& e) {
      // a publisher that fails (roscpp shutting down) must not end the thread or the node
      std::fprintf(stderr, "car: publishing failed: %s\n", e.what());
    }
    // the job's captures (a message, a publisher) are released outside the lock
    job.first = nullptr;
    l.lock();
    running_ = false;
    bytes_ -= job.second;
    ++done_;
    if (waiters_ > 0) room_.notify_all();
  }
}

}  // namespace car_ros
