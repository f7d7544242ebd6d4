// libgazebo_ros_control.so and its controller types, in the core: hand-derived values (docs/COMPAT-control.md).
#include <gtest/gtest.h>

#include <cmath>

#include "control_fixture.hpp"

using namespace car_sim;
using namespace car_sim::control_test;
using control::Params;

namespace {

double joint(const World& w, const std::string& robot, const std::string& j) {
  for (const auto& s : w.joint_states(robot))
    if (s.name == j) return s.position;
  return NAN;
}

}  // namespace

TEST(RosControl, ReadsTransmissionsWithAndWithoutPrefix) {
  const RobotModel m = load_urdf_file(data_path("control/arm.urdf"));
  ASSERT_EQ(m.transmissions.size(), 2u);
  EXPECT_EQ(m.transmissions[0].type, "transmission_interface/SimpleTransmission");
  EXPECT_EQ(m.transmissions[0].joints[0].interfaces, (std::vector<std::string>{"EffortJointInterface",
                                                                                "PositionJointInterface"}));
  EXPECT_EQ(m.transmissions[1].joints[0].interfaces, (std::vector<std::string>{"EffortJointInterface",
                                                                                "PositionJointInterface"}));
}

// The arm's joints offer effort AND position, so each has a Bullet joint motor; in effort mode it is switched off
// (MotorTarget::enabled), else it would resist velocity changes up to the joint's effort limit.
TEST(RosControl, EffortPidHoldsAgainstGravityWithErrorMglOverP) {
  // link2 folded straight (elbow held by a position controller): the shoulder carries 2 kg, centres of mass at
  // 0.5 m and 1.5 m: torque m g l = 1 * 9.8 * 0.5 + 1 * 9.8 * 1.5 = 19.6 N m at q = 0. With p only the steady
  // error is e = m g l cos(e) / p; p = 1000: e = 0.01962 rad (cos(e) = 0.9998 changes it by 4e-6).
  auto w = world_with("arm.urdf", "arm");
  RosControl& rc = manager(*w, "arm");
  rc.load("shoulder_ctl", "effort_controllers/JointPositionController",
          Params{{"joint", {"shoulder"}}, {"pid/p", {"1000"}}, {"pid/d", {"50"}}});
  rc.load("elbow_ctl", "position_controllers/JointPositionController", Params{{"joint", {"elbow"}}});
  start(rc, {"shoulder_ctl", "elbow_ctl"});
  w->step(5000);  // 5 s: the d-damped response settles
  const double e = 2 * 1.0 * kG * 1.0 / 1000;  // 19.6 / 1000 (m g l = 9.8 * (0.5 + 1.5))
  EXPECT_NEAR(joint(*w, "arm", "shoulder"), e, 5e-4);  // sags towards +q (gravity's torque about +y)
  EXPECT_NEAR(joint(*w, "arm", "elbow"), 0.0, 1e-3);
}

TEST(RosControl, PositionTrajectoryReachesItsPointAtItsTime) {
  // position_controllers/JointTrajectoryController: one point (0.5, -0.5) rad at 2 s, linear from (0, 0)
  auto w = world_with("arm.urdf", "arm");
  RosControl& rc = manager(*w, "arm");
  rc.load("arm_ctl", "position_controllers/JointTrajectoryController",
          Params{{"joints", {"shoulder", "elbow"}}, {"constraints/goal_time", {"0.5"}}});
  start(rc, {"arm_ctl"});
  control::TrajGoal g;
  g.joint_names = {"shoulder", "elbow"};
  g.points.push_back({{0.5, -0.5}, {}, {}, 2.0});
  std::string why;
  int code = 0;
  auto* tc = dynamic_cast<control::TrajectoryController*>(rc.controller("arm_ctl"));
  ASSERT_TRUE(tc->set_trajectory(g, 1, w->time(), &why, &code)) << why;
  w->step(1000);  // t = 1 s: half way, 0.25 and -0.25 rad
  EXPECT_NEAR(joint(*w, "arm", "shoulder"), 0.25, 0.01);
  EXPECT_NEAR(joint(*w, "arm", "elbow"), -0.25, 0.01);
  w->step(1000);  // t = 2 s
  EXPECT_NEAR(joint(*w, "arm", "shoulder"), 0.5, 0.01);
  EXPECT_NEAR(joint(*w, "arm", "elbow"), -0.5, 0.01);
}

// A twist through the manager's port, as the node gives it (held until the just-started controller's first update).
void drive(RosControl& rc, double v, double w) {
  Twist t;
  t.linear.x() = v;
  t.angular.z() = w;
  CommandResult r;
  rc.command("dd/cmd_vel", t, &r);
  ASSERT_FALSE(r.refused) << r.reason;
}

TEST(RosControl, DiffDriveWheelSpeedsAreVMinusPlusWTimesHalfSeparationOverRadius) {
  // rover: separation 0.6 m (from the URDF), radius 0.1 m (collision cylinder); v = 0.4 m/s, w = 0.5 rad/s:
  // left (0.4 - 0.5 * 0.3) / 0.1 = 2.5 rad/s, right (0.4 + 0.5 * 0.3) / 0.1 = 5.5 rad/s
  auto w = world_with("rover.urdf", "rover");
  RosControl& rc = manager(*w, "rover");
  rc.load("dd", "diff_drive_controller/DiffDriveController",
          Params{{"left_wheel", {"front_left_joint", "rear_left_joint"}},
                 {"right_wheel", {"front_right_joint", "rear_right_joint"}},
                 {"cmd_vel_timeout", {"10"}}});
  start(rc, {"dd"});
  drive(rc, 0.4, 0.5);
  w->step(1000);
  for (const auto& s : w->joint_states("rover")) {
    const double expect = s.name.find("left") != std::string::npos ? 2.5 : 5.5;
    EXPECT_NEAR(s.velocity, expect, 0.05) << s.name;
  }
}

TEST(RosControl, CmdVelTimeoutStopsTheWheels) {
  auto w = world_with("rover.urdf", "rover");
  RosControl& rc = manager(*w, "rover");
  rc.load("dd", "diff_drive_controller/DiffDriveController",
          Params{{"left_wheel", {"front_left_joint", "rear_left_joint"}},
                 {"right_wheel", {"front_right_joint", "rear_right_joint"}},
                 {"cmd_vel_timeout", {"0.25"}}});
  start(rc, {"dd"});
  drive(rc, 0.4, 0.0);
  w->step(200);  // 0.2 s < timeout: driving at 4 rad/s
  EXPECT_NEAR(w->joint_states("rover")[0].velocity, 4.0, 0.05);
  w->step(300);  // 0.5 s > 0.25 s: commanded 0
  EXPECT_NEAR(w->joint_states("rover")[0].velocity, 0.0, 0.05);
}

TEST(RosControl, BadInputNamesTheControllerKeyAndReason) {
  auto w = world_with("rover.urdf", "rover");
  RosControl& rc = manager(*w, "rover");
  auto error_of = [&](const std::string& name, const std::string& type, const Params& p) {
    try {
      rc.load(name, type, p);
    } catch (const control::ControllerError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error_of("a", "nope/Controller", {}).substr(0, 66),
            "controller 'a': type: unknown controller type 'nope/Controller' (c");
  EXPECT_EQ(error_of("b", "diff_drive_controller/DiffDriveController", {{"left_wheel", {"front_left_joint"}}}),
            "controller 'b': right_wheel: missing (required key)");
  EXPECT_EQ(error_of("c", "position_controllers/JointPositionController", {{"joint", {"front_left_joint"}}}),
            "controller 'c': joint: joint 'front_left_joint' has no hardware_interface/PositionJointInterface in its "
            "<transmission>");
  EXPECT_EQ(error_of("d", "joint_state_controller/JointStateController", {}),
            "controller 'd': publish_rate: missing (required key)");
}

TEST(RosControl, JointWithoutTransmissionIsRefused) {
  // the arm's anchor is fixed; a fictitious controller on the rover's base has no joint
  auto w = world_with("rover.urdf", "rover");
  try {
    manager(*w, "rover").load("x", "velocity_controllers/JointVelocityController", {{"joint", {"nope"}}});
    FAIL();
  } catch (const control::ControllerError& e) {
    EXPECT_STREQ(e.what(), "controller 'x': joint: no joint 'nope' in the robot");
  }
}

TEST(RosControl, StrictSwitchRefusesAConflictAndAnUnknownController) {
  auto w = world_with("arm.urdf", "arm");
  RosControl& rc = manager(*w, "arm");
  rc.load("a", "effort_controllers/JointEffortController", {{"joint", {"shoulder"}}});
  rc.load("b", "position_controllers/JointPositionController", {{"joint", {"shoulder"}}});
  std::string why;
  EXPECT_FALSE(rc.switch_controllers({"a", "b"}, {}, true, &why));
  EXPECT_EQ(why, "controller 'b': joint 'shoulder' is already claimed by 'a'");
  EXPECT_FALSE(rc.switch_controllers({"zz"}, {}, true, &why));
  EXPECT_EQ(why, "controller 'zz': not loaded, cannot start it");
  EXPECT_TRUE(rc.switch_controllers({"zz", "a"}, {}, false, &why));  // best effort: starts a
  EXPECT_TRUE(rc.loaded()[0].running);
}

// Issue 29 item 5: a robotSimType car lacks loads car's default hardware sim with one warning naming the type; the
// franka_hw state interface is left out and the standard ones drive the arm (the elbow's position controller holds
// it straight, as in EffortPidHoldsAgainstGravityWithErrorMglOverP).
TEST(RosControl, ForeignRobotSimTypeWarnsOnceAndRunsTheStandardInterfaces) {
  auto w = world_with("arm_foreign_sim.urdf", "arm");
  std::vector<Diagnostic> found;
  for (const auto& d : w->robot("arm").config.diagnostics)
    if (d.code == "robot-sim-type") found.push_back(d);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].severity, Severity::Warning);
  EXPECT_EQ(found[0].element, "gazebo/plugin[gazebo_ros_control]/robotSimType");
  EXPECT_EQ(found[0].message,
            "'franka_gazebo/FrankaHWSim' is not simulated by car; car's gazebo_ros_control/DefaultRobotHWSim drives "
            "the standard joint interfaces (Position-, Velocity-, EffortJointInterface) the transmissions declare, "
            "and leaves the others out");
  RosControl& rc = manager(*w, "arm");
  rc.load("shoulder_ctl", "effort_controllers/JointPositionController",
          Params{{"joint", {"shoulder"}}, {"pid/p", {"1000"}}, {"pid/d", {"50"}}});
  rc.load("elbow_ctl", "position_controllers/JointPositionController", Params{{"joint", {"elbow"}}});
  start(rc, {"shoulder_ctl", "elbow_ctl"});
  w->step(5000);
  EXPECT_NEAR(joint(*w, "arm", "shoulder"), 2 * 1.0 * kG * 1.0 / 1000, 5e-4);
  EXPECT_NEAR(joint(*w, "arm", "elbow"), 0.0, 1e-3);
}
