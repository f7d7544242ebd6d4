// The PID of car's ros_control controllers (src/plugins/ros_control, control::Pid) against control_toolbox 1.19.0's
// rules (docs/COMPAT-control.md "control_toolbox"), values by hand: without antiwindup the integral winds up behind
// the clamped term; with it the integral itself is clamped; i_clamp_min and i_clamp_max take forced signs.
#include <gtest/gtest.h>

#include <vector>

#include "ros_control/controllers.hpp"

using car_sim::control::ParamReader;
using car_sim::control::Params;
using car_sim::control::Pid;

namespace {

// The commands for errors taken each over 1 s (derivative 0).
std::vector<double> run(Pid& pid, const std::vector<double>& errors) {
  std::vector<double> out;
  for (double e : errors) out.push_back(pid.compute(e, 0.0, 1.0));
  return out;
}

}  // namespace

TEST(ControlPid, WithoutAntiwindupTheIntegralWindsUpBehindTheClampedTerm) {
  Pid pid;
  pid.i = 1.0, pid.i_min = -1.0, pid.i_max = 1.0;
  // integral 1, 2, 3, 2, 1, 0 (s): the term leaves its bound 1 only when the integral is back at 0
  EXPECT_EQ((std::vector<double>{1, 1, 1, 1, 1, 0}), run(pid, {1, 1, 1, -1, -1, -1}));
}

TEST(ControlPid, AntiwindupClampsTheIntegralItself) {
  Pid pid;
  pid.i = 1.0, pid.i_min = -1.0, pid.i_max = 1.0, pid.antiwindup = true;
  // integral held at i_max / i = 1, so one step of -1 brings it to 0
  EXPECT_EQ((std::vector<double>{1, 1, 1, 0}), run(pid, {1, 1, 1, -1}));
}

TEST(ControlPid, ClampMinAndMaxOverrideIClampWithTheirSignsForced) {
  const Params params{{"pid/p", {"1"}}, {"pid/i_clamp", {"2"}}, {"pid/i_clamp_min", {"5"}},
                      {"pid/i_clamp_max", {"-4"}}};
  const Pid pid = Pid::from(ParamReader("c", params), "pid");
  // i_clamp_min 5 -> -5, i_clamp_max -4 -> 4 (Pid::init's std::abs)
  EXPECT_EQ(-5.0, pid.i_min);
  EXPECT_EQ(4.0, pid.i_max);
}

TEST(ControlPid, ErrorOnlyComputeDifferencesTheLastError) {
  Pid pid;
  pid.d = 1.0;
  // d only, dt 0.1 s: no last error at first (derivative 0), then (1.5 - 1) / 0.1 = 5; dt < 0 keeps the last
  // derivative, 5, and not the error (a following 2.5 at dt 0.1 is (2.5 - 1.5) / 0.1 = 10)
  EXPECT_EQ(0.0, pid.compute(1.0, 0.1));
  EXPECT_DOUBLE_EQ(5.0, pid.compute(1.5, 0.1));
  EXPECT_DOUBLE_EQ(5.0, pid.compute(2.0, -0.1));
  EXPECT_DOUBLE_EQ(10.0, pid.compute(2.5, 0.1));
}
