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
