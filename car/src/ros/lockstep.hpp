// Lockstep with a node under test (docs/COMPAT-dropins.md "Lockstep"; car only, off unless ~lockstep is set):
// after a step that published a TRIGGER topic to someone, the node steps no further until a message on the
// pair's RESPONSE topic has arrived, or a wall-clock guard (~lockstep_timeout) ran out. Generic by message type:
// RESPONSE is taken as topic_tools::ShapeShifter (never deserialised); nothing here names a plug-in kind.
#pragma once

#include <ros/ros.h>
#include <topic_tools/shape_shifter.h>

#include <chrono>
#include <string>
#include <vector>

namespace car_ros {

class Lockstep {
 public:
  using clock = std::chrono::steady_clock;

  // Reads ~lockstep and ~lockstep_timeout from pnh, resolves the names with nh and subscribes to the responses.
  // Malformed entries are left out with a warning. Returns whether any pair is active.
  bool configure(ros::NodeHandle& nh, ros::NodeHandle& pnh);
  bool enabled() const { return !pairs_.empty(); }

  // A message was posted on `topic` (resolved name) with `subscribers` subscribers, during the current step.
  void published(const std::string& topic, uint32_t subscribers);
  // Whether a trigger fired during the step just done (the caller then flushes the publishing thread and calls
  // begin()).
  bool fired() const { return fired_; }
  // The step's triggers were handed to the transport: their pairs now wait for an answer. stamp: [s] sim time.
  void begin(clock::time_point now, double stamp);
  // Whether some pair still waits (no answer and no time out yet). A time out warns and ends that pair's wait.
  bool waiting(clock::time_point now);
  // The wait goes on from now (after a pause: time paused does not count against the guard).
  void resume(clock::time_point now) { since_ = now; }
  // reset_simulation: every wait ends.
  void reset();
  // Subscribes to the responses again (new subscriber objects first, then the old ones go), so the node's
  // callback for each answer is queued after every other subscriber's callback of that topic in this node (roscpp
  // queues a message's callbacks in the order they subscribed): after a spawn, whose plug-ins subscribe after
  // ours. Call it between steps with no wait pending (a latched answer re-delivered then runs before any wait).
  void resubscribe();

 private:
  struct Pair {
    std::string trigger, response;  // resolved topic names
    ros::Subscriber sub;
    uint64_t answers = 0;  // messages on response so far
    uint64_t answers_at_begin = 0;
    bool fired = false;      // trigger published in the current step
    bool pending = false;    // waits for an answer
    bool suspended = false;  // timed out: no waits until the next answer
    double trigger_stamp = 0.0;  // [s] sim time of the trigger waited for
  };
  void subscribe(Pair& p);
  void on_answer(size_t i);

  std::vector<Pair> pairs_;
  ros::NodeHandle nh_;
  double timeout_s_ = 5.0;  // [s] wall time
  bool fired_ = false;
  bool resubscribe_due_ = false;  // asked for during a wait
  clock::time_point since_{};  // wall time the current wait began
};

}  // namespace car_ros
