// The diff-drive plug-in's plain maths.
#include <gtest/gtest.h>

#include <cmath>

#include "diff_drive/diff_drive.hpp"
#include "seed_car.hpp"

using namespace car_sim;

TEST(DiffDrive, WheelSpeedsForTheSeedCommand) {
  double l = 0, r = 0;
  wheel_speeds(1.0, 1.0, 0.2, &l, &r);  // v - w sep/2, v + w sep/2
  EXPECT_DOUBLE_EQ(l, 0.9);
  EXPECT_DOUBLE_EQ(r, 1.1);
}

// The seed's drive (wheelAcceleration 1.8 m/s^2, updateRate 100 Hz) at 1 ms: upstream's seconds_since_last_update
// is 0.011 s (the period and one step), so an update adds at most 1.8 * 0.011 = 0.0198 m/s.
TEST(DiffDriveRamp, FromRestEachWheelGainsAccelTimesTheSecondsSinceTheLastUpdate) {
  WheelRamp r;
  const double target[2] = {0.9, 1.1}, current[2] = {0.0, 0.0};
  double out[2];
  r.update(target, current, 1.8, 0.011, out);
  EXPECT_DOUBLE_EQ(out[0], 1.8 * 0.011);
  EXPECT_DOUBLE_EQ(out[1], 1.8 * 0.011);
}

// One wheel within 0.01 m/s of its target ends the ramp of both (Noetic's ||): the right wheel jumps from 0.95 to
// 1.1, and the commanded speeds stay where the ramp left them.
TEST(DiffDriveRamp, OneWheelNearItsTargetSetsBothAtOnce) {
  WheelRamp r;
  r.instr[0] = 0.8915;
  r.instr[1] = 0.95;
  const double target[2] = {0.9, 1.1}, current[2] = {0.8915, 0.95};
  double out[2];
  r.update(target, current, 1.8, 0.011, out);
  EXPECT_EQ(out[0], 0.9);
  EXPECT_EQ(out[1], 1.1);
  EXPECT_EQ(r.instr[0], 0.8915);
  EXPECT_EQ(r.instr[1], 0.95);
}

// The step follows the wheel's actual speed, not the commanded one: a blocked wheel (current 0) winds the command
// up by 0.0198 m/s every update, 3 updates 0.0594 m/s, as upstream.
TEST(DiffDriveRamp, ABlockedWheelWindsTheCommandUp) {
  WheelRamp r;
  const double target[2] = {0.5, 0.5}, current[2] = {0.0, 0.0};
  double out[2];
  for (int i = 0; i < 3; ++i) r.update(target, current, 1.8, 0.011, out);
  EXPECT_NEAR(out[0], 3 * 0.0198, 1e-15);
  EXPECT_NEAR(out[1], 3 * 0.0198, 1e-15);
}

// Slowing down steps down by the same amount; a difference smaller than a step is taken whole.
TEST(DiffDriveRamp, StepsDownAndTakesASmallDifferenceWhole) {
  WheelRamp r;
  r.instr[0] = r.instr[1] = 0.5;
  const double target[2] = {0.0, 0.49}, current[2] = {0.5, 0.5};
  double out[2];
  r.update(target, current, 1.8, 0.011, out);
  EXPECT_DOUBLE_EQ(out[0], 0.5 - 0.0198);
  // |0.49 - 0.5| = 0.01 is not below 0.01: still the ramp, and the difference (-0.01) is within the step
  EXPECT_DOUBLE_EQ(out[1], 0.49);
}

// wheelAcceleration 0: the targets at once.
TEST(DiffDriveRamp, ZeroAccelerationSetsTheTargets) {
  WheelRamp r;
  const double target[2] = {-1.0, 1.0}, current[2] = {0.3, 0.3};
  double out[2];
  r.update(target, current, 0.0, 0.011, out);
  EXPECT_EQ(out[0], -1.0);
  EXPECT_EQ(out[1], 1.0);
}

// common::Time's arithmetic: 11 ms is 0.011 as Double(), and 10 ms equals the double 1/100 (so `> period` is false).
TEST(DiffDriveRamp, CommonTimeDoubleOfTheSeedsPeriod) {
  EXPECT_EQ(common_time_double(11000000), 11000000 * 1e-9);
  EXPECT_EQ(common_time_double(10000000), 1.0 / 100.0);
  EXPECT_EQ(common_time_ns(1.0 / 100.0), 10000000);
  EXPECT_EQ(common_time_double(1500000000), 1.5);
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

// The seed car's drive at 30 Hz follows UpdateChild's rule (test_update_clock.cpp): odometry at ticks 33, 66, 99,
// 133, 166, 199.
TEST(DiffDrive, ThirtyHertzUpdatesByUpdateChildsClock) {
  std::string xml = test_support::car_xml(false);
  xml.replace(xml.find("<updateRate>100.0</updateRate>"), 30, "<updateRate>30</updateRate>");
  World w(empty_world());
  w.spawn(load_urdf_string(xml, "car"), "mycar", at(0, 0, 0));
  w.step(200);
  std::vector<uint64_t> ticks;
  for (const auto& o : w.take_outputs())
    if (dynamic_cast<const OdometryOut*>(o.get())) ticks.push_back(o->tick);
  EXPECT_EQ(ticks, (std::vector<uint64_t>{33, 66, 99, 133, 166, 199}));
}

namespace {

// The seed car with `keys` added to its diff drive plug-in.
std::unique_ptr<World> car_with_drive_keys(const std::string& keys) {
  std::string xml = test_support::car_xml(false);
  xml.insert(xml.find("<updateRate>100.0</updateRate>"), keys);
  auto w = std::make_unique<World>(empty_world());
  w->spawn(load_urdf_string(xml, "car"), "mycar", at(0, 0, 0));
  return w;
}

}  // namespace

// publishTf false silences the odometry (message and TF) only: upstream's three checks in UpdateChild are
// independent, so the wheels' joint states still go out.
TEST(DiffDrive, PublishTfFalseKeepsTheWheelJointStates) {
  auto w = car_with_drive_keys("<publishTf>false</publishTf><publishWheelJointState>true</publishWheelJointState>");
  const PluginInfo p = w->plugins()[0];
  ASSERT_GE(p.outputs.size(), 2u);
  EXPECT_EQ(p.outputs[0].topic, "");
  EXPECT_EQ(p.outputs[0].tf, TfOrder::None);
  EXPECT_EQ(p.outputs[1].type, sample_type<JointStatesSample>());
  w->step(100);
  const auto outs = w->take_outputs();
  ASSERT_FALSE(outs.empty());
  EXPECT_TRUE(outs.back()->sample_of<JointStatesSample>());
}

// An odometrySource upstream's options map lacks is warned, and the default kept: world odometry.
TEST(DiffDrive, UnknownOdometrySourceIsWorldWithAWarning) {
  auto w = car_with_drive_keys("<odometrySource>1</odometrySource>");
  std::vector<std::string> messages;
  for (const Diagnostic& d : w->robot("mycar").config.diagnostics)
    if (d.code == "odometry-source") messages.push_back(d.message);
  EXPECT_EQ(messages, std::vector<std::string>{"<odometrySource> no matching key to 1: world odometry, as upstream"});
}
