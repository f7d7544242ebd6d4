// hector_gazebo_plugins' vector sensor models (IMU accel/rate, GPS position/velocity) as husky_description and
// jackal_description write them: only some keys given. A key not written keeps upstream's default and is not
// reported; one number written for a vector key is (upstream cannot read it). Found trying husky (issue 19 item 7).
#include <gtest/gtest.h>

#include "car_sim/description.hpp"
#include "car_sim/plugins.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

// A 1 kg box robot with one hector plug-in holding KEYS.
std::string robot_with(const std::string& filename, const std::string& keys) {
  return R"(<robot name="hector_bot"><link name="base_link"><inertial><mass value="1"/>
      <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
      <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
      <gazebo><plugin name="p" filename=")" + filename + R"(">)" + keys + R"(</plugin></gazebo></robot>)";
}

// Warnings with code key-value among the resolved plug-ins' diagnostics.
std::vector<std::string> key_value_warnings(const std::string& xml) {
  const ModelConfig c = resolve_plugins(load_urdf_string(xml, "hector_bot"));
  std::vector<std::string> out;
  for (const auto& d : c.diagnostics)
    if (d.code == "key-value") out.push_back(d.element);
  return out;
}

}  // namespace

TEST(Zoo19HectorDefaults, GpsWithOnlyDriftWrittenHasNoWarning) {
  // husky's gps_controller: <drift> given as three numbers, every other model key left out
  EXPECT_TRUE(key_value_warnings(robot_with("libhector_gazebo_ros_gps.so", "<bodyName>base_link</bodyName>"
                                                                           "<drift>0.0001 0.0001 0.0001</drift>"))
                  .empty());
}

TEST(Zoo19HectorDefaults, ImuWithDriftAndNoiseOnlyHasNoWarning) {
  // husky's imu_controller: accel/rate drift and noise as three numbers, heading ones as one number
  EXPECT_TRUE(key_value_warnings(robot_with("libhector_gazebo_ros_imu.so",
                                            "<bodyName>base_link</bodyName><accelDrift>0.005 0.005 0.005</accelDrift>"
                                            "<accelGaussianNoise>0.005 0.005 0.005</accelGaussianNoise>"
                                            "<rateDrift>0.005 0.005 0.005 </rateDrift>"
                                            "<headingDrift>0.005</headingDrift>"))
                  .empty());
}

TEST(Zoo19HectorDefaults, OneNumberWrittenForAVectorKeyIsStillReported) {
  const auto w = key_value_warnings(
      robot_with("libhector_gazebo_ros_gps.so", "<bodyName>base_link</bodyName><offset>0.5</offset>"));
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("offset"), std::string::npos) << w[0];
}
