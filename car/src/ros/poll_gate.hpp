// A bound on what waits inside roscpp. roscpp hands a published message to its subscribers' queues on its poll
// thread; until then the message waits in the topic's publish queue (ros::Publication::publish_queue_), which has
// no bound. At rtf 0 the publishing thread hands over 10 MB clouds faster than a busy machine schedules the poll
// thread, and they piled up there (heaptrack in the soak: 14 clouds, 138 MB at once; docs/RELIABILITY.md "The
// two-hour soak"). The gate: once max_bytes [bytes, serialised] have been handed to roscpp since the poll thread's
// last round, the publishing thread waits for its next round. Its listeners run after
// TopicManager::processPublishQueues, which empties every publish queue into the subscriber links (those keep at
// most their queue size and drop the oldest, as upstream), so at most about max_bytes wait there.
#pragma once

#include <ros/poll_manager.h>

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <mutex>

namespace car_ros {

class PollGate {
 public:
  explicit PollGate(size_t max_bytes) : max_bytes_(max_bytes) {}
  ~PollGate() { round_.disconnect(); }
  PollGate(const PollGate&) = delete;
  PollGate& operator=(const PollGate&) = delete;

  // Listens to roscpp's poll thread (after ros::start: its TopicManager listens first, so it runs first).
  void connect() { round_ = ros::PollManager::instance()->addPollThreadListener([this] { on_round(); }); }

  // The publishing thread, after publish() handed roscpp `bytes`. The wait is bounded (1 s of wall time): a poll
  // thread that has stopped (shutdown) never holds the node.
  void published(size_t bytes) {
    std::unique_lock<std::mutex> l(m_);
    handed_ += bytes;
    if (handed_ <= max_bytes_ || !round_.connected()) return;
    const uint64_t seen = rounds_;
    cv_.wait_for(l, std::chrono::seconds(1), [&] { return rounds_ != seen; });
  }

  // [bytes] handed to roscpp since the poll thread's last round.
  size_t handed() const {
    std::lock_guard<std::mutex> l(m_);
    return handed_;
  }
  // Rounds of the poll thread so far.
  uint64_t rounds() const {
    std::lock_guard<std::mutex> l(m_);
    return rounds_;
  }

  // roscpp's poll thread, once per round, after the publish queues were emptied (tests call it as that thread).
  void on_round() {
    {
      std::lock_guard<std::mutex> l(m_);
      handed_ = 0;
      ++rounds_;
    }
    cv_.notify_all();
  }

 private:

  const size_t max_bytes_;
  mutable std::mutex m_;
  std::condition_variable cv_;
  size_t handed_ = 0;  // [bytes] handed to roscpp since the poll thread's last round
  uint64_t rounds_ = 0;
  boost::signals2::connection round_;
};

}  // namespace car_ros
