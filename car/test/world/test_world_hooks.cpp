// World's calls for users' own plug-ins (the Gazebo 11 API's ground, docs/PLUGINS.md): per-step hooks, forces on
// links for one step, joint efforts and velocities, link velocities. Values worked out by hand for bodies floating
// in zero gravity, where only what the test applies acts. dt = 0.001 s.
#include <gtest/gtest.h>

#include <cmath>

#include "car_sim/world.hpp"

using namespace car_sim;

namespace {

// A box of 2 kg (Izz 0.5 kg m^2, com at its origin), alone: for the forces.
const char* kBox = R"(<?xml version="1.0"?>
<robot name="box">
  <link name="body">
    <inertial><mass value="2"/><inertia ixx="0.5" iyy="0.5" izz="0.5" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  </link>
</robot>)";

// The same box with a 1 kg wheel (Izz 0.5) on a continuous joint about z through both coms, 1 m above: the two
// turn about one axis, uncoupled from the rest. The joint has no damping; its <limit effort> is 0.5 N m.
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
    <axis xyz="0 0 1"/><limit effort="0.5" velocity="100"/></joint>
</robot>)";

// A robot named "p" at (0, 0, 5), yawed by `yaw`, in an empty world without gravity.
std::unique_ptr<World> floating(const char* urdf, double yaw = 0.0) {
  auto w = std::make_unique<World>(empty_world());
  w->set_gravity(Eigen::Vector3d::Zero());
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(0, 0, 5);
  pose.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  w->spawn(load_urdf_string(urdf, "p"), "p", pose);
  return w;
}

const LinkRef kBody{"p", "body", true};

}  // namespace

TEST(WorldHooks, BeforeSeesTheTickTheStepStartsFromAfterTheTickReached) {
  auto w = floating(kPuck);
  std::vector<uint64_t> before, after;
  w->add_step_hook(World::StepPhase::BeforePhysics, [&](uint64_t t) { before.push_back(t); });
  w->add_step_hook(World::StepPhase::AfterPhysics, [&](uint64_t t) { after.push_back(t); });
  w->step(3);
  EXPECT_EQ(before, (std::vector<uint64_t>{0, 1, 2}));
  EXPECT_EQ(after, (std::vector<uint64_t>{1, 2, 3}));
}

TEST(WorldHooks, CalledInTheOrderAdded) {
  auto w = floating(kPuck);
  std::string calls;
  w->add_step_hook(World::StepPhase::BeforePhysics, [&](uint64_t) { calls += "a"; });
  w->add_step_hook(World::StepPhase::BeforePhysics, [&](uint64_t) { calls += "b"; });
  w->step(2);
  EXPECT_EQ(calls, "abab");
}

TEST(WorldHooks, ARemovedHookIsNotCalledAgain) {
  auto w = floating(kPuck);
  int calls = 0;
  const uint64_t id = w->add_step_hook(World::StepPhase::BeforePhysics, [&](uint64_t) { ++calls; });
  EXPECT_NE(id, 0u);
  w->step(2);
  w->remove_step_hook(id);
  w->step(2);
  EXPECT_EQ(calls, 2);
}

TEST(WorldHooks, AHookMayRemoveItself) {
  auto w = floating(kPuck);
  int calls = 0;
  uint64_t id = 0;
  id = w->add_step_hook(World::StepPhase::AfterPhysics, [&](uint64_t) {
    ++calls;
    w->remove_step_hook(id);
  });
  w->step(3);
  EXPECT_EQ(calls, 1);
}

TEST(WorldHooks, AnEmptyHookIsRefused) {
  auto w = floating(kPuck);
  try {
    w->add_step_hook(World::StepPhase::BeforePhysics, nullptr);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "a step hook needs a function");
  }
}

// Hooks that do nothing leave the run bit for bit as without them.
TEST(WorldHooks, IdleHooksChangeNoBit) {
  auto a = floating(kPuck), b = floating(kPuck);
  b->add_step_hook(World::StepPhase::BeforePhysics, [](uint64_t) {});
  b->add_step_hook(World::StepPhase::AfterPhysics, [](uint64_t) {});
  for (auto* w : {a.get(), b.get()}) {
    w->set_joint_velocity("p", "axle", 1.5);
    w->set_link_velocity(kBody, Eigen::Vector3d(0.3, 0.1, 0), Eigen::Vector3d(0, 0, 0.2));
    w->step(500);
  }
  const ModelState sa = a->model_state("p"), sb = b->model_state("p");
  EXPECT_EQ(sa.pose.matrix(), sb.pose.matrix());
  EXPECT_EQ(sa.linear, sb.linear);
  EXPECT_EQ(a->joint_position("p", "axle"), b->joint_position("p", "axle"));
}

// 1 N on 2 kg for 1 s (a hook adds it every step): v = 0.5 m/s; x = sum of v_k dt, v_k = 0.5 k dt, k = 1..1000:
// 0.5 dt^2 1000 1001 / 2 = 0.25025 m.
TEST(WorldForce, OneNewtonOnTwoKilogramsForOneSecond) {
  auto w = floating(kBox);
  w->add_step_hook(World::StepPhase::BeforePhysics, [&](uint64_t) {
    w->add_link_wrench(kBody, Eigen::Vector3d(1, 0, 0), Eigen::Vector3d::Zero(), w->body_com(kBody),
                       World::Frame::World);
  });
  w->step(1000);
  const ModelState s = w->model_state("p");
  EXPECT_NEAR(s.linear.x(), 0.5, 1e-9);
  EXPECT_NEAR(s.pose.translation().x(), 0.25025, 1e-9);
}

// Between steps: the force acts in the coming step only. 1 N x 0.001 s / 2 kg = 0.0005 m/s, not twice that.
TEST(WorldForce, ActsForTheComingStepOnly) {
  auto w = floating(kBox);
  w->add_link_wrench(kBody, Eigen::Vector3d(1, 0, 0), Eigen::Vector3d::Zero(), w->body_com(kBody),
                     World::Frame::World);
  w->step(2);
  EXPECT_NEAR(w->model_state("p").linear.x(), 0.0005, 1e-12);
}

// The puck yawed by 90 degrees: its x axis is the world's y.
TEST(WorldForce, LinkFrameTurnsWithTheLink) {
  auto w = floating(kBox, M_PI / 2);
  w->add_link_wrench(kBody, Eigen::Vector3d(1, 0, 0), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                     World::Frame::Link);
  w->step();
  const Eigen::Vector3d v = w->model_state("p").linear;
  EXPECT_NEAR(v.x(), 0.0, 1e-12);
  EXPECT_NEAR(v.y(), 0.0005, 1e-12);
}

// 1 N along y at 1 m along x from the com, one step: linear y = 0.001 / 2; the moment 1 N m about z turns the box
// by 1 x 0.001 / 0.5 = 0.002 rad/s.
TEST(WorldForce, AForceOffTheComAlsoTurns) {
  auto w = floating(kBox);
  w->add_link_wrench(kBody, Eigen::Vector3d(0, 1, 0), Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 0, 5),
                     World::Frame::World);
  w->step();
  const ModelState s = w->model_state("p");
  EXPECT_NEAR(s.linear.y(), 0.0005, 1e-12);
  EXPECT_NEAR(s.angular.z(), 0.002, 1e-12);
}

// 0.2 N m about z for one step: 0.2 x 0.001 / 0.5 = 0.0004 rad/s.
TEST(WorldForce, TorqueTurns) {
  auto w = floating(kBox);
  w->add_link_wrench(kBody, Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 0.2), Eigen::Vector3d(0, 0, 5),
                     World::Frame::World);
  w->step();
  EXPECT_NEAR(w->model_state("p").angular.z(), 0.0004, 1e-12);
}

TEST(WorldForce, UnknownLinkAndNonFiniteForceAreRefused) {
  auto w = floating(kBox);
  try {
    w->add_link_wrench({"p", "nope", true}, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                       World::Frame::World);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "model 'p' has no link 'nope'");
  }
  try {
    w->add_link_wrench(kBody, Eigen::Vector3d(NAN, 0, 0), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                       World::Frame::World);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "force, torque and point must be finite");
  }
}

// 0.4 N m on the axle for 1 s (two efforts of 0.2 each step, which add up): the wheel turns up at 0.4 / 0.5 and
// the body back at 0.4 / 0.5, so the joint speeds up at 1.6 rad/s^2: 1.6 rad/s after 1 s.
TEST(WorldJoint, EffortsInAStepAddUp) {
  auto w = floating(kPuck);
  w->add_step_hook(World::StepPhase::BeforePhysics, [&](uint64_t) {
    w->add_joint_force("p", "axle", 0.2);
    w->add_joint_force("p", "axle", 0.2);
  });
  w->step(1000);
  EXPECT_NEAR(w->joint_velocity("p", "axle"), 1.6, 1e-9);
}

// 2 N m asked, the joint's <limit effort> 0.5 N m given: 0.5 x 4 x 0.001 = 0.002 rad/s after one step.
TEST(WorldJoint, EffortIsClampedToTheJointsLimit) {
  auto w = floating(kPuck);
  EXPECT_EQ(w->add_joint_force("p", "axle", 2.0), 0.5);
  EXPECT_EQ(w->add_joint_force("p", "axle", -0.1), -0.1);
  w->step();
  EXPECT_NEAR(w->joint_velocity("p", "axle"), 0.4 * 4 * 0.001, 1e-12);
}

// Set to 2 rad/s: read back at once, the position stays; free of torques it keeps turning, 2 rad in 1 s.
TEST(WorldJoint, SetVelocityKeepsThePositionAndThenTurns) {
  auto w = floating(kPuck);
  w->set_joint_velocity("p", "axle", 2.0);
  EXPECT_EQ(w->joint_velocity("p", "axle"), 2.0);
  EXPECT_EQ(w->joint_position("p", "axle"), 0.0);
  w->step(1000);
  EXPECT_NEAR(w->joint_position("p", "axle"), 2.0, 1e-9);
}

TEST(WorldJoint, UnknownJointAndBadNumbersAreRefused) {
  auto w = floating(kPuck);
  try {
    w->joint_position("p", "nope");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "model 'p' has no moving joint 'nope'");
  }
  try {
    w->add_joint_force("q", "axle", 1.0);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "no robot named 'q'");
  }
  try {
    w->set_joint_velocity("p", "axle", INFINITY);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "velocity must be a finite number");
  }
}

// The box's com set moving at 1 m/s along x: 1 m in 1 s.
TEST(WorldLinkVelocity, TheComMovesAtTheVelocitySet) {
  auto w = floating(kBox);
  w->set_link_velocity(kBody, Eigen::Vector3d(1, 0, 0), Eigen::Vector3d::Zero());
  w->step(1000);
  EXPECT_NEAR(w->model_state("p").pose.translation().x(), 1.0, 1e-9);
}

// The wheel (com on the axis, 1 m above the body's origin) set turning at 0.5 rad/s about z: the whole puck turns
// with it, the body's origin on the axis stays put, the joint keeps its speed (0).
TEST(WorldLinkVelocity, AngularVelocityTurnsTheModel) {
  auto w = floating(kPuck);
  w->set_link_velocity({"p", "wheel", true}, Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 0.5));
  const ModelState s = w->model_state("p");
  EXPECT_NEAR(s.angular.z(), 0.5, 1e-12);
  EXPECT_NEAR(s.linear.norm(), 0.0, 1e-12);
  EXPECT_NEAR(w->joint_velocity("p", "axle"), 0.0, 1e-12);
}
