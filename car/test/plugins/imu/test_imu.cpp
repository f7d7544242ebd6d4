// The IMU (libgazebo_ros_imu_sensor.so) on the seed car.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "imu/imu.hpp"
#include "seed_car.hpp"

using namespace car_sim;
using namespace car_sim::test_support;

namespace {

std::unique_ptr<World> world_with_imu_car() {
  // the seed car with an IMU on base_link (libgazebo_ros_imu_sensor.so), no noise
  std::string xml = car_xml(false);
  xml.insert(xml.rfind("</robot>"),
             "<gazebo reference=\"base_link\"><sensor type=\"imu\" name=\"imu\"><update_rate>100</update_rate>"
             "<plugin name=\"imu_plugin\" filename=\"libgazebo_ros_imu_sensor.so\"><topicName>imu</topicName>"
             "</plugin></sensor></gazebo>");
  auto w = std::make_unique<World>(load_world_file(std::string(CAR_SOURCE_DIR) + "/worlds/box_house.world"));
  w->spawn(load_urdf_string(xml, "car"), "mycar", Eigen::Isometry3d::Identity());
  w->set_sensor_active("mycar", "imu_plugin", true);
  return w;
}

}  // namespace

TEST(Imu, AtRestReadsGravityUp) {
  auto w = world_with_imu_car();
  w->step(1000);
  const auto imus = w->take_outputs<ImuOut>();
  ASSERT_FALSE(imus.empty());
  const ImuOut& m = imus.back();
  EXPECT_NEAR(m.linear_acceleration.z(), 9.8, 0.05);  // specific force: -g
  EXPECT_NEAR(m.angular_velocity.norm(), 0.0, 1e-3);
}

TEST(Imu, TurningOnTheSpotReadsTheYawRate) {
  auto w = world_with_imu_car();
  w->set_cmd_vel("mycar", 0.0, 1.0);
  w->step(2000);
  const auto imus = w->take_outputs<ImuOut>();
  ASSERT_FALSE(imus.empty());
  EXPECT_NEAR(imus.back().angular_velocity.z(), 1.0, 0.02);
  EXPECT_EQ(imus.size(), 200u);  // 100 Hz for 2 s
}

// The model plug-in libgazebo_ros_imu.so has p3d's rate control: at 30 Hz every 34 ms (test_update_clock.cpp).
TEST(Imu, ModelPluginAtThirtyHertzIsEveryThirtyFourMilliseconds) {
  std::string xml = car_xml(false);
  xml.insert(xml.rfind("</robot>"),
             "<gazebo><plugin name=\"imu\" filename=\"libgazebo_ros_imu.so\"><bodyName>base_link</bodyName>"
             "<topicName>imu</topicName><updateRate>30</updateRate></plugin></gazebo>");
  World w(empty_world());
  w.spawn(load_urdf_string(xml, "car"), "mycar", Eigen::Isometry3d::Identity());
  w.set_plugin_active("mycar", "imu", true);
  w.step(200);
  std::vector<uint64_t> ticks;
  for (const ImuOut& m : w.take_outputs<ImuOut>()) ticks.push_back(m.tick);
  EXPECT_EQ(ticks, (std::vector<uint64_t>{34, 68, 102, 136, 170}));
}
