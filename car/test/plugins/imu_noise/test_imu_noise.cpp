// The SDF imu sensor's <noise> on the imu kind: the cube at rest reads (0, 0, 0) rad/s and (0, 0, 9.8) m/s^2
// (the specific force of standing on the ground), plus the configured noise.
#include <gtest/gtest.h>

#include <cmath>

#include "../range/ray_world.hpp"
#include "imu/imu.hpp"  // ImuOut

using namespace car_sim;
using namespace car_sim::test_support;

namespace {

std::string imu_sensor(const std::string& imu) {
  return "<sensor type='imu' name='imu'><update_rate>100</update_rate><imu>" + imu +
         "</imu><plugin name='imu_plugin' filename='libgazebo_ros_imu_sensor.so'><topicName>imu</topicName>"
         "<frameName>base</frameName><updateRateHZ>100</updateRateHZ></plugin></sensor>";
}

std::string axis(const char* axis, const std::string& noise) {
  return std::string("<") + axis + "><noise type='gaussian'>" + noise + "</noise></" + axis + ">";
}

std::vector<ImuOut> readings(const std::string& imu, uint64_t seed = 0) {
  auto w = world_with_cube(ray_world(""), imu_sensor(imu), 0, 0, 0, seed);
  w->set_sensor_active("cube", "imu_plugin", true);
  w->step(3000);  // 300 readings at 100 Hz
  return w->take_outputs<ImuOut>();
}

}  // namespace

// linear_acceleration/z: mean 0.5 m/s^2, no spread: every reading 9.8 + 0.5; x and y untouched.
TEST(ImuNoise, PerAxisMeanShiftsThatAxisOnly) {
  const auto rs = readings("<linear_acceleration>" + axis("z", "<mean>0.5</mean><stddev>0</stddev>") +
                           "</linear_acceleration>");
  ASSERT_EQ(rs.size(), 300u);
  for (size_t i = 10; i < rs.size(); ++i) {
    EXPECT_NEAR(rs[i].linear_acceleration.z(), 9.8 + 0.5, 0.01) << i;
    EXPECT_NEAR(rs[i].linear_acceleration.x(), 0.0, 0.01) << i;
  }
}

// angular_velocity/x: stddev 0.01 rad/s around 0 over 300 readings; y and z stay at rest.
TEST(ImuNoise, PerAxisStddevIsTheSpread) {
  const auto rs = readings("<angular_velocity>" + axis("x", "<mean>0</mean><stddev>0.01</stddev>") +
                           "</angular_velocity>");
  double sum = 0, sum2 = 0;
  for (const auto& r : rs) {
    sum += r.angular_velocity.x();
    sum2 += r.angular_velocity.x() * r.angular_velocity.x();
    EXPECT_NEAR(r.angular_velocity.y(), 0.0, 1e-3);
  }
  const double n = static_cast<double>(rs.size());
  EXPECT_LT(std::abs(sum / n), 4 * 0.01 / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.01, 0.0015);
}

// bias_mean 0.2 rad/s, bias_stddev 0: one bias of +-0.2 (Gazebo picks the sign at random), the same in every
// reading; the same seed picks the same sign.
TEST(ImuNoise, BiasIsDrawnOnceWithARandomSign) {
  const std::string imu = "<angular_velocity>" + axis("z", "<bias_mean>0.2</bias_mean>") + "</angular_velocity>";
  const auto rs = readings(imu, 3);
  const double b = rs[10].angular_velocity.z();
  EXPECT_NEAR(std::abs(b), 0.2, 1e-3);
  for (size_t i = 10; i < rs.size(); ++i) EXPECT_NEAR(rs[i].angular_velocity.z(), b, 1e-3) << i;
  EXPECT_EQ(readings(imu, 3)[10].angular_velocity.z(), b);
}

// The old form <noise><type>gaussian</type><rate>..</rate><accel>..</accel></noise>: all three axes.
TEST(ImuNoise, OldRateAndAccelBlocksApplyToEveryAxis) {
  const auto rs = readings("<noise><type>gaussian</type><rate><mean>0.1</mean></rate><accel><mean>-0.3</mean>"
                           "</accel></noise>");
  const ImuOut& r = rs.back();
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(r.angular_velocity[k], 0.1, 1e-3) << k;
  EXPECT_NEAR(r.linear_acceleration.x(), -0.3, 0.01);
  EXPECT_NEAR(r.linear_acceleration.z(), 9.8 - 0.3, 0.01);
}

TEST(ImuNoise, NegativeStddevIsALoadError) {
  try {
    World w(ray_world(""));
    w.spawn(load_urdf_string(cube_robot(imu_sensor("<linear_acceleration>" + axis("y", "<stddev>-1</stddev>") +
                                                    "</linear_acceleration>")),
                             "cube"),
            "cube", at(0, 0, 0));
    FAIL() << "no error";
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("sensor[imu]/imu/linear_acceleration/y/noise/stddev"), std::string::npos)
        << e.what();
  }
}
