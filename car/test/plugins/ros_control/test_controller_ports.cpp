// ros_control through the world's one entry for commands and calls: controller_manager's services are the
// instance's calls, each loaded controller's topics and action are ports that come and go with it (as
// ros_controllers names them, docs/COMPAT-control.md).
#include <gtest/gtest.h>

#include <cmath>

#include "control_fixture.hpp"

using namespace car_sim;
using namespace car_sim::control_test;

namespace {

const char* const kPlugin = "gazebo_ros_control";

CallRequest load(const std::string& name, const CallParams& params) {
  CallRequest r;
  r.name = name;
  r.params = params;
  return r;
}

CallRequest switch_on(const std::vector<std::string>& start) {
  CallRequest r;
  r.start = start;
  r.strictness = 2;  // STRICT
  return r;
}

const CallParams kRoverDrive = {{"type", {"diff_drive_controller/DiffDriveController"}},
                                {"left_wheel", {"front_left_joint", "rear_left_joint"}},
                                {"right_wheel", {"front_right_joint", "rear_right_joint"}},
                                {"cmd_vel_timeout", {"10"}}};

const CallParams kArmTrajectory = {{"type", {"position_controllers/JointTrajectoryController"}},
                                   {"joints", {"shoulder", "elbow"}}};

std::vector<std::string> names_topics(const std::vector<InputPort>& ports) {
  std::vector<std::string> out;
  for (const auto& p : ports) out.push_back(p.name + " " + p.topic);
  return out;
}

std::vector<std::string> names_topics(const std::vector<OutputPort>& ports) {
  std::vector<std::string> out;
  for (const auto& p : ports) out.push_back(p.name + " " + p.topic);
  return out;
}

}  // namespace

// What the manager bound to, for the node's log line: the arm's two transmissions, one joint each.
TEST(ControllerPorts, SummaryCountsTransmissionsAndJoints) {
  auto w = world_with("arm.urdf", "arm");
  EXPECT_EQ(w->plugin_info("arm", kPlugin).summary, "2 transmissions, 2 joints");
}

// The services of the kind: controller_manager's six under <ns>/controller_manager/ (ns "/" on the rover: global),
// beside the pid_gains call, which is no service (test_pid_gains.cpp).
TEST(ControllerPorts, ServicesAreControllerManagersUnderTheNamespace) {
  auto w = world_with("arm.urdf", "arm");
  std::vector<std::string> got;
  for (const auto& s : w->plugin_info("arm", kPlugin).services)
    if (s.type != CallType::SetParameters) got.push_back(s.topic);
  EXPECT_EQ(got, (std::vector<std::string>{"/arm/controller_manager/load_controller",
                                           "/arm/controller_manager/unload_controller",
                                           "/arm/controller_manager/switch_controller",
                                           "/arm/controller_manager/list_controllers",
                                           "/arm/controller_manager/list_controller_types",
                                           "/arm/controller_manager/reload_controller_libraries"}));
}

// diff_drive_controller: cmd_vel in, odom out (frames as written, queue 100), under /<ns>/<name>/.
TEST(ControllerPorts, LoadAddsTheControllersPorts) {
  auto w = world_with("rover.urdf", "rover");
  EXPECT_TRUE(w->plugin_info("rover", kPlugin).inputs.empty());
  const CallResponse r = w->call("rover", kPlugin, "load_controller", load("dd", kRoverDrive));
  ASSERT_TRUE(r.ok) << (r.errors.empty() ? "" : r.errors[0]);
  EXPECT_TRUE(r.ports_changed);
  EXPECT_EQ(r.infos, (std::vector<std::string>{"controller_manager: loaded 'dd' "
                                               "(diff_drive_controller/DiffDriveController)"}));
  const PluginInfo& info = w->plugin_info("rover", kPlugin);
  EXPECT_EQ(names_topics(info.inputs), (std::vector<std::string>{"dd/cmd_vel /dd/cmd_vel"}));
  ASSERT_EQ(names_topics(info.outputs), (std::vector<std::string>{"dd/odom /dd/odom"}));
  EXPECT_EQ(info.outputs[0].frame, "odom");
  EXPECT_EQ(info.outputs[0].child_frame, "base_link");
  EXPECT_EQ(info.outputs[0].queue, 100u);
  EXPECT_EQ(info.outputs[0].tf, TfOrder::After);
}

TEST(ControllerPorts, UnloadRemovesThem) {
  auto w = world_with("rover.urdf", "rover");
  ASSERT_TRUE(w->call("rover", kPlugin, "load_controller", load("dd", kRoverDrive)).ok);
  CallRequest u;
  u.name = "dd";
  const CallResponse r = w->call("rover", kPlugin, "unload_controller", u);
  ASSERT_TRUE(r.ok);
  EXPECT_TRUE(r.ports_changed);
  EXPECT_TRUE(w->plugin_info("rover", kPlugin).inputs.empty());
  EXPECT_TRUE(w->plugin_info("rover", kPlugin).outputs.empty());
}

// A Twist through World::command drives the wheels as the controller's own set_twist does (test_ros_control:
// v 0.4 m/s, w 0.5 rad/s on wheels of radius 0.1 m, separation 0.6 m: left 2.5, right 5.5 rad/s).
TEST(ControllerPorts, CmdVelThroughTheWorldDrivesTheWheels) {
  auto w = world_with("rover.urdf", "rover");
  ASSERT_TRUE(w->call("rover", kPlugin, "load_controller", load("dd", kRoverDrive)).ok);
  ASSERT_TRUE(w->call("rover", kPlugin, "switch_controller", switch_on({"dd"})).ok);
  Twist t;
  t.linear.x() = 0.4;
  t.angular.z() = 0.5;
  ASSERT_TRUE(w->command("rover", kPlugin, "dd/cmd_vel", t).accepted);
  w->step(1000);
  for (const auto& s : w->joint_states("rover")) {
    const double expect = s.name.find("left") != std::string::npos ? 2.5 : 5.5;
    EXPECT_NEAR(s.velocity, expect, 0.05) << s.name;
  }
}

// Its odometry goes out on its own port only.
TEST(ControllerPorts, OutputsNameTheirPort) {
  auto w = world_with("rover.urdf", "rover");
  ASSERT_TRUE(w->call("rover", kPlugin, "load_controller", load("dd", kRoverDrive)).ok);
  ASSERT_TRUE(w->call("rover", kPlugin, "switch_controller", switch_on({"dd"})).ok);
  w->step(100);
  const OutputQueue out = w->take_outputs_if([](const Output& o) { return o.plugin == kPlugin; });
  ASSERT_FALSE(out.empty());
  for (const auto& o : out) {
    EXPECT_EQ(o->port, "dd/odom");
    EXPECT_TRUE(o->sample_of<OdometrySample>());
  }
}

// The world checks a joint command once: a NaN never reaches the controller.
TEST(ControllerPorts, NonFiniteCommandIsRejectedByTheWorld) {
  auto w = world_with("arm.urdf", "arm");
  ASSERT_TRUE(w->call("arm", kPlugin, "load_controller",
                      load("elbow", {{"type", {"position_controllers/JointPositionController"}}, {"joint", {"elbow"}}}))
                  .ok);
  const CommandResult r = w->command("arm", kPlugin, "elbow/command", Float64{NAN});
  EXPECT_FALSE(r.accepted);
  EXPECT_EQ(r.reason, "a non-finite value (data nan)");
}

// A goal for a stopped trajectory controller is rejected as INVALID_GOAL (-1), as upstream's isRunning check.
TEST(ControllerPorts, GoalForAStoppedControllerIsRefused) {
  auto w = world_with("arm.urdf", "arm");
  ASSERT_TRUE(w->call("arm", kPlugin, "load_controller", load("traj", kArmTrajectory)).ok);
  TrajectoryGoal g;
  g.id = 1;
  g.trajectory.joint_names = {"shoulder", "elbow"};
  g.trajectory.points.push_back({{0.1, 0.1}, 1.0});
  const CommandResult r = w->command("arm", kPlugin, "traj/follow_joint_trajectory", g);
  EXPECT_TRUE(r.accepted);
  EXPECT_TRUE(r.refused);
  EXPECT_EQ(r.code, -1);
  EXPECT_EQ(r.reason, "controller 'traj' is not running");
}

// A goal's end comes back on the action's port as a GoalResult with its id: one point at 1 s; no goal position
// tolerance (0: unchecked) and a stopped-velocity tolerance of 10 rad/s, which the arm at rest meets, so it
// succeeds once its time is reached.
TEST(ControllerPorts, GoalEndsAsAGoalResultOnTheActionsPort) {
  auto w = world_with("arm.urdf", "arm");
  CallParams params = kArmTrajectory;
  params["constraints/goal_time"] = {"1.0"};
  params["constraints/stopped_velocity_tolerance"] = {"10"};
  ASSERT_TRUE(w->call("arm", kPlugin, "load_controller", load("traj", params)).ok);
  ASSERT_TRUE(w->call("arm", kPlugin, "switch_controller", switch_on({"traj"})).ok);
  TrajectoryGoal g;
  g.id = 42;
  g.trajectory.joint_names = {"shoulder", "elbow"};
  g.trajectory.points.push_back({{0.1, 0.1}, 1.0});
  const CommandResult r = w->command("arm", kPlugin, "traj/follow_joint_trajectory", g);
  ASSERT_FALSE(r.refused) << r.reason;
  w->step(2100);
  const OutputQueue out =
      w->take_outputs_if([](const Output& o) { return o.sample_of<GoalResultSample>() != nullptr; });
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0]->port, "traj/follow_joint_trajectory");
  const GoalResultSample& s = *out[0]->sample_of<GoalResultSample>();
  EXPECT_EQ(s.goal, 42u);
  EXPECT_EQ(s.status, GoalResultSample::Status::Succeeded) << s.error_string;
  EXPECT_EQ(s.error_code, 0);
}

TEST(ControllerPorts, LoadWithoutTypeNamesTheKey) {
  auto w = world_with("arm.urdf", "arm");
  const CallResponse r = w->call("arm", kPlugin, "load_controller", load("x", {{"joint", {"elbow"}}}));
  EXPECT_FALSE(r.ok);
  EXPECT_FALSE(r.ports_changed);
  EXPECT_EQ(r.errors, (std::vector<std::string>{"controller_manager: could not load controller 'x': "
                                                "/arm/x/type: missing (required key)"}));
}

TEST(ControllerPorts, SwitchWithAnUnknownStrictnessIsRefused) {
  auto w = world_with("arm.urdf", "arm");
  CallRequest r;
  r.strictness = 0;
  EXPECT_EQ(w->call("arm", kPlugin, "switch_controller", r).errors,
            (std::vector<std::string>{"controller_manager: switch_controller: strictness 0 is neither BEST_EFFORT "
                                      "(1) nor STRICT (2)"}));
}

TEST(ControllerPorts, ListControllersSaysWhatRuns) {
  auto w = world_with("arm.urdf", "arm");
  ASSERT_TRUE(w->call("arm", kPlugin, "load_controller", load("traj", kArmTrajectory)).ok);
  const CallResponse r = w->call("arm", kPlugin, "list_controllers", {});
  ASSERT_EQ(r.controllers.size(), 1u);
  EXPECT_EQ(r.controllers[0].name, "traj");
  EXPECT_EQ(r.controllers[0].type, "position_controllers/JointTrajectoryController");
  EXPECT_EQ(r.controllers[0].state, "stopped");
  ASSERT_EQ(r.controllers[0].claimed.size(), 1u);
  EXPECT_EQ(r.controllers[0].claimed[0].second, (std::vector<std::string>{"shoulder", "elbow"}));
}

TEST(ControllerPorts, UnknownServiceThrowsWithItsName) {
  auto w = world_with("arm.urdf", "arm");
  try {
    w->call("arm", kPlugin, "kill", {});
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "plug-in 'gazebo_ros_control' of robot 'arm' has no service 'kill'");
  }
}
