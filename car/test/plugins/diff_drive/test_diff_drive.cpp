// The diff-drive plug-in's plain maths.
#include <gtest/gtest.h>

#include <cmath>

#include "diff_drive/diff_drive.hpp"

using namespace car_sim;

TEST(DiffDrive, WheelSpeedsForTheSeedCommand) {
  double l = 0, r = 0;
  wheel_speeds(1.0, 1.0, 0.2, &l, &r);  // v - w sep/2, v + w sep/2
  EXPECT_DOUBLE_EQ(l, 0.9);
  EXPECT_DOUBLE_EQ(r, 1.1);
}

TEST(DiffDrive, RateLimitStepsTowardTarget) {
  EXPECT_DOUBLE_EQ(rate_limit(0.0, 1.0, 0.018), 0.018);  // 1.8 m/s^2 over 10 ms
  EXPECT_DOUBLE_EQ(rate_limit(0.99, 1.0, 0.018), 1.0);
  EXPECT_DOUBLE_EQ(rate_limit(0.0, -1.0, 0.018), -0.018);
  EXPECT_DOUBLE_EQ(rate_limit(0.3, -1.0, 0.0), -1.0);  // 0 = unlimited
}

TEST(DiffDrive, EncoderStraightAndTurn) {
  EncoderOdometry e;
  e.integrate(0.01, 0.01, 0.2, 0.01);
  EXPECT_DOUBLE_EQ(e.x, 0.01);
  EXPECT_DOUBLE_EQ(e.v, 1.0);
  EncoderOdometry t;
  t.integrate(-0.01, 0.01, 0.2, 0.01);  // turn on the spot: dtheta = sdiff / sep
  EXPECT_DOUBLE_EQ(t.theta, 0.1);
  EXPECT_DOUBLE_EQ(t.x, 0.0);
}

TEST(DiffDrive, EncoderKeepsTheSignWhenReversing) {
  EncoderOdometry e;
  e.integrate(-0.005, -0.005, 0.2, 0.01);
  EXPECT_DOUBLE_EQ(e.v, -0.5);  // upstream reports |v| here
}
