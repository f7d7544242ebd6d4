// Schedule::update_clock: gazebo_ros's UpdateChild rule (UpdateClock; docs/COMPAT-plugins.md "the update and the
// wheel ramp"): the call at tick k + 1 (which reads tick k's state) updates when (t - last).Double() > 1 / rate,
// and then last += common::Time(1 / rate).
#include <gtest/gtest.h>

#include <vector>

#include "car_sim/plugin.hpp"

using car_sim::Schedule;

namespace {

std::vector<uint64_t> due_ticks(Schedule s, uint64_t from, uint64_t to) {
  std::vector<uint64_t> ticks;
  for (uint64_t k = from; k <= to; ++k)
    if (s.due(k)) {
      ticks.push_back(k);
      s.advance(k);
    }
  return ticks;
}

}  // namespace

// 30 Hz at 1 ms: period 1/30 s, last += 33 333 333 ns. Update 1: (k + 1) ms > 33.333 ms, k = 33. Update 2:
// (k + 1) ms - 33.333333 ms > 33.333 ms, k + 1 = 67. Update 3: 100 ms - 66.666666 ms = 33.333334 ms > 33.3333333 ms,
// k = 99; then 133 (134 - 99.999999 > 33.3333333), 166, 199. Whole periods counted from tick 0 would be the ticks
// ceil(100 k / 3) = 34, 67, 100, ...: one step later.
TEST(UpdateClockSchedule, ThirtyHertzUpdatesAtTheFirstCallPastEachPeriod) {
  EXPECT_EQ(due_ticks(Schedule::update_clock(30, 0.001, 0), 1, 200), (std::vector<uint64_t>{33, 66, 99, 133, 166, 199}));
}

// 100 Hz: t - last is exactly 0.01 at tick k = 9 (not > 0.01), so ticks 10, 20, 30, ... as the counting schedule.
TEST(UpdateClockSchedule, AWholeNumberOfStepsUpdatesEveryPeriod) {
  EXPECT_EQ(due_ticks(Schedule::update_clock(100, 0.001, 0), 1, 50), (std::vector<uint64_t>{10, 20, 30, 40, 50}));
}

// A restart (a world reset at tick 1000) starts last at the reset's time: 1033, 1066, 1099.
TEST(UpdateClockSchedule, ARestartStartsTheClockAtItsTick) {
  Schedule s = Schedule::update_clock(30, 0.001, 0);
  s.restart(1000);
  EXPECT_EQ(due_ticks(s, 1001, 1100), (std::vector<uint64_t>{1033, 1066, 1099}));
}

// updateRate 0: period 0, and t - last > 0 at every call.
TEST(UpdateClockSchedule, RateZeroUpdatesEveryStep) {
  EXPECT_EQ(due_ticks(Schedule::update_clock(0, 0.001, 0), 1, 4), (std::vector<uint64_t>{1, 2, 3, 4}));
}

// Schedule::since_last, the rate control of p3d, the imu model plug-in and ft_sensor: a call at tick k's time t
// publishes unless (t - last).Double() < 1.0 / rate, then last = t. At 30 Hz and 1 ms 0.033 < 0.0333 holds and 0.034
// does not: every 34 ms (29.4 Hz, not 30).
TEST(SinceLastSchedule, ThirtyHertzPublishesEveryThirtyFourMilliseconds) {
  EXPECT_EQ(due_ticks(Schedule::since_last(30, 0.001, 0, false), 1, 200),
            (std::vector<uint64_t>{34, 68, 102, 136, 170}));
}

// 50 Hz: 20 000 000 ns as a double is 0.02 == 1.0 / 50, not less: every 20 ms.
TEST(SinceLastSchedule, FiftyHertzPublishesEveryTwentyMilliseconds) {
  EXPECT_EQ(due_ticks(Schedule::since_last(50, 0.001, 0, false), 1, 80), (std::vector<uint64_t>{20, 40, 60, 80}));
}

// from_zero (ft_sensor's last_time_ of 0): started at tick 500 at 10 Hz, the first call is already 0.501 s past 0.
TEST(SinceLastSchedule, FromZeroPublishesAtTheFirstCallAfterALateStart) {
  EXPECT_EQ(due_ticks(Schedule::since_last(10, 0.001, 500, true), 501, 750), (std::vector<uint64_t>{501, 601, 701}));
}

// A rate of 1e-300 Hz: its period (1e300 s) saturates at 4.6e18 ns instead of an undefined conversion, and the
// clock never comes due.
TEST(UpdateClockSchedule, ATinyRateNeverComesDue) {
  EXPECT_EQ(car_sim::common_time_ns(1e300), 4600000000000000000);
  EXPECT_EQ(car_sim::common_time_ns(-1e300), -4600000000000000000);
  EXPECT_TRUE(due_ticks(Schedule::update_clock(1e-300, 0.001, 0), 1, 1000).empty());
}
