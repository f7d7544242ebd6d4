// PeriodGate: gazebo_ros's throttled publishers (gazebo_ros_range's OnNewLaserScans, camera_utils'
// PublishCameraInfo): send at sim time t when t - last >= period, last starting at 0; time going back sets last to
// t (docs/COMPAT-sensors.md "Throttled publishers"). Expected times worked out by hand from that rule.
#include <gtest/gtest.h>

#include <vector>

#include "car_sim/ports.hpp"

using car_sim::PeriodGate;

namespace {

constexpr int64_t kMs = 1000000;  // [ns]

// The times [ms] at which the gate lets a message through, of updates at `times` [ms].
std::vector<int64_t> passed(PeriodGate& g, const std::vector<int64_t>& times) {
  std::vector<int64_t> out;
  for (int64_t t : times)
    if (g.due(t * kMs)) out.push_back(t);
  return out;
}

}  // namespace

// A 10 Hz sensor (updates at 0, 100, ... ms) throttled to 4 Hz (0.25 s): 300 - 0 is the first difference >= 250,
// then 600 - 300 and 900 - 300 ... so 300, 600, 900. The update at time 0 does not go out.
TEST(PeriodGate, TheFirstMessageWaitsOnePeriodAfterTimeZero) {
  PeriodGate g(0.25);
  EXPECT_EQ(passed(g, {0, 100, 200, 300, 400, 500, 600, 700, 800, 900, 1000}), (std::vector<int64_t>{300, 600, 900}));
}

// After 900 went out, time goes back to 100 (reset_simulation): last becomes 100 and the next message waits until
// an update at least 250 ms later: 400, then 700.
TEST(PeriodGate, TimeGoingBackRestartsTheCountFromThere) {
  PeriodGate g(0.25);
  passed(g, {300, 600, 900});
  EXPECT_EQ(passed(g, {100, 200, 300, 400, 500, 600, 700}), (std::vector<int64_t>{400, 700}));
}

// Period 0 (updateRate 0 or absent): every update, time 0 and time going back included.
TEST(PeriodGate, ZeroPeriodSendsEveryUpdate) {
  PeriodGate g(0.0);
  EXPECT_EQ(passed(g, {0, 1, 2, 1, 0}), (std::vector<int64_t>{0, 1, 2, 1, 0}));
}

// 30 Hz: common::Time(1/30.0) is 0 s + round(33 333 333.33 ns) = 33 333 333 ns. At 1 ms steps the update at 33 ms is
// 333 333 ns short of it, the one at 34 ms past it: whole nanoseconds, no tolerance.
TEST(PeriodGate, ThePeriodIsRoundedToTheNanosecondAsCommonTime) {
  PeriodGate g(1.0 / 30.0);
  EXPECT_EQ(g.period_ns(), 33333333);
  EXPECT_FALSE(g.due(33 * kMs));
  EXPECT_TRUE(g.due(34 * kMs));
  // 1.5 s: floor 1 s, then 0.5 s
  EXPECT_EQ(PeriodGate(1.5).period_ns(), 1500000000);
}
