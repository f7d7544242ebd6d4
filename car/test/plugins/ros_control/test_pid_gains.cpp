// gazebo_ros_control's pid_gains (DefaultRobotHWSim): a position or velocity joint with gains at
// <ns>/gazebo_ros_control/pid_gains/JOINT is driven by that PID's effort, capped by its effort limit
// (docs/COMPAT-control.md "pid_gains"). The skin hands the parameters over in one call, "pid_gains"; these tests
// make that call as the node does.
//
// Timing (test_controller_types.cpp says why): 1 ms steps; a controller started at t = 0 acts from the second
// step, so over N steps its command acts for N - 1. Bullet integrates semi-implicit Euler.
#include <gtest/gtest.h>

#include <cmath>

#include "control_fixture.hpp"

using namespace car_sim;
using namespace car_sim::control_test;
using control::Params;

namespace {

constexpr char kPlugin[] = "gazebo_ros_control";

JointState joint(const World& w, const std::string& robot, const std::string& j) {
  for (const auto& s : w.joint_states(robot))
    if (s.name == j) return s;
  ADD_FAILURE() << "no joint " << j;
  return {};
}

CallResponse pid_gains(World& w, const std::string& robot, const Params& p) {
  CallRequest rq;
  rq.params = p;
  return w.call(robot, kPlugin, "pid_gains", rq);
}

// A one-joint command through the manager's port, as the node gives it.
void command(RosControl& rc, const std::string& controller, double v) {
  CommandResult r;
  rc.command(controller + "/command", Float64{v}, &r);
  ASSERT_FALSE(r.refused) << r.reason;
}

}  // namespace

// The port: no ROS service (empty topic), the parameters' namespace under the robot's.
TEST(PidGains, PortReadsUnderTheRobotNamespace) {
  auto w = world_with("arm.urdf", "arm");
  const ServicePort* port = nullptr;
  for (const auto& s : w->plugin_info("arm", kPlugin).services)
    if (s.name == "pid_gains") port = &s;
  ASSERT_NE(port, nullptr) << "no pid_gains port";
  EXPECT_EQ(port->type, CallType::SetParameters);
  EXPECT_EQ(port->topic, "");
  EXPECT_EQ(port->ns, "/arm/gazebo_ros_control/pid_gains");
}

// Position PID on the shoulder: it sags under gravity as an effort PID does. Link2 held straight (the elbow's
// motor, no gains): the shoulder carries 2 kg at 0.5 m and 1.5 m: m g l = 9.8 * (0.5 + 1.5) = 19.6 N m at q = 0.
// p only in the steady state: e = m g l cos(e) / p = 19.6 / 1000 = 0.0196 rad (cos(e) changes it by 4e-6). A motor
// (car before pid_gains; Gazebo without gains) holds 0.
TEST(PidGains, PositionJointSagsByMglOverP) {
  auto w = world_with("arm.urdf", "arm");
  ASSERT_TRUE(pid_gains(*w, "arm", Params{{"shoulder/p", {"1000"}}, {"shoulder/d", {"50"}}}).ok);
  RosControl& rc = manager(*w, "arm");
  rc.load("shoulder_ctl", "position_controllers/JointPositionController", Params{{"joint", {"shoulder"}}});
  rc.load("elbow_ctl", "position_controllers/JointPositionController", Params{{"joint", {"elbow"}}});
  start(rc, {"shoulder_ctl", "elbow_ctl"});
  w->step(5000);  // 5 s: omega = sqrt(1000 / 2.6) = 20 rad/s, damping ratio 0.5: settled within 1 s
  EXPECT_NEAR(joint(*w, "arm", "shoulder").position, 2 * 1.0 * kG * 1.0 / 1000, 5e-4);
  EXPECT_NEAR(joint(*w, "arm", "elbow").position, 0.0, 1e-3);
}

// Velocity PID, p only, on turntable joint a (I = 0.5 kg m^2, free): I dw/dt = p (w_c - w), so per step
// w_c - w shrinks by (1 - p dt / I) = 1 - 5 * 0.001 / 0.5 = 0.99, and over N steps of the command by 0.99^N:
// from 100 to 200 steps it shrinks by 0.99^100 = 0.36603 (e^-1 = 0.36788 continuous), whenever the command began.
// A motor (no gains) reaches w_c within steps: 0/0.
TEST(PidGains, VelocityJointApproachesItsCommandWithTimeConstantIOverP) {
  auto w = world_with("turntable.urdf", "tt");
  ASSERT_TRUE(pid_gains(*w, "tt", Params{{"a/p", {"5"}}}).ok);
  RosControl& rc = manager(*w, "tt");
  rc.load("a_ctl", "velocity_controllers/JointVelocityController", Params{{"joint", {"a"}}});
  start(rc, {"a_ctl"});
  command(rc, "a_ctl", 2.0);
  w->step(100);
  const double gap1 = 2.0 - joint(*w, "tt", "a").velocity;  // [rad/s]
  w->step(100);
  const double gap2 = 2.0 - joint(*w, "tt", "a").velocity;
  EXPECT_NEAR(gap1, 2.0 * std::pow(0.99, 99), 1e-6);  // 99 steps of the command in the first 100
  EXPECT_NEAR(gap2 / gap1, std::pow(0.99, 100), 1e-6);
}

// The PID's effort is capped by <limit effort> 100 N m: on joint b (I = 0.25 kg m^2) a 1 rad step with p = 1000
// asks 1000 N m, gets 100: alpha = 400 rad/s^2, so w rises 4 rad/s in 10 steps (uncapped: 40).
TEST(PidGains, EffortIsCappedByTheJointsEffortLimit) {
  auto w = world_with("turntable.urdf", "tt");
  ASSERT_TRUE(pid_gains(*w, "tt", Params{{"b/p", {"1000"}}}).ok);
  RosControl& rc = manager(*w, "tt");
  rc.load("b_ctl", "position_controllers/JointPositionController", Params{{"joint", {"b"}}});
  start(rc, {"b_ctl"});
  command(rc, "b_ctl", 1.0);
  w->step(11);
  const double w1 = joint(*w, "tt", "b").velocity;  // [rad/s]
  w->step(10);  // still saturated: b is 0.084 rad on, the error 0.916 rad asks 916 N m
  EXPECT_NEAR(joint(*w, "tt", "b").velocity - w1, 400.0 * 10 * 0.001, 1e-9);
}

// What the node logs for gains it used.
TEST(PidGains, UsedGainsAreLogged) {
  auto w = world_with("arm.urdf", "arm");
  const CallResponse r = pid_gains(*w, "arm", Params{{"shoulder/p", {"1000"}}, {"shoulder/d", {"50"}}});
  EXPECT_TRUE(r.ok);
  EXPECT_EQ(r.infos, (std::vector<std::string>{
                         "gazebo_ros_control: /arm/gazebo_ros_control/pid_gains/shoulder: joint 'shoulder' follows "
                         "its position and velocity commands by this PID (p 1000, i 0, d 50), its effort capped by "
                         "the joint's effort limit"}));
  EXPECT_TRUE(r.warnings.empty());
}

// Gains without p: upstream's Pid::init fails ("No p gain specified for pid") and the joint keeps SetPosition.
TEST(PidGains, GainsWithoutPKeepTheMotor) {
  auto w = world_with("arm.urdf", "arm");
  const CallResponse r = pid_gains(*w, "arm", Params{{"shoulder/i", {"1"}}});
  EXPECT_TRUE(r.ok);
  EXPECT_EQ(r.warnings, (std::vector<std::string>{
                            "gazebo_ros_control: /arm/gazebo_ros_control/pid_gains/shoulder: no p (required key); "
                            "joint 'shoulder' keeps its motor (Gazebo says 'No p gain specified for pid')"}));
  RosControl& rc = manager(*w, "arm");
  rc.load("shoulder_ctl", "position_controllers/JointPositionController", Params{{"joint", {"shoulder"}}});
  rc.load("elbow_ctl", "position_controllers/JointPositionController", Params{{"joint", {"elbow"}}});
  start(rc, {"shoulder_ctl", "elbow_ctl"});
  w->step(2000);
  EXPECT_NEAR(joint(*w, "arm", "shoulder").position, 0.0, 1e-3);  // held by the motor, no sag
}

TEST(PidGains, GainOfNoNumberIsAnError) {
  auto w = world_with("arm.urdf", "arm");
  const CallResponse r = pid_gains(*w, "arm", Params{{"shoulder/p", {"stiff"}}});
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.errors, (std::vector<std::string>{
                          "gazebo_ros_control: /arm/gazebo_ros_control/pid_gains/shoulder/p: 'stiff' is not a "
                          "finite number; joint 'shoulder' keeps its motor"}));
}

// Gains of a joint no transmission drives: Gazebo ignores them, and a mimic joint's plug-in may read them (the
// mimic tutorial loads its left finger's there), so car says so in an info line, not a warning.
TEST(PidGains, GainsOfAJointWithoutTransmissionAreLeftToOtherPlugins) {
  auto w = world_with("arm.urdf", "arm");
  const CallResponse r = pid_gains(*w, "arm", Params{{"wrist/p", {"10"}}});
  EXPECT_TRUE(r.ok);
  EXPECT_TRUE(r.warnings.empty());
  EXPECT_EQ(r.infos, (std::vector<std::string>{"gazebo_ros_control: /arm/gazebo_ros_control/pid_gains/wrist: no "
                                               "transmission joint 'wrist' in this robot: not gazebo_ros_control's "
                                               "(another plug-in may read them)"}));
}

// Gazebo uses the gains only for position and velocity joints; the rover's wheels offer velocity, so use a robot
// whose joints offer effort alone: none of the fixtures, so a two-line one.
TEST(PidGains, GainsOfAnEffortOnlyJointAreNotUsed) {
  const std::string urdf = R"(<robot name="r"><link name="world"/><link name="l">
    <inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
    <joint name="j" type="continuous"><parent link="world"/><child link="l"/><axis xyz="0 0 1"/></joint>
    <transmission name="t"><type>transmission_interface/SimpleTransmission</type>
      <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
      <actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator></transmission>
    <gazebo><plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so"/></gazebo></robot>)";
  World w(empty_world());
  w.spawn(load_urdf_string(urdf), "r", at(0, 0, 0));
  const CallResponse r = pid_gains(w, "r", Params{{"j/p", {"10"}}});
  EXPECT_EQ(r.warnings, (std::vector<std::string>{"gazebo_ros_control: /r/gazebo_ros_control/pid_gains/j: joint 'j' "
                                                  "offers only an effort interface; its gains are not used (as in "
                                                  "Gazebo)"}));
}
