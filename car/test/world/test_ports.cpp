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
  EXPECT_EQ(ports[0].type, sample_type<OdometrySample>());
  EXPECT_EQ(ports[1].type, sample_type<JointStatesSample>());
  EXPECT_EQ(ports[2].type, sample_type<JointTransformsSample>());
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

// p3d, as the ROS node attaches it for ground truth: header.frame_id under the tf_prefix of its own namespace, the
// child frame as written (p3d.cpp Load: getParam("tf_prefix")), gaussianNoise 0.1 m giving
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
  EXPECT_EQ(p.type, sample_type<OdometrySample>());
  EXPECT_EQ(p.topic, "/gazebo/ground_truth/mycar");
  EXPECT_EQ(p.queue, 100u);
  EXPECT_EQ(p.frame, "world");
  EXPECT_EQ(p.child_frame, "base_footprint");
  EXPECT_EQ(p.frame_rule, FrameRule::PrefixHere);
  EXPECT_EQ(p.tf, TfOrder::None);
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(p.pose_covariance[i], 0.01, 1e-15);
    EXPECT_NEAR(p.twist_covariance[i], 0.01, 1e-15);
  }
}

// ---- sensors: laser, range, imu, gps, magnetic, wrench, contacts, pose ----

namespace {

std::vector<OutputPort> attached_ports(const std::string& filename, const ParamList& params) {
  auto w = world_with_car(false);
  PluginSpec spec;
  spec.name = "probe";
  spec.filename = filename;
  spec.params = params;
  w->attach_plugin("mycar", spec);
  for (const auto& p : w->plugins())
    if (p.config.name == "probe") return p.outputs;
  return {};
}

}  // namespace

// hector_imu's covariances as its upstream Load writes them, at g = 9.8 m/s^2: rate noise (0.01, 0.02, 0.03)^2 =
// (1e-4, 4e-4, 9e-4); accel noise (0.1, 0.2, 0.3)^2 = (0.01, 0.04, 0.09); orientation roll 0.1^2 / 9.8^2 =
// 0.01 / 96.04, pitch 0.04 / 96.04, yaw the yaw noise 0.05^2 = 0.0025. Frame frameId, queue 10.
TEST(WorldPorts, HectorImuCovariancesFromItsNoise) {
  const auto ports = attached_ports("libhector_gazebo_ros_imu.so",
                                    {{"frameId", "/imu_link"}, {"accelGaussianNoise", "0.1 0.2 0.3"},
                                     {"rateGaussianNoise", "0.01 0.02 0.03"}, {"yawGaussianNoise", "0.05"}});
  ASSERT_EQ(ports.size(), 2u);
  const OutputPort& p = ports[0];
  EXPECT_EQ(p.type, sample_type<ImuSample>());
  EXPECT_EQ(p.name, "imu");
  EXPECT_EQ(p.frame, "imu_link");  // a Frame key loses its leading '/' when resolved
  EXPECT_EQ(p.frame_rule, FrameRule::NoPrefix);
  EXPECT_EQ(p.queue, 10u);
  EXPECT_NEAR(p.angular_velocity_covariance[0], 1e-4, 1e-18);
  EXPECT_NEAR(p.angular_velocity_covariance[1], 4e-4, 1e-18);
  EXPECT_NEAR(p.angular_velocity_covariance[2], 9e-4, 1e-18);
  EXPECT_NEAR(p.linear_acceleration_covariance[0], 0.01, 1e-17);
  EXPECT_NEAR(p.linear_acceleration_covariance[1], 0.04, 1e-17);
  EXPECT_NEAR(p.linear_acceleration_covariance[2], 0.09, 1e-17);
  EXPECT_NEAR(p.orientation_covariance[0], 0.01 / 96.04, 1e-18);
  EXPECT_NEAR(p.orientation_covariance[1], 0.04 / 96.04, 1e-18);
  EXPECT_NEAR(p.orientation_covariance[2], 0.0025, 1e-18);
}

// a non-zero gaussianNoise 0.5 replaces both accel and rate noise: 0.25 on their diagonals, 0.25 / 96.04 roll
TEST(WorldPorts, HectorImuGaussianNoiseReplacesAccelAndRate) {
  const auto ports = attached_ports("libhector_gazebo_ros_imu.so",
                                    {{"gaussianNoise", "0.5"}, {"accelGaussianNoise", "0.1 0.2 0.3"}});
  ASSERT_EQ(ports.size(), 2u);
  EXPECT_NEAR(ports[0].linear_acceleration_covariance[1], 0.25, 1e-17);
  EXPECT_NEAR(ports[0].angular_velocity_covariance[2], 0.25, 1e-17);
  EXPECT_NEAR(ports[0].orientation_covariance[0], 0.25 / 96.04, 1e-18);
}

// the biases: topicName + "/bias", no covariances
TEST(WorldPorts, HectorImuBiasPort) {
  const auto ports = attached_ports("libhector_gazebo_ros_imu.so", {{"topicName", "/himu"}});
  ASSERT_EQ(ports.size(), 2u);
  EXPECT_EQ(ports[1].name, "bias");
  EXPECT_EQ(ports[1].type, sample_type<ImuSample>());
  EXPECT_EQ(ports[1].topic, "/himu/bias");
  const std::array<double, 3> none = {0, 0, 0};
  EXPECT_EQ(ports[1].orientation_covariance, none);
  EXPECT_EQ(ports[1].linear_acceleration_covariance, none);
}

// the fix, then the velocity (the order the messages go out in)
TEST(WorldPorts, HectorGpsFixThenVelocity) {
  const auto ports = attached_ports("libhector_gazebo_ros_gps.so",
                                    {{"topicName", "/fix"}, {"velocityTopicName", "/fix_velocity"}});
  ASSERT_EQ(ports.size(), 2u);
  EXPECT_EQ(ports[0].type, sample_type<NavSatFixSample>());
  EXPECT_EQ(ports[0].topic, "/fix");
  EXPECT_EQ(ports[1].type, sample_type<Vector3Sample>());
  EXPECT_EQ(ports[1].topic, "/fix_velocity");
}

// useMagneticFieldMsgs picks sensor_msgs/MagneticField over Vector3Stamped
TEST(WorldPorts, HectorMagneticMessageType) {
  EXPECT_EQ(attached_ports("libhector_gazebo_ros_magnetic.so", {}).at(0).type, sample_type<Vector3Sample>());
  EXPECT_EQ(attached_ports("libhector_gazebo_ros_magnetic.so", {{"useMagneticFieldMsgs", "true"}}).at(0).type,
            sample_type<MagneticFieldSample>());
}

// TF world -> <frameId>_actual, frameId's leading '/' dropped
TEST(WorldPorts, HandOfGodActualPoseOnTf) {
  const auto ports = attached_ports("libgazebo_ros_hand_of_god.so", {{"linkName", "base_footprint"}, {"frameId", "/hog"}});
  ASSERT_EQ(ports.size(), 1u);
  EXPECT_EQ(ports[0].type, sample_type<TransformSample>());
  EXPECT_EQ(ports[0].topic, "");
  EXPECT_EQ(ports[0].frame, "world");
  EXPECT_EQ(ports[0].child_frame, "hog_actual");
}
