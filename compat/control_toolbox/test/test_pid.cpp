// control_toolbox::Pid's arithmetic against values worked out by hand from upstream's rules (control_toolbox
// 1.19.0, src/pid.cpp): command = p e + i_term + d de/dt; without antiwindup the integral winds up behind the clamped
// term, with it the integral itself is clamped; reset() differentiates the next error from 0. No ROS master.
#include <control_toolbox/pid.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

using control_toolbox::Pid;

namespace {

// The commands for errors taken each over dt.
std::vector<double> run(Pid& pid, const std::vector<double>& errors, double dt) {
  std::vector<double> out;
  for (double e : errors) out.push_back(pid.computeCommand(e, ros::Duration(dt)));
  return out;
}

}  // namespace

TEST(Pid, ProportionalIsPTimesTheError) {
  Pid pid(2.0, 0.0, 0.0, 0.0, 0.0);
  // 2 * 0.5
  EXPECT_DOUBLE_EQ(1.0, pid.computeCommand(0.5, 0.0, ros::Duration(0.1)));
}

TEST(Pid, WithoutAntiwindupTheIntegralWindsUpBehindTheClampedTerm) {
  Pid pid(0.0, 1.0, 0.0, 1.0, -1.0, false);
  // integral 1, 2, 3, 2, 1, 0 (s): the term 1 * integral clamped to [-1, 1], so it leaves 1 only when the
  // integral is back below 1, three steps after the error turned
  EXPECT_EQ((std::vector<double>{1, 1, 1, 1, 1, 0}), run(pid, {1, 1, 1, -1, -1, -1}, 1.0));
}

TEST(Pid, AntiwindupClampsTheIntegralItself) {
  Pid pid(0.0, 1.0, 0.0, 1.0, -1.0, true);
  // integral 1, 1 (clamped to i_max / i = 1), 1, then 0 after one step of -1
  EXPECT_EQ((std::vector<double>{1, 1, 1, 0}), run(pid, {1, 1, 1, -1}, 1.0));
}

TEST(Pid, AntiwindupWithANegativeIGainOrdersTheBounds) {
  Pid pid(0.0, -2.0, 0.0, 1.0, -1.0, true);
  // the integral within [min(-1/-2, 1/-2), max(...)] = [-0.5, 0.5]: 0.5, 0.5, -0.5; the term -2 * integral
  EXPECT_EQ((std::vector<double>{-1, -1, 1}), run(pid, {1, 1, -1}, 1.0));
}

TEST(Pid, CrossedBoundsGiveTheUpperOneWhenAboveIt) {
  // i_max -1 below i_min 1 (a user's mistake): the term 5 is not below 1, and above -1, so -1 (boost's clamp)
  Pid pid(0.0, 1.0, 0.0, -1.0, 1.0);
  EXPECT_DOUBLE_EQ(-1.0, pid.computeCommand(5.0, 0.0, ros::Duration(1.0)));
}

TEST(Pid, TheFirstDerivativeAfterResetIsTheErrorOverDt) {
  Pid pid(0.0, 0.0, 1.0, 0.0, 0.0);
  // (0.5 - 0) / 0.1, (0.5 - 0.5) / 0.1, (0.3 - 0.5) / 0.1
  const std::vector<double> got = run(pid, {0.5, 0.5, 0.3}, 0.1);
  EXPECT_NEAR(5.0, got[0], 1e-12);
  EXPECT_NEAR(0.0, got[1], 1e-12);
  EXPECT_NEAR(-2.0, got[2], 1e-12);
}

TEST(Pid, ResetWithADErrorUsesItForTheNextCommand) {
  Pid pid(0.0, 0.0, 1.0, 0.0, 0.0);
  pid.reset(2.0, 0.0);
  // the given derivative 2, then (0.7 - 0.5) / 0.1 = 2 from the error it kept
  const std::vector<double> got = run(pid, {0.5, 0.7}, 0.1);
  EXPECT_DOUBLE_EQ(2.0, got[0]);
  EXPECT_NEAR(2.0, got[1], 1e-12);
}

TEST(Pid, ResetWithAnIErrorStartsTheIntegralThere) {
  Pid pid(0.0, 1.0, 0.0, 10.0, -10.0);
  pid.reset(0.0, 3.0);
  // 3 + 1 * 1 s
  EXPECT_DOUBLE_EQ(4.0, pid.computeCommand(1.0, ros::Duration(1.0)));
}

TEST(Pid, ZeroDtAndNonFiniteErrorsGiveZeroAndKeepTheIntegral) {
  Pid pid(1.0, 1.0, 0.0, 10.0, -10.0);
  EXPECT_DOUBLE_EQ(2.0, pid.computeCommand(1.0, ros::Duration(1.0)));  // p 1 + integral 1
  EXPECT_DOUBLE_EQ(0.0, pid.computeCommand(1.0, ros::Duration(0.0)));
  EXPECT_DOUBLE_EQ(0.0, pid.computeCommand(std::numeric_limits<double>::quiet_NaN(), ros::Duration(1.0)));
  EXPECT_DOUBLE_EQ(0.0, pid.computeCommand(1.0, std::numeric_limits<double>::infinity(), ros::Duration(1.0)));
  EXPECT_DOUBLE_EQ(3.0, pid.computeCommand(1.0, ros::Duration(1.0)));  // p 1 + integral 2
}

TEST(Pid, UpdatePidIsTheNegativeCommand) {
  Pid pid(2.0, 0.0, 0.0, 0.0, 0.0);
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
  EXPECT_DOUBLE_EQ(-1.0, pid.updatePid(0.5, 0.0, ros::Duration(0.1)));
#pragma GCC diagnostic pop
}

TEST(Pid, ACopyTakesTheGainsAndStartsReset) {
  Pid a(1.0, 1.0, 0.0, 10.0, -10.0, true);
  a.computeCommand(1.0, 0.0, ros::Duration(1.0));
  Pid b(a);
  // b's integral starts at 0: p 1 + integral 1
  EXPECT_DOUBLE_EQ(2.0, b.computeCommand(1.0, 0.0, ros::Duration(1.0)));
  double p, i, d, i_max, i_min;
  bool antiwindup;
  b.getGains(p, i, d, i_max, i_min, antiwindup);
  EXPECT_EQ((std::vector<double>{1, 1, 0, 10, -10}), (std::vector<double>{p, i, d, i_max, i_min}));
  EXPECT_TRUE(antiwindup);
}

TEST(Pid, CurrentErrorsAreTheLastCommandsOnes) {
  Pid pid(1.0, 1.0, 1.0, 10.0, -10.0);
  pid.computeCommand(0.5, 0.25, ros::Duration(2.0));
  double pe, ie, de;
  pid.getCurrentPIDErrors(&pe, &ie, &de);
  // error 0.5, integral 0.5 * 2 s, derivative as given; command 0.5 + 1 + 0.25
  EXPECT_EQ((std::vector<double>{0.5, 1.0, 0.25}), (std::vector<double>{pe, ie, de}));
  EXPECT_DOUBLE_EQ(1.75, pid.getCurrentCmd());
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
