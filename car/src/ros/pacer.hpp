// Real-time pacing of the node's stepping loop at a real-time factor rtf > 0 (docs/COMPAT-dropins.md "Pacing").
// Steps keep a schedule from an anchor (wall time, tick): the step after tick t is due at
// anchor_wall + (t - anchor_tick) * dt / rtf, so sleep overshoot and short delays are made up and the mean rate is
// exact. A stall longer than max_lag (a busy machine, a debugger, SIGSTOP) is not made up: like Gazebo's
// World::Step, which paces each step from the previous one, the simulation goes on at rtf from where it is instead
// of running the lost time in one burst (which floods publisher queues: roscpp drops the oldest of a queue of 10
// while its poll thread waits for a CPU). No ROS headers.
#pragma once

#include <chrono>
#include <cstdint>

namespace car_ros {

class Pacer {
 public:
  using clock = std::chrono::steady_clock;

  // max_lag [wall time]: how far behind its schedule the loop may fall and still catch up.
  explicit Pacer(clock::duration max_lag) : max_lag_(max_lag) {}

  // Anchors the schedule: tick is the world's tick at wall time now (after a pause, a reset, a new rtf).
  void restart(clock::time_point now, uint64_t tick) {
    wall0_ = now;
    tick0_ = tick;
  }

  // When the step after `tick` may start [wall time], given dt [s of sim time per step] and rtf > 0. A schedule
  // more than max_lag behind `now` is dropped first (re-anchored at now, tick): the answer is then now.
  clock::time_point due(uint64_t tick, double dt, double rtf, clock::time_point now) {
    const double sim_elapsed = static_cast<double>(tick - tick0_) * dt;  // [s] since the anchor
    const clock::time_point at =
        wall0_ + std::chrono::duration_cast<clock::duration>(std::chrono::duration<double>(sim_elapsed / rtf));
    if (now - at > max_lag_) {
      restart(now, tick);
      ++dropped_;
      return now;
    }
    return at;
  }

  // Stalls dropped so far (for tests and the log).
  uint64_t dropped() const { return dropped_; }

 private:
  const clock::duration max_lag_;
  clock::time_point wall0_{};
  uint64_t tick0_ = 0;
  uint64_t dropped_ = 0;
};

}  // namespace car_ros
