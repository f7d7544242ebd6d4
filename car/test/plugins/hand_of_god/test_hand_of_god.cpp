// libgazebo_ros_hand_of_god.so: a 10 kg box pulled to a target pose; values worked out by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "car_sim/world.hpp"
#include "hand_of_god/hand_of_god.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

std::unique_ptr<World> hog_world() {
  const std::string xml = R"(<robot name="hog">
  <link name="body">
    <inertial><mass value="10"/><origin xyz="0 0 0.1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0 0 0.1"/><geometry><box size="0.4 0.4 0.2"/></geometry></collision>
  </link>
  <gazebo><plugin name="hog" filename="libgazebo_ros_hand_of_god.so"><linkName>body</linkName></plugin></gazebo>
</robot>)";
  auto w = std::make_unique<World>(empty_world());
  w->spawn(load_urdf_string(xml, "hog.urdf"), "hog", at(0, 0, 0));
  return w;
}

}  // namespace

TEST(HandOfGod, WrenchIsTheSpringAndDamper) {
  // 1 m short along x, at rest: force kl * 1 = 200 N along x; target turned 0.2 rad about z: torque ka * 0.1
  // (half the angle: ignition's Quaternion::Log) = 20 N m about z
  Eigen::Isometry3d target = Eigen::Isometry3d::Identity();
  target.translation() = Eigen::Vector3d(1, 0, 0);
  target.linear() = Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Wrench w = hand_of_god_wrench(Eigen::Isometry3d::Identity(), Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 0, 0),
                                      target, 200, 200, 89.4, 8.9);
  EXPECT_NEAR(w.force.x(), 200.0, 1e-9);
  EXPECT_NEAR(w.torque.z(), 20.0, 1e-9);
  // moving at 1 m/s toward it: the damper takes cl * 1 off
  const Wrench d = hand_of_god_wrench(Eigen::Isometry3d::Identity(), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 0, 0),
                                      target, 200, 200, 89.4, 8.9);
  EXPECT_NEAR(d.force.x(), 200.0 - 89.4, 1e-9);
}

TEST(HandOfGod, FloatsWithoutATarget) {
  // gravity off for the link: lifted 1 mm above the ground it stays there (no target, no force)
  auto w = hog_world();
  ModelState s = w->model_state("hog");
  s.pose.translation().z() = 0.001;
  w->set_model_state("hog", s);
  w->step(1000);
  EXPECT_NEAR(w->model_state("hog").pose.translation().z(), 0.001, 1e-6);
}

TEST(HandOfGod, ReachesTheTargetPose) {
  // kl = 200 N/m on m = 10 kg with cl = 2 sqrt(kl m): critically damped at wn = sqrt(kl / m) = 4.47 rad/s; from
  // 0.84 m away the error after 3 s is 0.84 (1 + wn t) e^(-wn t) = 0.84 * 14.4 * 1.5e-6 = 1.8e-5 m. The yaw
  // spring (ka/2 effective, ca = 2 sqrt(ka Ixx): damping ratio sqrt(2)) settles at its slow pole
  // 31.6 (1.414 - 1) = 13 rad/s, long before 3 s.
  auto w = hog_world();
  Eigen::Isometry3d target = Eigen::Isometry3d::Identity();
  target.translation() = Eigen::Vector3d(0.5, -0.3, 0.6);
  target.linear() = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  dynamic_cast<PoseTarget*>(w->plugin("hog", "hog"))->set_target(target);
  w->set_plugin_active("hog", "hog", true);  // the actual-pose output (the pull runs regardless)
  w->step(3000);
  const Eigen::Isometry3d p = w->model_state("hog").pose;
  EXPECT_NEAR((p.translation() - target.translation()).norm(), 0.0, 1e-3);
  EXPECT_NEAR(std::atan2(p.linear()(1, 0), p.linear()(0, 0)), 0.5, 1e-3);
  const OutputQueue q = w->take_outputs();
  ASSERT_EQ(q.size(), 3000u);  // the actual pose every step
  EXPECT_TRUE(dynamic_cast<const PoseOut&>(*q.back()).pose.isApprox(p, 1e-12));
}

// Upstream's UpdateChild returns before its TF when the lookup of <frameId>_desired fails: no <frameId>_actual
// until a target was found.
TEST(HandOfGod, SendsNoActualPoseBeforeATarget) {
  auto w = hog_world();
  w->set_plugin_active("hog", "hog", true);
  w->step(10);
  EXPECT_TRUE(w->take_outputs().empty());
}

// A lookup that fails later (PoseCommand found = false): neither force nor actual pose for that update; the box,
// pulled up toward a target 1 m above, then coasts at the speed it had (its gravity stays off).
TEST(HandOfGod, AFailedLookupStopsThePull) {
  auto w = hog_world();
  w->set_plugin_active("hog", "hog", true);
  Eigen::Isometry3d target = Eigen::Isometry3d::Identity();
  target.translation() = Eigen::Vector3d(0, 0, 1);
  PoseCommand found;
  found.pose = target;
  w->command("hog", "hog", w->plugins()[0].inputs[0].name, found);
  w->step(100);
  w->take_outputs();
  PoseCommand lost;
  lost.found = false;
  w->command("hog", "hog", w->plugins()[0].inputs[0].name, lost);
  const double v0 = w->model_state("hog").linear.z();
  w->step(50);
  EXPECT_TRUE(w->take_outputs().empty());
  EXPECT_GT(v0, 0.1);
  EXPECT_NEAR(w->model_state("hog").linear.z(), v0, 1e-6);
}
