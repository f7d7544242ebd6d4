// velodyne_simulator's plug-in: a VLP-16-style lidar (16 rings from -15 to +15 degrees, 2 degrees apart) in a
// square room returns 16 rings at their elevations, each point on its ring's cone; the band drops points.
#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <map>

#include "../range/ray_world.hpp"
#include "velodyne/velodyne.hpp"

using namespace car_sim;
using namespace car_sim::test_support;

namespace {

constexpr double kDeg = M_PI / 180.0;

// Four walls 10 m high whose inner faces are the planes x = +-3 m and y = +-3 m.
WorldDescription room() {
  return ray_world(box_model("e", 3.1, 0, 5, 0.2, 6.4, 10) + box_model("w", -3.1, 0, 5, 0.2, 6.4, 10) +
                   box_model("n", 0, 3.1, 5, 6.4, 0.2, 10) + box_model("s", 0, -3.1, 5, 6.4, 0.2, 10));
}

// VLP-16 as velodyne_description writes it: 361 columns over [-pi, pi] (1 degree apart), 16 rows over
// [-15, 15] degrees; the lidar 0.9 m above the cube's centre (z = 1.0 m); range 0.3..100 m.
std::string vlp16(const std::string& extra = "", const char* file = "libgazebo_ros_velodyne_laser.so",
                  const char* type = "ray") {
  return ray_sensor(type, "vlp16", "0 0 0.9 0 0 0", scan_axis(361, -M_PI, M_PI), scan_axis(16, -15 * kDeg, 15 * kDeg),
                    0.3, 100,
                    std::string("<plugin name='velodyne_plugin' filename='") + file +
                        "'><topicName>velodyne_points</topicName><frameName>velodyne</frameName>" + extra +
                        "</plugin>");
}

VelodyneOut one_cloud(World& w) {
  w.set_sensor_active("cube", "velodyne_plugin", true);
  w.step(100);
  const auto cs = w.take_outputs<VelodyneOut>();
  EXPECT_FALSE(cs.empty());
  return cs.back();
}

}  // namespace

// Every ray meets a wall or the floor: 361 x 16 points; ring j holds 361 points, all at elevation
// -15 + 2 j degrees (atan2(z, hypot(x, y)), exact up to float rounding).
TEST(Velodyne, Vlp16ReturnsSixteenRingsAtTheirElevations) {
  auto w = world_with_cube(room(), vlp16());
  const VelodyneOut c = one_cloud(*w);
  ASSERT_EQ(c.rings.size(), 361u * 16u);
  std::map<int, int> per_ring;
  for (size_t k = 0; k < c.rings.size(); ++k) {
    const int j = c.rings[k];
    ++per_ring[j];
    const float* p = &c.points[3 * k];
    const double elevation = std::atan2(p[2], std::hypot(p[0], p[1]));
    EXPECT_NEAR(elevation, (-15.0 + 2.0 * j) * kDeg, 2e-6) << "point " << k << " ring " << j;
  }
  ASSERT_EQ(per_ring.size(), 16u);
  for (const auto& [ring, n] : per_ring) EXPECT_EQ(n, 361) << "ring " << ring;
}

// Order: columns outer, rings inner; column 180 looks along +x at the wall x = 3: its ring-j point is
// (dx, 0, dx tan(-15 + 2 j deg)) with dx = 3 - x_s (for the lowest ring, z = -0.80 m stays above the floor,
// which is z_s = 1.0 m below).
TEST(Velodyne, ColumnAlongXMeetsTheWallAtTheRingsHeights) {
  auto w = world_with_cube(room(), vlp16());
  const VelodyneOut c = one_cloud(*w);
  const Eigen::Isometry3d s = w->link_pose("cube", "base") * Eigen::Translation3d(0, 0, 0.9);
  const double dx = 3.0 - s.translation().x();
  for (int j = 0; j < 16; ++j) {
    const size_t k = 180 * 16 + j;
    ASSERT_EQ(c.rings[k], j);
    EXPECT_NEAR(c.points[3 * k], dx, 1e-4);
    EXPECT_NEAR(c.points[3 * k + 1], 0.0, 1e-4);
    EXPECT_NEAR(c.points[3 * k + 2], dx * std::tan((-15.0 + 2.0 * j) * kDeg), 1e-4);
  }
}

// max_range 2.5 m: every wall is 3 m or more away and a downward ring meets the floor (z_s = 1 m below) at
// r = 1 / sin(-v) >= 1 / sin 15 deg = 3.86 m: nothing is left.
TEST(Velodyne, PointsBeyondMaxRangeAreDropped) {
  auto w = world_with_cube(room(), vlp16("<max_range>2.5</max_range>"));
  EXPECT_EQ(one_cloud(*w).rings.size(), 0u);
}

// min_range 3.5 m: along +x (azimuth 0) the wall is 3 m away horizontally, slant 3 / cos v <= 3.11 m for
// |v| <= 15 deg: all 16 dropped. Towards the corner (azimuth 45 deg, 4.24 m horizontally) ring 0 meets the
// floor at 1 / sin 15 deg = 3.86 m and the others the walls at 4.24 / cos v >= 4.24 m: all 16 kept.
TEST(Velodyne, PointsInsideMinRangeAreDropped) {
  auto w = world_with_cube(room(), vlp16("<min_range>3.5</min_range>"));
  const VelodyneOut c = one_cloud(*w);
  int along_x = 0, corner = 0;
  for (size_t k = 0; k < c.rings.size(); ++k) {
    const float* p = &c.points[3 * k];
    EXPECT_GT(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), 3.5f);
    const double az = std::atan2(p[1], p[0]);
    along_x += std::abs(az) < 0.5 * kDeg;
    corner += std::abs(az - 45 * kDeg) < 0.5 * kDeg;
  }
  EXPECT_EQ(along_x, 0);
  EXPECT_EQ(corner, 16);
}

TEST(Velodyne, GpuFileAndSensorTypeAreTheSameKind) {
  auto a = world_with_cube(room(), vlp16());
  auto b = world_with_cube(room(), vlp16("", "libgazebo_ros_velodyne_gpu_laser.so", "gpu_ray"));
  const VelodyneOut ca = one_cloud(*a), cb = one_cloud(*b);
  ASSERT_EQ(ca.points.size(), cb.points.size());
  for (size_t k = 0; k < ca.points.size(); ++k) ASSERT_EQ(ca.points[k], cb.points[k]) << k;
}

// min_range >= max_range: upstream's band keeps no point, so every cloud is empty; car the same, with a warning.
TEST(Velodyne, MinRangeNotBelowMaxRangeGivesEmptyClouds) {
  World w(room());
  w.spawn(load_urdf_string(cube_robot(vlp16("<min_range>5</min_range><max_range>2</max_range>")), "cube"), "cube",
          at(0, 0, 0));
  std::vector<std::string> codes;
  for (const Diagnostic& d : w.robot("cube").config.diagnostics) codes.push_back(d.code);
  EXPECT_NE(std::find(codes.begin(), codes.end(), "velodyne-band"), codes.end());
  w.set_sensor_active("cube", "velodyne_plugin", true);
  w.step(200);
  const auto clouds = w.take_outputs<VelodyneOut>();
  ASSERT_FALSE(clouds.empty());
  EXPECT_TRUE(clouds.back().points.empty());
}

// the CPU build's Load throws "requires a Ray Sensor as its parent": the model loads without the plug-in.
TEST(Velodyne, CpuFileOnAGpuRaySensorDoesNotLoad) {
  const std::string plugin = "<plugin name='p' filename='libgazebo_ros_velodyne_laser.so'/>";
  EXPECT_EQ(not_loaded_on("gpu_ray", plugin),
            "libgazebo_ros_velodyne_laser.so needs a sensor of type ray, not 'gpu_ray'; the plug-in is not loaded");
  // and absent, not only reported: nothing resolved, so the world runs no velodyne kind for it; the same element on a
  // ray sensor loads (the check is not empty for another reason)
  EXPECT_EQ(loaded_kinds_on("gpu_ray", plugin), std::vector<std::string>{});
  EXPECT_EQ(loaded_kinds_on("ray", plugin), std::vector<std::string>{"velodyne"});
}

// the GPU build's Load throws "requires a GpuRay Sensor as its parent": the model loads without the plug-in.
TEST(Velodyne, GpuFileOnARaySensorDoesNotLoad) {
  const std::string plugin = "<plugin name='p' filename='libgazebo_ros_velodyne_gpu_laser.so'/>";
  EXPECT_EQ(not_loaded_on("ray", plugin),
            "libgazebo_ros_velodyne_gpu_laser.so needs a sensor of type gpu_ray, not 'ray'; the plug-in is not loaded");
  // and absent, not only reported: nothing resolved, so the world runs no velodyne kind for it; the same element on a
  // gpu_ray sensor loads (the check is not empty for another reason)
  EXPECT_EQ(loaded_kinds_on("ray", plugin), std::vector<std::string>{});
  EXPECT_EQ(loaded_kinds_on("gpu_ray", plugin), std::vector<std::string>{"velodyne"});
}
