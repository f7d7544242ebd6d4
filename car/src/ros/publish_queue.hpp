// The node's publishing thread: messages built on the stepping thread are serialised and written to their
// subscribers' sockets on a second thread, so the physics does not wait on send(2) (docs/COMPAT-dropins.md
// "Publishing thread"). Jobs run one at a time in the order they were posted, so every topic keeps its order and
// so does the node's output as a whole. No ROS headers: the jobs are plain callables.
#pragma once

#include <chrono>
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
  // At most max_bytes of messages [bytes, serialised size] or max_jobs jobs wait at once, besides the one being
  // sent: post() blocks beyond that (the simulation waits for its subscribers' sockets instead of queueing
  // without bound). The thread takes what is queued as one batch; its jobs count until the batch is done.
  // after_job: called on the thread after each job with its bytes (the node's gate on roscpp's queues), if set.
  PublishQueue(size_t max_bytes, size_t max_jobs, std::function<void(size_t)> after_job = {});
  // Runs what is still queued, then joins the thread.
  ~PublishQueue();
  PublishQueue(const PublishQueue&) = delete;
  PublishQueue& operator=(const PublishQueue&) = delete;

  // Queues a job of `bytes` bytes; a job larger than max_bytes waits until the queue is empty. Outside hold()
  // the thread is woken for it; inside, it waits for release() (or for a full queue, or flush()).
  void post(std::function<void()> job, size_t bytes);
  // hold() ... release(gap): the jobs posted in between wake the thread once, at release(), and only when `gap`
  // [wall time] has passed since the thread was last woken for held jobs; otherwise they wait for a later
  // release(), wake() or flush() (or a full queue). The node holds during a step's publishing and releases with
  // a gap of 1 ms: at rtf 0 the messages of some tens of steps cost one wake-up instead of one each.
  void hold();
  void release(std::chrono::steady_clock::duration gap = std::chrono::steady_clock::duration::zero());
  // Wakes the thread for held jobs now (before the node sleeps, so nothing waits on its sleep).
  void wake() { release(); }
  // Returns once every job posted before the call has run (a service answer or a callback then sees the
  // messages of every earlier step already sent, as when publishing was synchronous).
  void flush();
  // Jobs run so far (for tests and the log).
  size_t done() const;

 private:
  void loop();
  // Marks the posted jobs as woken for and wakes the thread if it sleeps; unlocks l (held on m_) first.
  void wake_thread(std::unique_lock<std::mutex>& l);

  const size_t max_bytes_, max_jobs_;
  mutable std::mutex m_;
  std::condition_variable work_;  // the thread waits for a job
  std::condition_variable room_;  // post() and flush() wait for the thread
  std::deque<std::pair<std::function<void()>, size_t>> q_;
  size_t bytes_ = 0;     // [bytes] queued, the running batch included
  size_t batch_jobs_ = 0;  // jobs in the batch being run
  size_t done_ = 0;
  bool running_ = false;  // a job is being run outside the lock
  bool idle_ = false;     // the thread waits on work_
  bool held_ = false;     // inside hold() ... release()
  bool unwoken_ = false;  // jobs were posted while held and the thread was not woken for them
  // long ago: the first release wakes whatever the gap
  std::chrono::steady_clock::time_point last_wake_ = std::chrono::steady_clock::now() - std::chrono::hours(24 * 365);
  int waiters_ = 0;       // callers waiting on room_
  bool stop_ = false;
  const std::function<void(size_t)> after_job_;
  std::thread thread_;
};

}  // namespace car_ros
