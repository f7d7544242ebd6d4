// libgazebo_ros_joint_pose_trajectory.so: points played one at a time by setting the joint; hand-derived ticks.
#include <gtest/gtest.h>

#include "car_sim/world.hpp"
#include "joint_pose_trajectory/joint_pose_trajectory.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

// A base box on the ground with an arm on a vertical revolute joint (gravity exerts no torque about it).
std::unique_ptr<World> arm_world() {
  const std::string xml = R"(<robot name="arm">
  <link name="base">
    <inertial><mass value="10"/><origin xyz="0 0 0.1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0 0 0.1"/><geometry><box size="0.4 0.4 0.2"/></geometry></collision>
  </link>
  <link name="arm">
    <inertial><mass value="1"/><origin xyz="0 0.2 0.05"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="arm_joint" type="continuous"><parent link="base"/><child link="arm"/><origin xyz="0 0 0.2"/>
    <axis xyz="0 0 1"/></joint>
  <gazebo><plugin name="traj" filename="libgazebo_ros_joint_pose_trajectory.so"/></gazebo>
</robot>)";
  auto w = std::make_unique<World>(empty_world());
  w->spawn(load_urdf_string(xml, "arm.urdf"), "arm", at(0, 0, 0));
  return w;
}

double arm_angle(const World& w) {
  for (const auto& j : w.joint_states("arm"))
    if (j.name == "arm_joint") return j.position;
  return NAN;
}

}  // namespace

TEST(JointPoseTrajectory, PlaysOnePointPerItsWait) {
  // (tolerance 1e-4 rad: the free joint drifts by some 1e-5 rad while the base settles on its contacts)
  // three points 0.5, 1.0, 1.5 rad, each with time_from_start 0.1 s, starting now (t = 0): upstream sets point k in
  // the step that ends at or after start + the earlier points' time_from_start: from ticks 0, 99, 199; then it ends
  auto w = arm_world();
  JointTrajectory t;
  t.joint_names = {"arm_joint"};
  for (double q : {0.5, 1.0, 1.5}) t.points.push_back({{q}, 0.1});
  EXPECT_TRUE(dynamic_cast<TrajectoryCommand*>(w->plugin("arm", "traj"))->set_trajectory(t).empty());
  w->step(50);
  EXPECT_NEAR(arm_angle(*w), 0.5, 1e-4);
  w->step(100);  // t = 0.15 s
  EXPECT_NEAR(arm_angle(*w), 1.0, 1e-4);
  w->step(100);  // t = 0.25 s
  EXPECT_NEAR(arm_angle(*w), 1.5, 1e-4);
  w->step(500);  // done: the joint stays where the last point put it
  EXPECT_NEAR(arm_angle(*w), 1.5, 1e-4);
}

TEST(JointPoseTrajectory, UnknownJointsAreReportedAndWrongPointsSkipped) {
  // "nope" is skipped; the first point has one position for two names: skipped (but its wait still counts)
  auto w = arm_world();
  JointTrajectory t;
  t.joint_names = {"arm_joint", "nope"};
  t.points.push_back({{0.7}, 0.01});
  t.points.push_back({{0.9, 0.0}, 0.01});
  const auto unknown = dynamic_cast<TrajectoryCommand*>(w->plugin("arm", "traj"))->set_trajectory(t);
  ASSERT_EQ(unknown.size(), 1u);
  EXPECT_EQ(unknown[0], "nope");
  w->step(5);
  EXPECT_NEAR(arm_angle(*w), 0.0, 1e-4);
  w->step(10);
  EXPECT_NEAR(arm_angle(*w), 0.9, 1e-4);
}

namespace {

// A trajectory through the plug-in's port (the node's path), frame `frame`: points 0.5, 1.0 rad, 0.1 s each.
CommandResult send(World& w, const std::string& frame) {
  JointTrajectory t;
  t.joint_names = {"arm_joint"};
  t.frame_id = frame;
  for (double q : {0.5, 1.0}) t.points.push_back({{q}, 0.1});
  return w.command("arm", "traj", w.plugins()[0].inputs[0].name, t);
}

}  // namespace

// UpdateStates runs at WorldUpdateBegin, where the sim time already counts the coming step: the second point (due
// 0.1 s after the first) is set in the step that starts at tick 99, so the joint reads it after step 100.
TEST(JointPoseTrajectory, APointLandsInTheStepThatEndsAtItsTime) {
  auto w = arm_world();
  ASSERT_TRUE(send(*w, "world").accepted);
  w->step(99);
  EXPECT_NEAR(arm_angle(*w), 0.5, 1e-9);
  w->step(1);
  EXPECT_NEAR(arm_angle(*w), 1.0, 1e-9);
}

// While a trajectory plays the world's physics stands still (the constructor's disable_physics_updates_): the
// arm lifted 0.5 m does not fall until the trajectory has ended (0.2 s), then falls.
TEST(JointPoseTrajectory, PhysicsStandsStillWhileATrajectoryPlays) {
  auto w = arm_world();
  ModelState s = w->model_state("arm");
  s.pose.translation().z() = 0.5;
  w->set_model_state("arm", s);
  ASSERT_TRUE(send(*w, "world").accepted);
  w->step(150);
  EXPECT_EQ(w->model_state("arm").pose.translation().z(), 0.5);
  w->step(150);
  EXPECT_LT(w->model_state("arm").pose.translation().z(), 0.45);
}

// An empty frame_id (the message's default) names no link: upstream logs and ignores the trajectory.
TEST(JointPoseTrajectory, AnEmptyFrameIdIsRefusedAsUpstream) {
  auto w = arm_world();
  const CommandResult r = send(*w, "");
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_EQ(r.notes[0].text, "ros_joint_trajectory plugin needs a reference link [] as frame_id, aborting.");
  w->step(50);
  EXPECT_NEAR(arm_angle(*w), 0.0, 1e-4);
}
