// hector's IMU (libhector_gazebo_ros_imu.so) on the cube at rest: specific force (0, 0, 9.8) m/s^2, no rotation,
// plus what its sensor models add.
#include <gtest/gtest.h>

#include <cmath>

#include "../range/ray_world.hpp"
#include "hector_imu/hector_imu.hpp"

using namespace car_sim;
using namespace car_sim::test_support;

namespace {

std::string with_plugin(const std::string& keys) {
  std::string xml = cube_robot("");
  xml.insert(xml.rfind("</robot>"), "<gazebo><plugin name='imu' filename='libhector_gazebo_ros_imu.so'>"
                                    "<updateRate>100</updateRate>" + keys + "</plugin></gazebo>");
  return xml;
}

std::vector<HectorImuOut> readings(const std::string& keys, double yaw = 0) {
  World w(ray_world(""));
  Eigen::Isometry3d p = at(0, 0, yaw);
  p.translation().z() = 0.1;
  w.spawn(load_urdf_string(with_plugin(keys), "cube"), "cube", p);
  w.set_plugin_active("cube", "imu", true);
  w.step(2000);
  return w.take_outputs<HectorImuOut>();
}

double yaw_of(const Eigen::Quaterniond& q) {
  return std::atan2(2 * (q.w() * q.z() + q.x() * q.y()), 1 - 2 * (q.y() * q.y() + q.z() * q.z()));
}

}  // namespace

// 100 Hz; the cube at rest, turned by yaw 0.5: orientation yaw 0.5, rate 0, specific force (0, 0, 9.8).
TEST(HectorImu, AtRestReadsGravityAndItsYaw) {
  const auto rs = readings("", 0.5);
  ASSERT_EQ(rs.size(), 200u);
  const HectorImuOut& r = rs.back();
  EXPECT_NEAR(yaw_of(r.orientation), 0.5, 1e-3);
  EXPECT_NEAR(r.angular_velocity.norm(), 0.0, 1e-3);
  EXPECT_NEAR(r.linear_acceleration.x(), 0.0, 0.01);
  EXPECT_NEAR(r.linear_acceleration.z(), 9.8, 0.01);
}

// rateOffset (0, 0, 0.05) rad/s and yawOffset 0.2 rad: the rate reads 0.05 about z, the orientation's yaw 0.2.
TEST(HectorImu, RateAndYawOffsets) {
  const HectorImuOut r = readings("<rateOffset>0 0 0.05</rateOffset><yawOffset>0.2</yawOffset>").back();
  EXPECT_NEAR(r.angular_velocity.z(), 0.05, 1e-3);
  EXPECT_NEAR(yaw_of(r.orientation), 0.2, 1e-3);
  EXPECT_NEAR(r.rate_bias.z(), 0.05, 1e-12);
}

// accelOffset (0.1, 0, 0) m/s^2: x reads 0.1; the orientation pitches by the angle that bias would mean,
// the quaternion (1, 0, -0.5 x 0.1 / 9.8, 0) normalised: y = -0.0051.
TEST(HectorImu, AccelBiasTiltsTheOrientation) {
  const HectorImuOut r = readings("<accelOffset>0.1 0 0</accelOffset>").back();
  EXPECT_NEAR(r.linear_acceleration.x(), 0.1, 0.01);
  const double y = -0.5 * 0.1 / 9.8;
  EXPECT_NEAR(r.orientation.y(), y / std::sqrt(1 + y * y), 1e-4);
}

// rpyOffset (0, 0, 0.3): the reported orientation is turned by 0.3 about z; gravity still reads along z.
TEST(HectorImu, RpyOffsetTurnsTheFrame) {
  const HectorImuOut r = readings("<rpyOffset>0 0 0.3</rpyOffset>").back();
  EXPECT_NEAR(yaw_of(r.orientation), 0.3, 1e-3);
  EXPECT_NEAR(r.linear_acceleration.z(), 9.8, 0.01);
}

// gaussianNoise 0.02 replaces the accel and rate noise: 200 readings spread by 0.02 on each axis.
TEST(HectorImu, GaussianNoiseOnAccelAndRate) {
  const auto rs = readings("<gaussianNoise>0.02</gaussianNoise>");
  double a2 = 0, w2 = 0;
  for (const auto& r : rs) {
    a2 += r.linear_acceleration.x() * r.linear_acceleration.x();
    w2 += r.angular_velocity.y() * r.angular_velocity.y();
  }
  EXPECT_NEAR(std::sqrt(a2 / rs.size()), 0.02, 0.004);
  EXPECT_NEAR(std::sqrt(w2 / rs.size()), 0.02, 0.004);
}

TEST(HectorImu, BiasTopicFollowsTheTopic) {
  const ModelConfig cfg = resolve_plugins(load_urdf_string(with_plugin("<topicName>raw_imu</topicName>"), "cube"));
  ASSERT_EQ(cfg.plugins.size(), 1u);
  EXPECT_EQ(cfg.plugins[0].text("biasTopicName"), "raw_imu/bias");
  EXPECT_EQ(cfg.plugins[0].text("frameId"), "base");
}

TEST(HectorImu, BadOffsetIsALoadError) {
  try {
    resolve_plugins(load_urdf_string(with_plugin("<rpyOffset>0 0</rpyOffset>"), "cube"));
    FAIL() << "no error";
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("plugin[imu]/rpyOffset"), std::string::npos) << e.what();
  }
}

// Upstream's Reset zeroes orientation, velocity and accel, not the rate: a cube spun at 1 rad/s about z in the air,
// then reset_world, reads that rate in the first message after the reset (dt 0), not 0.
TEST(HectorImu, ResetKeepsTheLastRate) {
  World w(ray_world(""));
  Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
  p.translation().z() = 10.0;
  w.spawn(load_urdf_string(with_plugin(""), "cube"), "cube", p);
  w.set_plugin_active("cube", "imu", true);
  ModelState spin = w.model_state("cube");
  spin.angular = Eigen::Vector3d(0, 0, 1);
  w.set_model_state("cube", spin);
  w.step(500);
  ASSERT_NEAR(w.take_outputs<HectorImuOut>().back().angular_velocity.z(), 1.0, 1e-3);
  w.reset_poses();
  w.step(10);
  const auto rs = w.take_outputs<HectorImuOut>();
  ASSERT_FALSE(rs.empty());
  EXPECT_NEAR(rs.front().angular_velocity.z(), 1.0, 1e-3);
}
