// Output ports resolved in the core (PluginInfo::outputs), on the seed car's diff drive: <robotNamespace>/ (global),
// odometryTopic odom, odometryFrame odom, robotBaseFrame base_footprint, publishWheelJointState and publishWheelTF
// true, publishOdomTF at its default (true). Queues and covariances as gazebo_ros_diff_drive.cpp writes them.
#include <gtest/gtest.h>

#include "seed_car.hpp"

using namespace car_sim;
using namespace car_sim::test_support;

namespace {

std::vector<OutputPort> drive_ports() {
  auto w = world_with_car(false);
  for (const auto& p : w->plugins())
    if (p.config.name == "differential_drive_controller") return p.outputs;
  return {};
}

}  // namespace

TEST(WorldPorts, DiffDriveHasOdometryJointStatesAndWheelTf) {
  const auto ports = drive_ports();
  ASSERT_EQ(ports.size(), 3u);
  EXPECT_EQ(ports[0].type, SampleType::Odometry);
  EXPECT_EQ(ports[1].type, SampleType::JointStates);
  EXPECT_EQ(ports[2].type, SampleType::JointTransforms);
}

TEST(WorldPorts, DiffDriveOdometryTopicFramesAndTf) {
  const OutputPort p = drive_ports().at(0);
  EXPECT_EQ(p.topic, "/odom");
  EXPECT_EQ(p.queue, 100u);
  EXPECT_EQ(p.ns, "");
  EXPECT_EQ(p.frame, "odom");
  EXPECT_EQ(p.child_frame, "base_footprint");
  EXPECT_EQ(p.tf, TfOrder::After);
}

// pose (1e-5, 1e-5, 1e12, 1e12, 1e12, 1e-3); no twist covariance
TEST(WorldPorts, DiffDriveOdometryCovariance) {
  const OutputPort p = drive_ports().at(0);
  const std::array<double, 6> pose = {1e-5, 1e-5, 1e12, 1e12, 1e12, 1e-3}, twist = {0, 0, 0, 0, 0, 0};
  EXPECT_EQ(p.pose_covariance, pose);
  EXPECT_EQ(p.twist_covariance, twist);
}

TEST(WorldPorts, DiffDriveWheelJointStatesTopic) {
  const OutputPort p = drive_ports().at(1);
  EXPECT_EQ(p.topic, "/joint_states");
  EXPECT_EQ(p.queue, 10u);
}

// p3d, as the ROS node attaches it for ground truth: its frames untouched by tf_prefix, gaussianNoise 0.1 m giving
// the variance 0.01 on every diagonal entry of pose and twist, queue 100
TEST(WorldPorts, P3dOdometryPort) {
  auto w = world_with_car(false);
  PluginSpec truth;
  truth.name = "truth";
  truth.filename = "libgazebo_ros_p3d.so";
  truth.params = {{"bodyName", "base_footprint"}, {"topicName", "/gazebo/ground_truth/mycar"}, {"frameName", "world"},
                  {"gaussianNoise", "0.1"}};
  w->attach_plugin("mycar", truth);
  std::vector<OutputPort> ports;
  for (const auto& p : w->plugins())
    if (p.config.name == "truth") ports = p.outputs;
  ASSERT_EQ(ports.size(), 1u);
  const OutputPort& p = ports[0];
  EXPECT_EQ(p.type, SampleType::Odometry);
  EXPECT_EQ(p.topic, "/gazebo/ground_truth/mycar");
  EXPECT_EQ(p.queue, 100u);
  EXPECT_EQ(p.frame, "world");
  EXPECT_EQ(p.child_frame, "base_footprint");
  EXPECT_FALSE(p.tf_prefix);
  EXPECT_EQ(p.tf, TfOrder::None);
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(p.pose_covariance[i], 0.01, 1e-15);
    EXPECT_NEAR(p.twist_covariance[i], 0.01, 1e-15);
  }
}
