// The block laser (libgazebo_ros_block_laser.so): rows of vertical samples see a low box in the rows whose
// pitch meets its face, worked out from the geometry.
#include <gtest/gtest.h>

#include <cmath>

#include "../range/ray_world.hpp"
#include "block_laser/block_laser.hpp"

using namespace car_sim;
using namespace car_sim::test_support;

namespace {

// A box 0.2 m deep, 1 m wide, 0.3 m high: its face on the plane x = 1.5 m, its top at z = 0.3 m.
WorldDescription box_world() { return ray_world(box_model("box", 1.6, 0, 0.15, 0.2, 1, 0.3)); }

// The laser 0.1 m ahead of the cube's centre, 0.4 m above it (z = 0.5 m): 3 columns at yaw -0.1, 0, 0.1 and
// 9 rows at pitch -0.4 + 0.1 j (j = 0..8), range 0.05..3 m.
std::string block(const std::string& extra = "") {
  return ray_sensor("ray", "block", "0.1 0 0.4 0 0 0", scan_axis(3, -0.1, 0.1), scan_axis(9, -0.4, 0.4), 0.05, 3.0,
                    "<plugin name='block_plugin' filename='libgazebo_ros_block_laser.so'><topicName>cloud</topicName>"
                    "<frameName>block</frameName>" + extra + "</plugin>");
}

BlockLaserOut one_cloud(World& w) {
  w.set_sensor_active("cube", "block_plugin", true);
  w.step(100);
  const auto cs = w.take_outputs<BlockLaserOut>();
  EXPECT_FALSE(cs.empty());
  return cs.back();
}

}  // namespace

// From the laser at (x_s, z_s) = (0.1, 0.5), a ray of pitch v meets the face x = 1.5 (dx = 1.4) at height
// z_s + dx tan v: on the face (0 <= z <= 0.3) for tan v in [-0.357, -0.143], i.e. rows j = 1 (v = -0.3, z = 0.067)
// and j = 2 (v = -0.2, z = 0.216). Row 0 (v = -0.4) meets the ground first, 0.5 / tan 0.4 = 1.18 m ahead; rows
// 3.. (v >= -0.1) pass over the box (z = 0.34 at its back edge x = 1.7) and reach the ground beyond 3 m, or never.
TEST(BlockLaser, SeesTheBoxInTheRowsAtItsHeight) {
  auto w = world_with_cube(box_world(), block());
  const BlockLaserOut c = one_cloud(*w);
  ASSERT_EQ(c.rows, 9);
  ASSERT_EQ(c.cols, 3);
  const Eigen::Isometry3d s = w->link_pose("cube", "base") * Eigen::Translation3d(0.1, 0, 0.4);
  const double dx = 1.5 - s.translation().x(), zs = s.translation().z();
  EXPECT_NEAR(dx, 1.4, 2e-3);
  for (int j = 0; j < 9; ++j) {
    const double v = -0.4 + 0.1 * j;
    for (int i = 0; i < 3; ++i) {
      const double h = -0.1 + 0.1 * i;
      const float* p = &c.points[3 * (i + j * 3)];
      const double r = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
      if (j == 1 || j == 2) {
        // on the face: x = dx in the sensor frame, z = dx tan v
        EXPECT_NEAR(p[0], dx, 1e-4) << "row " << j << " col " << i;
        EXPECT_NEAR(p[2], dx * std::tan(v) / std::cos(h), 1e-4) << "row " << j << " col " << i;
      } else if (j == 0) {
        // on the ground, z_s below the laser
        EXPECT_NEAR(p[2], -zs, 1e-4) << "col " << i;
      } else {
        // no hit: on the range.max sphere along its own ray
        EXPECT_NEAR(r, 3.0, 1e-5) << "row " << j << " col " << i;
        EXPECT_NEAR(std::asin(p[2] / r), v, 1e-5) << "row " << j << " col " << i;
        EXPECT_NEAR(std::atan2(p[1], p[0]), h, 1e-5) << "row " << j << " col " << i;
      }
    }
  }
}

// Every point lies on its own ray (upstream skews points half a step; car does not): the column's yaw.
TEST(BlockLaser, EachPointOnItsOwnRay) {
  auto w = world_with_cube(box_world(), block());
  const BlockLaserOut c = one_cloud(*w);
  for (int k = 0; k < 27; ++k) {
    const float* p = &c.points[3 * k];
    EXPECT_NEAR(std::atan2(p[1], p[0]), -0.1 + 0.1 * (k % 3), 1e-5) << k;
  }
}

TEST(BlockLaser, OneVerticalSampleIsAPlanarScan) {
  std::string s = block();
  s.replace(s.find("<samples>9</samples>"), 20, "<samples>1</samples>");
  s.replace(s.find("<min_angle>-0.400000</min_angle>"), 32, "<min_angle>0.000000</min_angle>");
  s.replace(s.find("<max_angle>0.400000</max_angle>"), 31, "<max_angle>0.000000</max_angle>");
  auto w = world_with_cube(box_world(), s);
  const BlockLaserOut c = one_cloud(*w);
  ASSERT_EQ(c.rows, 1);
  for (int i = 0; i < 3; ++i) EXPECT_FLOAT_EQ(c.points[3 * i + 2], 0.f);  // level, no NaN (upstream: 0/0)
}

TEST(BlockLaser, MinAngleAboveMaxAngleIsALoadError) {
  std::string s = block();
  s.replace(s.find("<min_angle>-0.400000</min_angle>"), 32, "<min_angle>0.500000</min_angle>");
  try {
    World w(box_world());
    w.spawn(load_urdf_string(cube_robot(s), "cube"), "cube", at(0, 0, 0));
    FAIL() << "no error";
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("sensor[block]/ray/scan/vertical/min_angle"), std::string::npos) << e.what();
  }
}

// Upstream averages the retro of a point's ray and its next neighbours (i+1, j+1; clamped at the last): with the
// box's laser_retro 100 seen by rows 1 and 2 (ground and sky 0), every column reads row 0: 50, row 1: 100,
// row 2: 50, the rest 0.
TEST(BlockLaser, IntensityAveragesFourNeighbouringRays) {
  const WorldDescription d = ray_world(
      "<model name='box'><static>true</static><pose>1.6 0 0.15 0 0 0</pose><link name='l'><collision name='c'>"
      "<laser_retro>100</laser_retro><geometry><box><size>0.2 1 0.3</size></box></geometry></collision></link>"
      "</model>");
  auto w = world_with_cube(d, block());
  const BlockLaserOut c = one_cloud(*w);
  const double want[9] = {50, 100, 50, 0, 0, 0, 0, 0, 0};
  for (int j = 0; j < 9; ++j)
    for (int i = 0; i < 3; ++i) EXPECT_FLOAT_EQ(c.intensities[i + 3 * j], static_cast<float>(want[j])) << i << " " << j;
}

// A gpu_ray sensor is no RaySensor: upstream's RayPlugin::Load throws "RayPlugin requires a Ray Sensor as its parent". The model loads without the plug-in.
TEST(BlockLaser, OnAGpuRaySensorThePluginDoesNotLoad) {
  EXPECT_EQ(not_loaded_on("gpu_ray", "<plugin name='p' filename='libgazebo_ros_block_laser.so'/>"),
            "libgazebo_ros_block_laser.so needs a sensor of type ray, not 'gpu_ray'; the plug-in is not loaded");
}
