// A `ray` sensor does not see its own rigid body (Gazebo's ODE rays: ODE collides no two geoms of one body), a
// `gpu_ray` sensor does (Gazebo renders it). Kobuki's cliff sensors start inside its base cylinder. No gravity; the
// probe's body is a 0.4 m cube about the sensors' origin, one ray each along +x (range [0.05, 10] m), and a static
// wall's near face is the plane x = 2 m.
#include <gtest/gtest.h>

#include <string>

#include "car_sim/world.hpp"
#include "laser/laser.hpp"

using namespace car_sim;

namespace {

std::string sensor(const std::string& type, const std::string& file) {
  return R"(<gazebo reference="body"><sensor type=")" + type + R"(" name=")" + type + R"("><update_rate>1000</update_rate>
    <ray><scan><horizontal><samples>1</samples><resolution>1</resolution><min_angle>0</min_angle>
    <max_angle>0</max_angle></horizontal></scan><range><min>0.05</min><max>10</max><resolution>0.01</resolution>
    </range></ray><plugin name=")" + type + R"(" filename=")" + file + R"("><topicName>)" + type +
         R"(</topicName><frameName>body</frameName></plugin></sensor></gazebo>)";
}

// The first ray's range [m] of the sensor (plug-in) named type after one step.
float range_of(const std::string& type) {
  auto w = std::make_unique<World>(load_world_string(R"(<?xml version="1.0"?>
<sdf version="1.6"><world name="lab"><gravity>0 0 0</gravity>
  <model name="wall"><static>true</static><pose>2.1 0 1 0 0 0</pose><link name="l">
    <collision name="c"><geometry><box><size>0.2 4 4</size></box></geometry></collision></link></model>
</world></sdf>)"));
  const std::string urdf = R"(<?xml version="1.0"?><robot name="probe"><link name="body">
    <inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.4 0.4 0.4"/></geometry></collision></link>)" +
                           sensor("ray", "libgazebo_ros_laser.so") + sensor("gpu_ray", "libgazebo_ros_gpu_laser.so") +
                           "</robot>";
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(0, 0, 1);
  w->spawn(load_urdf_string(urdf, "probe"), "probe", pose);
  w->set_sensor_active("probe", type, true);
  w->step(1);
  const auto scans = w->take_outputs<LaserScanOut>();
  EXPECT_EQ(scans.size(), 1u);
  return scans.empty() ? -1.f : scans.back().ranges.at(0);
}

}  // namespace

// The ray leaves the cube at 0.2 m and goes on to the wall: 2 m.
TEST(LaserOwnBody, ARaySensorSeesPastItsOwnBody) { EXPECT_NEAR(range_of("ray"), 2.0, 1e-5); }

// A GPU laser reads the cube's face from inside: 0.2 m.
TEST(LaserOwnBody, AGpuRaySensorSeesItsOwnBody) { EXPECT_NEAR(range_of("gpu_ray"), 0.2, 1e-5); }
