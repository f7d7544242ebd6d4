// Every ray-casting kind sees its own link, from inside too, as Gazebo 11's sensors do (docs/COMPAT-sensors.md
// "A ray sensor and its own body": a `ray` sensor's ODE ray geoms are on no body, so ODE's same-body rule never
// applies; a `gpu_ray` sensor renders with culling off). The fixture, no gravity: the probe's link "body" is a
// 0.4 m cube about its origin, spawned at (0, 0, 1); each sensor sits at the link's origin and looks along +x with
// range [0.05, 10] m; a static wall's near face is the plane x = 2 m. A ray straight ahead leaves the cube through
// its face x = 0.2 m: every kind reads 0.2 m there (a kind that skipped its own body would read the wall, 2 m).
// Kinds with a grid of 3 rows (pitch -0.1, 0, 0.1 rad) go through Embree, the others through the planar fan.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "block_laser/block_laser.hpp"
#include "common/sensor_outputs.hpp"
#include "car_sim/world.hpp"
#include "laser/laser.hpp"
#include "velodyne/velodyne.hpp"

using namespace car_sim;

namespace {

// One horizontal sample looking ahead; `rows` vertical samples over [-0.1, 0.1] rad (1: one row at pitch 0).
std::string sensor(const std::string& type, const std::string& file, int rows, const std::string& pose = "0 0 0 0 0 0",
                   const std::string& range = "<min>0.05</min><max>10</max>") {
  return R"(<sensor type=")" + type + R"(" name="s"><pose>)" + pose + R"(</pose><update_rate>1000</update_rate>
    <ray><scan><horizontal><samples>1</samples><resolution>1</resolution><min_angle>0</min_angle>
    <max_angle>0</max_angle></horizontal><vertical><samples>)" + std::to_string(rows) +
         R"(</samples><resolution>1</resolution><min_angle>-0.1</min_angle><max_angle>0.1</max_angle></vertical>
    </scan><range>)" + range + R"(<resolution>0.01</resolution></range></ray>
    <plugin name="p" filename=")" + file + R"("><topicName>t</topicName></plugin></sensor>)";
}

// The probe (a link with `collision` and `sensor` on it) at (0, 0, 1) beside the wall, its sensor switched on,
// after 200 steps of 1 ms (hector's sonar publishes at 10 Hz: twice).
std::unique_ptr<World> probe(const std::string& sensor_xml,
                             const std::string& collision = R"(<geometry><box size="0.4 0.4 0.4"/></geometry>)") {
  auto w = std::make_unique<World>(load_world_string(R"(<?xml version="1.0"?>
<sdf version="1.6"><world name="lab"><gravity>0 0 0</gravity>
  <model name="wall"><static>true</static><pose>2.1 0 1 0 0 0</pose><link name="l">
    <collision name="c"><geometry><box><size>0.2 4 4</size></box></geometry></collision></link></model>
</world></sdf>)"));
  const std::string urdf = R"(<?xml version="1.0"?><robot name="probe"><link name="body">
    <inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision>)" + collision + R"(</collision></link><gazebo reference="body">)" +
                           sensor_xml + "</gazebo></robot>";
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(0, 0, 1);
  w->spawn(load_urdf_string(urdf, "probe"), "probe", pose);
  w->set_sensor_active("probe", "p", true);
  w->step(200);
  return w;
}

// The laser's first range [m] in its last scan.
float laser_range(World& w) {
  const auto scans = w.take_outputs<LaserScanOut>();
  EXPECT_FALSE(scans.empty());
  return scans.empty() ? -1.f : scans.back().ranges.at(0);
}

// A range kind's last reading [m].
float range_reading(World& w) {
  const auto rs = w.take_outputs<RangeOut>();
  EXPECT_FALSE(rs.empty());
  return rs.empty() ? -1.f : rs.back().range;
}

// x [m] of the velodyne's ring-1 point (pitch 0) in its last cloud; -1 when there is none.
float velodyne_ahead(World& w) {
  const auto clouds = w.take_outputs<VelodyneOut>();
  EXPECT_FALSE(clouds.empty());
  if (clouds.empty()) return -1.f;
  const VelodyneOut& c = clouds.back();
  for (size_t k = 0; k < c.rings.size(); ++k)
    if (c.rings[k] == 1) return c.points[3 * k];
  return -1.f;
}

}  // namespace

// The fixture itself: a laser 0.3 m ahead of the origin, outside the cube, reads the wall at 2 - 0.3 = 1.7 m.
TEST(RayOwnBody, FromOutsideItsBodyALaserReadsTheWall) {
  auto w = probe(sensor("ray", "libgazebo_ros_laser.so", 1, "0.3 0 0 0 0 0"));
  EXPECT_NEAR(laser_range(*w), 1.7, 1e-5);
}

// laser, `ray` sensor, one ray (planar fan): the cube's face from inside, 0.2 m.
TEST(RayOwnBody, ARaySensorSeesItsOwnBody) {
  auto w = probe(sensor("ray", "libgazebo_ros_laser.so", 1));
  EXPECT_NEAR(laser_range(*w), 0.2, 1e-5);
}

// laser, `gpu_ray` sensor: Gazebo's GPU laser draws its own link with culling off; 0.2 m.
TEST(RayOwnBody, AGpuRaySensorSeesItsOwnBody) {
  auto w = probe(sensor("gpu_ray", "libgazebo_ros_gpu_laser.so", 1));
  EXPECT_NEAR(laser_range(*w), 0.2, 1e-5);
}

// Kobuki's cliff sensor (kobuki_description's numbers): base_link's collision a cylinder of radius 0.178 m and
// length 0.10938 m centred 0.05949 m up, so its bottom is at 0.05949 - 0.10938 / 2 = 0.0048 m; the sensor at
// (0.08734, 0.13601, 0.0214) (0.1616 m from the axis: inside), pitched pi/2 to look down, range [0.01, 0.15] m. Its
// ray leaves the cylinder through the bottom: 0.0214 - 0.0048 = 0.0166 m. Skipping the body would read nothing
// within 0.15 m (+inf): nothing else is below it.
TEST(RayOwnBody, KobukisCliffRayReadsItsBaseFromInside) {
  auto w = probe(sensor("ray", "libgazebo_ros_laser.so", 1, "0.08734 0.13601 0.0214 0 1.5707963267948966 0",
                        "<min>0.01</min><max>0.15</max>"),
                 R"(<origin xyz="0 0 0.05949"/><geometry><cylinder radius="0.178" length="0.10938"/></geometry>)");
  EXPECT_NEAR(laser_range(*w), 0.0166, 1e-5);
}

// gazebo_ros_range over 3 rows (Embree): the nearest ray is the one at pitch 0, 0.2 m (the others 0.2 / cos 0.1).
TEST(RayOwnBody, TheRangeSensorSeesItsOwnBody) {
  auto w = probe(sensor("ray", "libgazebo_ros_range.so", 3));
  EXPECT_NEAR(range_reading(*w), 0.2, 1e-5);
}

// hector's sonar over 3 rows (Embree), its sensor model at its defaults (scale 1, no offset, drift or noise): 0.2 m.
TEST(RayOwnBody, HectorsSonarSeesItsOwnBody) {
  auto w = probe(sensor("ray", "libhector_gazebo_ros_sonar.so", 3));
  EXPECT_NEAR(range_reading(*w), 0.2, 1e-5);
}

// The block laser over 3 rows (Embree): the middle row's point (index 1, pitch 0) is (0.2, 0, 0).
TEST(RayOwnBody, TheBlockLaserSeesItsOwnBody) {
  auto w = probe(sensor("ray", "libgazebo_ros_block_laser.so", 3));
  const auto clouds = w->take_outputs<BlockLaserOut>();
  ASSERT_FALSE(clouds.empty());
  EXPECT_NEAR(clouds.back().points.at(3 * 1), 0.2, 1e-5);
}

// velodyne on a `ray` sensor, 3 rings (Embree): ring 1 (pitch 0) at x = 0.2 m, inside its band (0.05, 10).
TEST(RayOwnBody, TheVelodyneSeesItsOwnBody) {
  auto w = probe(sensor("ray", "libgazebo_ros_velodyne_laser.so", 3));
  EXPECT_NEAR(velodyne_ahead(*w), 0.2, 1e-5);
}

// velodyne on a `gpu_ray` sensor: as the ray one, 0.2 m.
TEST(RayOwnBody, TheGpuVelodyneSeesItsOwnBody) {
  auto w = probe(sensor("gpu_ray", "libgazebo_ros_velodyne_gpu_laser.so", 3));
  EXPECT_NEAR(velodyne_ahead(*w), 0.2, 1e-5);
}
