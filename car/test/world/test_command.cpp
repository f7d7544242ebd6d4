// World::command, the one entry for commands into the core (typed input ports), on the seed car's diff drive:
// its port resolved from the schema, the one finite check, and the errors for a wrong port or type.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "seed_car.hpp"

using namespace car_sim;
using namespace car_sim::test_support;

namespace {

const char* kDrive = "differential_drive_controller";

Twist twist(double vx, double vy, double wz) {
  Twist t;
  t.linear = Eigen::Vector3d(vx, vy, 0.0);
  t.angular = Eigen::Vector3d(0.0, 0.0, wz);
  return t;
}

std::string thrown(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(nothing thrown)";
}

}  // namespace

// commandTopic cmd_vel under <robotNamespace>/</robotNamespace> (global), queue 10 as gazebo_ros_diff_drive,
// reading linear.x and angular.z only
TEST(WorldCommand, DiffDrivePortIsResolvedFromItsSchema) {
  auto w = world_with_car(false);
  const InputPort* port = nullptr;
  for (const auto& p : w->plugins())
    if (p.config.name == kDrive) {
      ASSERT_EQ(p.inputs.size(), 1u);
      port = &p.inputs[0];
      EXPECT_EQ(port->name, "cmd_vel");
      EXPECT_EQ(port->type, InputType::Twist);
      EXPECT_EQ(port->topic, "/cmd_vel");
      EXPECT_EQ(port->queue, 10u);
      EXPECT_EQ(port->axes, kLinearX | kAngularZ);
    }
  EXPECT_NE(port, nullptr);
}

TEST(WorldCommand, NonFiniteTwistIsRejectedWithItsValue) {
  auto w = world_with_car(false);
  const CommandResult r = w->command("mycar", kDrive, "cmd_vel", twist(std::nan(""), 0.0, 0.0));
  EXPECT_FALSE(r.accepted);
  EXPECT_EQ(r.reason, "a non-finite value (linear.x nan)");
}

// a rejected value does not reach the drive: the command before it holds (0.2 m/s for 1 s: about 0.2 m)
TEST(WorldCommand, RejectedTwistLeavesTheLastCommand) {
  auto w = world_with_car(false);
  w->step(200);
  const double x0 = w->model_state("mycar").pose.translation().x();
  ASSERT_TRUE(w->command("mycar", kDrive, "cmd_vel", twist(0.2, 0.0, 0.0)).accepted);
  ASSERT_FALSE(w->command("mycar", kDrive, "cmd_vel", twist(0.0, 0.0, INFINITY)).accepted);
  w->step(1000);
  EXPECT_NEAR(w->model_state("mycar").pose.translation().x() - x0, 0.2, 0.03);
}

// linear.y is not the diff drive's: a NaN there is dropped with it, and the rest goes through
TEST(WorldCommand, ComponentsThePortDoesNotReadAreDropped) {
  auto w = world_with_car(false);
  EXPECT_TRUE(w->command("mycar", kDrive, "cmd_vel", twist(0.2, std::nan(""), 0.0)).accepted);
}

// the same twist through command() and through set_cmd_vel() drives the car bit for bit alike
TEST(WorldCommand, CommandDrivesAsSetCmdVel) {
  auto a = world_with_car(false);
  auto b = world_with_car(false);
  a->command("mycar", kDrive, "cmd_vel", twist(0.2, 0.0, 0.5));
  b->set_cmd_vel("mycar", 0.2, 0.5);
  a->step(500);
  b->step(500);
  EXPECT_TRUE(a->model_state("mycar").pose.matrix() == b->model_state("mycar").pose.matrix());
  EXPECT_GT(a->model_state("mycar").pose.translation().norm(), 0.05);
}

TEST(WorldCommand, ValueOfAnotherTypeThrows) {
  auto w = world_with_car(false);
  EXPECT_EQ(thrown([&] { w->command("mycar", kDrive, "cmd_vel", Wrench()); }),
            "input 'cmd_vel' of plug-in 'differential_drive_controller' takes a cmd_vel");
}

TEST(WorldCommand, UnknownPortThrows) {
  auto w = world_with_car(false);
  EXPECT_EQ(thrown([&] { w->command("mycar", kDrive, "odom", Twist()); }),
            "plug-in 'differential_drive_controller' of robot 'mycar' has no input 'odom'");
}

TEST(WorldCommand, UnknownPluginThrows) {
  auto w = world_with_car(false);
  EXPECT_EQ(thrown([&] { w->command("mycar", "nope", "cmd_vel", Twist()); }), "robot 'mycar' has no plug-in 'nope'");
}
