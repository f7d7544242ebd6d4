// libgazebo_ros_planar_move.so: a frictionless box base in the empty world, values worked out by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "car_sim/drive.hpp"
#include "car_sim/sdf_model.hpp"
#include "car_sim/world.hpp"
#include "planar_move/planar_move.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

// A 0.4 x 0.4 x 0.2 m box of 10 kg standing on the ground (mu 0: the ground cannot drag it) with planar_move.
std::string box_robot(const std::string& plugin_keys) {
  return R"(<robot name="box">
  <link name="base_footprint">
    <inertial><mass value="10"/><origin xyz="0 0 0.1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0 0 0.1"/><geometry><box size="0.4 0.4 0.2"/></geometry></collision>
  </link>
  <gazebo reference="base_footprint"><mu1>0</mu1><mu2>0</mu2></gazebo>
  <gazebo><plugin name="move" filename="libgazebo_ros_planar_move.so">)" +
         plugin_keys + R"(</plugin></gazebo>
</robot>)";
}

std::unique_ptr<World> world_with(const std::string& keys) {
  auto w = std::make_unique<World>(empty_world());
  w->spawn(load_urdf_string(box_robot(keys), "box.urdf"), "box", at(0, 0, 0));
  return w;
}

double yaw_of(const Eigen::Isometry3d& p) { return std::atan2(p.linear()(1, 0), p.linear()(0, 0)); }

}  // namespace

TEST(PlanarMove, WorldVelocityRotatesTheBodyCommandByYaw) {
  // yaw 90 deg: body x is world y, body y is world -x
  const Eigen::Vector2d v = planar_world_velocity(1.0, 0.5, M_PI / 2);
  EXPECT_NEAR(v.x(), -0.5, 1e-12);
  EXPECT_NEAR(v.y(), 1.0, 1e-12);
}

TEST(PlanarMove, TwistGivesTheArcAfterT) {
  // Body twist (vx, vy, w) = (0.5, 0.2, 0.5) held for T = 2 s from the origin at yaw 0. With yaw(t) = w t:
  //   x(T) = int_0^T (vx cos wt - vy sin wt) dt = (vx sin wT + vy (cos wT - 1)) / w
  //        = (0.5 * 0.841471 + 0.2 * (0.540302 - 1)) / 0.5 = 0.657592 m
  //   y(T) = int_0^T (vy cos wt + vx sin wt) dt = (vy sin wT + vx (1 - cos wT)) / w
  //        = (0.2 * 0.841471 + 0.5 * (1 - 0.540302)) / 0.5 = 0.796286 m
  //   yaw(T) = w T = 1 rad.
  // Upstream sets the velocity from the yaw at the start of each 1 ms step; that lags the heading by w dt per
  // step: at most |v| w dt T = 0.54 * 0.5 * 0.001 * 2 = 0.54 mm over the arc, so a 1 mm tolerance.
  auto w = world_with("<odometryRate>20</odometryRate>");
  Twist t;
  t.linear = Eigen::Vector3d(0.5, 0.2, 0.0);
  t.angular.z() = 0.5;
  w->set_cmd_vel("box", t);
  w->step(2000);
  const ModelState s = w->model_state("box");
  EXPECT_NEAR(s.pose.translation().x(), 0.657592, 1e-3);
  EXPECT_NEAR(s.pose.translation().y(), 0.796286, 1e-3);
  EXPECT_NEAR(yaw_of(s.pose), 1.0, 1e-3);
  EXPECT_NEAR(s.pose.translation().z(), 0.0, 1e-3);  // z velocity held at 0: neither sinks nor jumps
}

// Upstream's clock (docs/COMPAT-plugins.md): odometry when more than 1/20 s has passed since the last, counted at
// the sim time after the step, then last = that time. 50 ms of whole steps is not more than 0.05 (as a double it is
// equal), so the first goes out on the state after step 50 (t = 51 ms since the load at 0) and then every 51 steps:
// ticks 50, 101, 152, ..., 50 + 38 * 51 = 1988 in 2 s: 39 messages (19.6 Hz).
TEST(PlanarMove, OdometryEveryPeriodAndOneStepAsUpstream) {
  auto w = world_with("<odometryRate>20</odometryRate>");
  w->step(2000);
  const OutputQueue out = w->take_outputs();
  ASSERT_EQ(out.size(), 39u);
  for (size_t i = 0; i < out.size(); ++i) EXPECT_EQ(out[i]->tick, 50u + 51u * i) << i;
}

TEST(PlanarMove, OdometryTwistIsTheFiniteDifferenceOverItsPeriod) {
  // A body moving at (0.5, 0.2) m/s while turning at 0.5 rad/s, seen over upstream's 51 ms (the test above): the
  // chord of an arc, |v| sin(w P / 2) / (w P / 2) = |v| (1 - 2.7e-5), so within 1e-3 of the command in the base
  // frame, rotated by the end-of-period yaw: a lag of w P / 2 = 12.75 mrad turns (0.5, 0.2) by that angle (x 0.5 +
  // 0.2 * 0.01275, y 0.2 - 0.5 * 0.01275). The last message (tick 1988) has yaw 0.5 * 1.988.
  auto w = world_with("<odometryRate>20</odometryRate>");
  Twist t;
  t.linear = Eigen::Vector3d(0.5, 0.2, 0.0);
  t.angular.z() = 0.5;
  w->set_cmd_vel("box", t);
  w->step(2000);
  const OutputQueue out = w->take_outputs();
  ASSERT_EQ(out.size(), 39u);
  const auto& o = dynamic_cast<const OdometryOut&>(*out.back());
  EXPECT_EQ(o.tick, 1988u);
  EXPECT_NEAR(o.linear.x(), 0.5 + 0.2 * 0.01275, 1e-3);
  EXPECT_NEAR(o.linear.y(), 0.2 - 0.5 * 0.01275, 1e-3);
  EXPECT_NEAR(o.angular.z(), 0.5, 1e-3);
  EXPECT_NEAR(yaw_of(o.pose), 0.5 * 1.988, 1e-3);
}

TEST(PlanarMove, CmdTimeoutStopsTheBase) {
  // cmdTimeout 0.5 s: 1 m/s forward moves 0.5 m (+ one 1 ms step), then stops
  auto w = world_with("<cmdTimeout>0.5</cmdTimeout>");
  w->set_cmd_vel("box", 1.0, 0.0);
  w->step(2000);
  EXPECT_NEAR(w->model_state("box").pose.translation().x(), 0.5, 2e-3);
}

// Upstream publishes odometry only when odometryRate > 0: a negative rate is no odometry, warned, not refused.
TEST(PlanarMove, NegativeOdometryRateIsNoOdometryAndWarned) {
  auto w = world_with("<odometryRate>-1</odometryRate>");
  w->step(200);
  EXPECT_TRUE(w->take_outputs().empty());
  std::vector<std::string> messages;
  for (const Diagnostic& d : resolve_plugins(load_urdf_string(box_robot("<odometryRate>-1</odometryRate>"), "box.urdf")).diagnostics)
    if (d.element == "gazebo/plugin[move]/odometryRate") messages.push_back(d.message);
  EXPECT_EQ(messages, std::vector<std::string>{"<odometryRate> -1 is not > 0: no odometry, as upstream"});
}

// publishOdometry fills position x and y only (z stays 0 in the message); the TF carries the pose's z.
TEST(PlanarMove, OdometryMessageIsPlanar) {
  auto w = world_with("<odometryRate>20</odometryRate>");
  const PluginInfo p = w->plugins()[0];
  ASSERT_EQ(p.outputs.size(), 1u);
  EXPECT_TRUE(p.outputs[0].planar_position);
  EXPECT_EQ(p.outputs[0].tf, TfOrder::Before);
}

// Model::SetLinearVel sets each link's centre-of-mass velocity: a base whose centre of mass is 0.2 m ahead of its
// origin, turning on the spot at 1 rad/s, turns about its centre of mass (which stays put) while its origin
// circles it: after pi/2 s the origin is at com + 0.2 (cos(pi + pi/2), sin(pi + pi/2)) = (0.2, -0.2).
TEST(PlanarMove, TurnsAboutTheCentreOfMass) {
  const std::string xml = R"(<robot name="box">
  <link name="base_footprint">
    <inertial><mass value="10"/><origin xyz="0.2 0 0.1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0.2 0 0.1"/><geometry><box size="0.4 0.4 0.2"/></geometry></collision>
  </link>
  <gazebo reference="base_footprint"><mu1>0</mu1><mu2>0</mu2></gazebo>
  <gazebo><plugin name="move" filename="libgazebo_ros_planar_move.so"><cmdTimeout>-1</cmdTimeout></plugin></gazebo>
</robot>)";
  World w(empty_world());
  w.spawn(load_urdf_string(xml, "box.urdf"), "box", at(0, 0, 0));
  Twist t;
  t.angular.z() = 1.0;
  w.command("box", "move", w.plugins()[0].inputs[0].name, t);
  w.step(static_cast<uint64_t>(std::lround(M_PI / 2 * 1000)));
  const Eigen::Isometry3d p = w.model_state("box").pose;
  EXPECT_NEAR(p.translation().x(), 0.2, 2e-3);
  EXPECT_NEAR(p.translation().y(), -0.2, 2e-3);
}

// Gazebo's planar_move publishes parent_->WorldPose(), the model frame. An SDF model whose only link sits 0.3 m
// ahead of the model frame, at rest at the origin on a frictionless ground, reads (0, 0); the link's own pose, what
// car published before, reads (0.3, 0).
TEST(PlanarMove, OdometryOfAnSdfModelIsItsModelFrame) {
  const SdfRobot r = load_sdf_model_string(R"(<?xml version='1.0'?><sdf version='1.7'><model name='box'>
  <link name='base'><pose>0.3 0 0 0 0 0</pose>
    <inertial><pose>0 0 0.1 0 0 0</pose><mass>10</mass>
      <inertia><ixx>0.1</ixx><iyy>0.1</iyy><izz>0.1</izz><ixy>0</ixy><ixz>0</ixz><iyz>0</iyz></inertia></inertial>
    <collision name='c'><pose>0 0 0.1 0 0 0</pose><geometry><box><size>0.4 0.4 0.2</size></box></geometry>
      <surface><friction><ode><mu>0</mu><mu2>0</mu2></ode></friction></surface></collision>
  </link>
  <plugin name='move' filename='libgazebo_ros_planar_move.so'><odometryRate>20</odometryRate></plugin>
</model></sdf>)");
  World w(empty_world());
  w.spawn_sdf(r, "box", at(0, 0, 0));
  w.step(100);
  const OutputQueue out = w.take_outputs();
  ASSERT_FALSE(out.empty());
  const auto& o = dynamic_cast<const OdometryOut&>(*out.back());
  EXPECT_NEAR(o.pose.translation().x(), 0.0, 1e-4);
  EXPECT_NEAR(o.pose.translation().y(), 0.0, 1e-4);
}
