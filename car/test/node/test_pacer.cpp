// The node's real-time pacing (src/ros/pacer.hpp) on a made-up wall clock: 1 ms steps at rtf 1 and 0.5, a short
// delay made up, a long stall not.
#include <gtest/gtest.h>

#include <chrono>

#include "pacer.hpp"

using car_ros::Pacer;
using std::chrono::milliseconds;
using std::chrono::microseconds;

namespace {
const Pacer::clock::time_point kT0 = Pacer::clock::time_point() + std::chrono::hours(1);
const double kDt = 0.001;  // [s] per step
}  // namespace

// At rtf 1, the step after tick 100 + 25 is due 25 ms of wall time after the anchor at tick 100.
TEST(Pacer, StepIsDueItsSimTimeAfterTheAnchorAtRealTime) {
  Pacer p(milliseconds(10));
  p.restart(kT0, 100);
  EXPECT_EQ(p.due(125, kDt, 1.0, kT0 + milliseconds(3)), kT0 + milliseconds(25));
}

// At rtf 0.5 sim time runs at half the wall's: 25 steps of 1 ms take 50 ms.
TEST(Pacer, HalfRealTimeTakesTwiceTheWallTime) {
  Pacer p(milliseconds(10));
  p.restart(kT0, 0);
  EXPECT_EQ(p.due(25, kDt, 0.5, kT0), kT0 + milliseconds(50));
}

// A loop 4 ms behind (less than the 10 ms bound) keeps its schedule: the due time is in the past, so the next
// steps run at once until the 4 ms are made up.
TEST(Pacer, ShortDelayIsMadeUp) {
  Pacer p(milliseconds(10));
  p.restart(kT0, 0);
  EXPECT_EQ(p.due(20, kDt, 1.0, kT0 + milliseconds(24)), kT0 + milliseconds(20));
  EXPECT_EQ(p.dropped(), 0u);
}

// After a 300 ms stall the lost time is dropped: the next step is due now and the one after it 1 ms later, not
// 300 steps at once.
TEST(Pacer, LongStallIsNotMadeUp) {
  Pacer p(milliseconds(10));
  p.restart(kT0, 0);
  const auto now = kT0 + milliseconds(320);
  EXPECT_EQ(p.due(20, kDt, 1.0, now), now);
  EXPECT_EQ(p.due(21, kDt, 1.0, now + microseconds(100)), now + milliseconds(1));
  EXPECT_EQ(p.dropped(), 1u);
}

// The bound is strict: exactly max_lag behind still catches up.
TEST(Pacer, LagOfExactlyTheBoundIsMadeUp) {
  Pacer p(milliseconds(10));
  p.restart(kT0, 0);
  EXPECT_EQ(p.due(5, kDt, 1.0, kT0 + milliseconds(15)), kT0 + milliseconds(5));
}
