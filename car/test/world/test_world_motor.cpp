// World's ODE joint motor (set_joint_motor: Gazebo's Joint::SetParam "vel"/"fmax") and gravity mode
// (set_link_gravity: Gazebo's Link::SetGravityMode). Values worked out by hand; dt = 0.001 s.
//
// The puck: a 2 kg body (Izz 0.5 kg m^2) and a wheel (Izz 0.5) on a continuous joint about z through both coms,
// floating without gravity. A joint torque tau turns the wheel at tau/0.5 and the body at -tau/0.5, so the joint's
// rate changes at tau (1/0.5 + 1/0.5) = 4 tau [rad/s^2]: the joint's effective inertia is 0.25 kg m^2.
#include <gtest/gtest.h>

#include <cmath>

#include "car_sim/world.hpp"

using namespace car_sim;

namespace {

const char* kPuck = R"(<?xml version="1.0"?>
<robot name="puck">
  <link name="body">
    <inertial><mass value="2"/><inertia ixx="0.5" iyy="0.5" izz="0.5" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  </link>
  <link name="wheel">
    <inertial><mass value="1"/><inertia ixx="0.5" iyy="0.5" izz="0.5" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><cylinder radius="0.1" length="0.05"/></geometry></collision>
  </link>
  <joint name="axle" type="continuous"><parent link="body"/><child link="wheel"/><origin xyz="0 0 1"/>
    <axis xyz="0 0 1"/><limit effort="0.5" velocity="1"/></joint>
</robot>)";

const char* kBox = R"(<?xml version="1.0"?>
<robot name="box">
  <link name="body">
    <inertial><mass value="2"/><inertia ixx="0.5" iyy="0.5" izz="0.5" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  </link>
</robot>)";

// A robot named "p" at (0, 0, 5) in an empty world with gravity g [m/s^2] along -z.
std::unique_ptr<World> at_five(const char* urdf, double g) {
  auto w = std::make_unique<World>(empty_world());
  w->set_gravity(Eigen::Vector3d(0, 0, -g));
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(0, 0, 5);
  w->spawn(load_urdf_string(urdf, "p"), "p", pose);
  return w;
}

const LinkRef kBody{"p", "body", true};

}  // namespace

// 2 rad/s from rest needs 2 x 0.25 / 0.001 = 500 N m for one step; 1000 N m is enough: there after one step.
TEST(WorldJointMotor, ReachesTheVelocityInOneStepWhenTheEffortSuffices) {
  auto w = at_five(kPuck, 0.0);
  w->set_joint_motor("p", "axle", {2.0, 1000.0});
  w->step();
  EXPECT_NEAR(w->joint_velocity("p", "axle"), 2.0, 1e-9);
}

// 0.1 N m is far too little for 100 rad/s: the joint accelerates at 4 x 0.1 = 0.4 rad/s^2, 0.4 rad/s after 1 s.
TEST(WorldJointMotor, WithTooLittleEffortAcceleratesAtMaxEffortOverInertia) {
  auto w = at_five(kPuck, 0.0);
  w->set_joint_motor("p", "axle", {100.0, 0.1});
  w->step();
  EXPECT_NEAR(w->joint_velocity("p", "axle"), 0.4 * 0.001, 1e-12);
  w->step(999);
  EXPECT_NEAR(w->joint_velocity("p", "axle"), 0.4, 1e-9);
}

// ODE's motor knows neither <limit effort> (0.5 N m) nor <limit velocity> (1 rad/s): 2 N m gives 4 x 2 x 0.001 =
// 0.008 rad/s in one step, and 1000 N m reaches 3 rad/s.
TEST(WorldJointMotor, IsNotCappedByTheJointsLimits) {
  auto w = at_five(kPuck, 0.0);
  w->set_joint_motor("p", "axle", {100.0, 2.0});
  w->step();
  EXPECT_NEAR(w->joint_velocity("p", "axle"), 0.008, 1e-12);
  w->set_joint_motor("p", "axle", {3.0, 1000.0});
  w->step();
  EXPECT_NEAR(w->joint_velocity("p", "axle"), 3.0, 1e-9);
}

// Max effort 0 is off: a joint set turning at 1 rad/s keeps turning, 1 rad in 1 s.
TEST(WorldJointMotor, ZeroMaxEffortIsOff) {
  auto w = at_five(kPuck, 0.0);
  w->set_joint_motor("p", "axle", {5.0, 0.0});
  w->set_joint_velocity("p", "axle", 1.0);
  w->step(1000);
  EXPECT_NEAR(w->joint_velocity("p", "axle"), 1.0, 1e-12);
  EXPECT_NEAR(w->joint_position("p", "axle"), 1.0, 1e-9);
}

// A motor holding 0 rad/s against a 0.3 N m effort (within its 0.4 N m): the joint stays still.
TEST(WorldJointMotor, HoldsItsVelocityAgainstAnEffortWithinItsCap) {
  auto w = at_five(kPuck, 0.0);
  w->set_joint_motor("p", "axle", {0.0, 0.4});
  w->add_step_hook(World::StepPhase::BeforePhysics, [&](uint64_t) { w->add_joint_force("p", "axle", 0.3); });
  w->step(100);
  EXPECT_NEAR(w->joint_velocity("p", "axle"), 0.0, 1e-12);
}

// The setting is read back, kept over reset_simulation and reset_world, and acts after them.
TEST(WorldJointMotor, IsKeptOverResets) {
  auto w = at_five(kPuck, 0.0);
  EXPECT_EQ(w->joint_motor("p", "axle").max_effort, 0.0);
  w->set_joint_motor("p", "axle", {2.0, 1000.0});
  w->step(5);
  w->reset();
  EXPECT_EQ(w->joint_motor("p", "axle").velocity, 2.0);
  EXPECT_EQ(w->joint_motor("p", "axle").max_effort, 1000.0);
  EXPECT_EQ(w->joint_velocity("p", "axle"), 0.0);
  w->step();
  EXPECT_NEAR(w->joint_velocity("p", "axle"), 2.0, 1e-9);
  w->reset_poses();
  w->step();
  EXPECT_NEAR(w->joint_velocity("p", "axle"), 2.0, 1e-9);
}

// A robot whose motor is on can be removed, and the world goes on.
TEST(WorldJointMotor, GoesWithItsRobot) {
  auto w = at_five(kPuck, 0.0);
  w->set_joint_motor("p", "axle", {2.0, 1000.0});
  w->remove("p");
  w->step(2);
  EXPECT_FALSE(w->has_model("p"));
}

TEST(WorldJointMotor, BadSettingsAreRefused) {
  auto w = at_five(kPuck, 0.0);
  try {
    w->set_joint_motor("p", "axle", {1.0, -1.0});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "a joint motor's max effort must be >= 0 (got -1.000000)");
  }
  try {
    w->set_joint_motor("p", "axle", {NAN, 1.0});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "a joint motor's velocity and max effort must be finite numbers");
  }
  try {
    w->set_joint_motor("p", "nope", {1.0, 1.0});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "model 'p' has no moving joint 'nope'");
  }
}

// Gravity 3 m/s^2: with gravity off the box keeps its height over 1 s; it reports gravity off.
TEST(WorldGravityMode, ALinkWithGravityOffKeepsItsHeight) {
  auto w = at_five(kBox, 3.0);
  w->set_link_gravity(kBody, false);
  EXPECT_FALSE(w->link_gravity(kBody));
  EXPECT_FALSE(w->link_properties(kBody).gravity);
  w->step(1000);
  EXPECT_NEAR(w->link_state(kBody).pose.translation().z(), 5.0, 1e-12);
  EXPECT_NEAR(w->link_state(kBody).linear.z(), 0.0, 1e-12);
}

// Back on, it falls as a free body: semi-implicit Euler over n = 1000 steps drops g dt^2 n (n + 1) / 2
// = 3 x 1e-6 x 1000 x 1001 / 2 = 1.5015 m.
TEST(WorldGravityMode, GravityBackOnItFallsAgain) {
  auto w = at_five(kBox, 3.0);
  w->set_link_gravity(kBody, false);
  w->step(10);
  w->set_link_gravity(kBody, true);
  EXPECT_TRUE(w->link_gravity(kBody));
  w->step(1000);
  EXPECT_NEAR(w->link_state(kBody).pose.translation().z(), 5.0 - 1.5015, 1e-9);
}

TEST(WorldGravityMode, AnUnknownLinkIsRefused) {
  auto w = at_five(kBox, 3.0);
  try {
    w->set_link_gravity({"p", "nope", true}, false);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "model 'p' has no link 'nope'");
  }
}
