// The node's publishing thread: messages built on the stepping thread are serialised and written to their
// subscribers' sockets on a second thread, so the physics does not wait on send(2) (docs/COMPAT-dropins.md
// "Publishing thread"). Jobs run one at a time in the order they were posted, so every topic keeps its order and
// so does the node's output as a whole. No ROS headers: the jobs are plain callables.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <utility>

namespace car_ros {

class PublishQueue {
 public:
  // At most max_bytes of messages [bytes, serialised size] or max_jobs jobs wait at once: post() blocks beyond
  // that (the simulation waits for its subscribers' sockets instead of queueing without bound).
  PublishQueue(size_t max_bytes, size_t max_jobs);
  // Runs what is still queued, then joins the thread.
  ~PublishQueue();
  PublishQueue(const PublishQueue&) = delete;
  PublishQueue& operator=(const PublishQueue&) = delete;

  // Queues a job of `bytes` bytes; a job larger than max_bytes waits until the queue is empty.
  void post(std::function<void()> job, size_t bytes);
  // Returns once every job posted before the call has run (a service answer or a callback then sees the
  // messages of every earlier step already sent, as when publishing was synchronous).
  void flush();
  // Jobs run so far (for tests and the log).
  size_t done() const;

 private:
  void loop();

  const size_t max_bytes_, max_jobs_;
  mutable std::mutex m_;
  std::condition_variable work_;  // the thread waits for a job
  std::condition_variable room_;  // post() and flush() wait for the thread
  std::deque<std::pair<std::function<void()>, size_t>> q_;
  size_t bytes_ = 0;     // [bytes] queued, the running job included
  size_t done_ = 0;
  bool running_ = false;  // a job is being run outside the lock
  bool idle_ = false;     // the thread waits on work_
  int waiters_ = 0;       // callers waiting on room_
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace car_ros
