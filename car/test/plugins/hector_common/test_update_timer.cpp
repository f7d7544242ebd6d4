// hector's UpdateTimer (update_timer.h, docs/COMPAT-sensors.md "When, exactly"): a grid of absolute sim time,
// updatePeriod and updateOffset read as sdf::Time "SEC NSEC", and the warnings where that reading surprises.
#include <gtest/gtest.h>

#include "../range/ray_world.hpp"
#include "hector_gps/hector_gps.hpp"

using namespace car_sim;
using namespace car_sim::test_support;

namespace {

std::string with_gps(const std::string& keys) {
  std::string xml = cube_robot("");
  xml.insert(xml.rfind("</robot>"),
             "<gazebo><plugin name='gps' filename='libhector_gazebo_ros_gps.so'>" + keys + "</plugin></gazebo>");
  return xml;
}

// The ticks of the fixes of a GPS spawned after `before` steps, over ticks up to `last` (1 ms steps).
std::vector<uint64_t> fix_ticks(const std::string& keys, uint64_t before, uint64_t last = 1000) {
  World w(ray_world(""));
  w.step(before);
  w.spawn(load_urdf_string(with_gps(keys), "cube"), "cube", at(0, 0, 0.1));
  w.set_plugin_active("cube", "gps", true);
  w.step(last - before);
  std::vector<uint64_t> ticks;
  for (const GpsOut& f : w.take_outputs<GpsOut>()) ticks.push_back(f.tick);
  return ticks;
}

std::vector<Diagnostic> warnings(const std::string& keys, const std::string& key) {
  std::vector<Diagnostic> out;
  for (const Diagnostic& d : resolve_plugins(load_urdf_string(with_gps(keys), "cube")).diagnostics)
    if (d.element == "gazebo/plugin[gps]/" + key) out.push_back(d);
  return out;
}

std::vector<uint64_t> due_ticks(const Schedule& s, uint64_t last) {
  std::vector<uint64_t> ticks;
  for (uint64_t k = 1; k <= last; ++k)
    if (s.due(k)) ticks.push_back(k);
  return ticks;
}

}  // namespace

// 3 Hz at 1 ms: period common::Time(1/3).Double() = 0.333333333 s; fmod(t + 0.0005, period) < 0.001 holds at
// t = 0.333 (0.000166667), 0.667 (0.000833334) and 1.000 (0.000500001), not at 0.334 (0.001166667) or 0.666
// (0.333166667). Whole periods counted from tick 0 would be ticks ceil(1000 k / 3) = 334, 667, 1000.
TEST(HectorUpdateTimer, ThreeHertzUpdatesOnTheStepNearestEachThirdOfASecond) {
  const double period = common_time_double(common_time_ns(1.0 / 3.0));
  EXPECT_EQ(due_ticks(Schedule::absolute(period, 0, 0.001), 1000), (std::vector<uint64_t>{333, 667, 1000}));
}

// Period 0 (updateRate 0, IMU's and the magnetometer's default): every step.
TEST(HectorUpdateTimer, PeriodZeroIsEveryStep) {
  EXPECT_EQ(due_ticks(Schedule::absolute(0.0, 0, 0.001), 5).size(), 5u);
}

// A GPS (4 Hz) spawned at tick 123 updates at 0.25, 0.5, 0.75, 1.0 s of sim time, not 0.25 s after its spawn
// (373, 623, 873).
TEST(HectorUpdateTimer, AModelSpawnedLateUpdatesOnTheGridOfAbsoluteSimTime) {
  EXPECT_EQ(fix_ticks("", 123), (std::vector<uint64_t>{250, 500, 750, 1000}));
}

// updateOffset '0 100000000' (0.1 s) moves the grid: 0.1, 0.35, 0.6, 0.85 s.
TEST(HectorUpdateTimer, UpdateOffsetShiftsTheGrid) {
  EXPECT_EQ(fix_ticks("<updateOffset>0 100000000</updateOffset>", 0), (std::vector<uint64_t>{100, 350, 600, 850}));
}

// updatePeriod '0 200000000' is 0.2 s: 5 fixes in 1 s, and no warning.
TEST(HectorUpdateTimer, UpdatePeriodReadsSecondsAndNanoseconds) {
  EXPECT_EQ(fix_ticks("<updatePeriod>0 200000000</updatePeriod>", 0), (std::vector<uint64_t>{200, 400, 600, 800, 1000}));
  EXPECT_TRUE(warnings("<updatePeriod>0 200000000</updatePeriod>", "updatePeriod").empty());
}

// updatePeriod '2' is 2 s: one whole integer is the seconds.
TEST(HectorUpdateTimer, UpdatePeriodOfOneIntegerIsWholeSeconds) {
  EXPECT_EQ(fix_ticks("<updatePeriod>2</updatePeriod>", 0, 4000), (std::vector<uint64_t>{2000, 4000}));
}

// updatePeriod '0.25' reads as 0 s 0 ns (sdf::Time's integer read stops at the '.'), so every step, as upstream,
// with a warning that says so and what to write instead.
TEST(HectorUpdateTimer, DecimalUpdatePeriodIsZeroSecondsEveryStepAndWarned) {
  EXPECT_EQ(fix_ticks("<updatePeriod>0.25</updatePeriod>", 0, 10).size(), 10u);
  const auto ws = warnings("<updatePeriod>0.25</updatePeriod>", "updatePeriod");
  ASSERT_EQ(ws.size(), 1u);
  EXPECT_EQ(ws[0].message,
            "<updatePeriod> '0.25' is read as sdf::Time 'SEC NSEC' by hector's UpdateTimer: 0 s, so the plug-in "
            "updates every step; write <updateRate>4</updateRate> or '0 250000000'");
}

// updatePeriod '1.5' reads as 1 s: a fix every second, warned.
TEST(HectorUpdateTimer, DecimalUpdatePeriodKeepsOnlyItsWholeSeconds) {
  EXPECT_EQ(fix_ticks("<updatePeriod>1.5</updatePeriod>", 0, 3000), (std::vector<uint64_t>{1000, 2000, 3000}));
  const auto ws = warnings("<updatePeriod>1.5</updatePeriod>", "updatePeriod");
  ASSERT_EQ(ws.size(), 1u);
  EXPECT_EQ(ws[0].message,
            "<updatePeriod> '1.5' is read as sdf::Time 'SEC NSEC' by hector's UpdateTimer: 1 s; write "
            "<updateRate>0.666667</updateRate> or '1 500000000'");
}

TEST(HectorUpdateTimer, DecimalUpdateOffsetIsWarned) {
  const auto ws = warnings("<updateOffset>0.1</updateOffset>", "updateOffset");
  ASSERT_EQ(ws.size(), 1u);
  EXPECT_EQ(ws[0].message,
            "<updateOffset> '0.1' is read as sdf::Time 'SEC NSEC' by hector's UpdateTimer: 0 s; write '0 100000000'");
}

// A negative updateRate gives period 0 upstream (every step): warned, not refused.
TEST(HectorUpdateTimer, NegativeUpdateRateIsEveryStepAndWarned) {
  EXPECT_EQ(fix_ticks("<updateRate>-5</updateRate>", 0, 10).size(), 10u);
  const auto ws = warnings("<updateRate>-5</updateRate>", "updateRate");
  ASSERT_EQ(ws.size(), 1u);
  EXPECT_EQ(ws[0].message, "<updateRate> -5 is not > 0: the plug-in updates every step, as upstream");
}
