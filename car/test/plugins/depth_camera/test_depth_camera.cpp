// The generic depth camera (libgazebo_ros_depth_camera.so): depth along the optical axis in front of a wall,
// the floor in the lower rows, no upper cutoff, NaN at or below pointCloudCutoff.
#include <gtest/gtest.h>

#include <cmath>

#include "../range/ray_world.hpp"
#include "camera/camera.hpp"

using namespace car_sim;
using namespace car_sim::test_support;

namespace {

// A wall 20 m wide and 10 m high, its face on the plane x = 6 m.
WorldDescription wall_world() { return ray_world(box_model("wall", 6.1, 0, 5, 0.2, 20, 10)); }

// 64 x 48, hfov 1.0 rad: f = 64 / (2 tan 0.5) = 58.54 px, cx = 31.5, cy = 23.5; 0.1 m ahead of the cube's
// centre and 0.4 m above it (z = 0.5 m), looking along +x.
std::string depth_sensor(const std::string& extra = "") {
  return "<sensor type='depth' name='depth'><pose>0.1 0 0.4 0 0 0</pose><update_rate>10</update_rate><camera>"
         "<horizontal_fov>1.0</horizontal_fov><image><width>64</width><height>48</height><format>R8G8B8</format>"
         "</image><clip><near>0.05</near><far>20</far></clip></camera>"
         "<plugin name='depth_plugin' filename='libgazebo_ros_depth_camera.so'><cameraName>cam</cameraName>"
         "<frameName>cam_optical</frameName>" + extra + "</plugin></sensor>";
}

CameraOut one_frame(World& w) {
  w.set_sensor_active("cube", "depth_plugin", true);
  w.step(100);
  const auto fs = w.take_outputs<CameraOut>();
  EXPECT_FALSE(fs.empty());
  return fs.back();
}

}  // namespace

// The wall is perpendicular to the optical axis: every pixel on it has depth dx = 6 - x_s = 5.9 m -- beyond the
// Kinect's 5 m cutoff, valid here. A pixel of row v looks down by atan((v - 23.5) / f) and meets the floor
// (z_s = 0.5 m below) at depth 0.5 f / (v - 23.5), nearer than the wall from row 29 on (4.96 px below cy):
// row 47 reads 0.5 x 58.54 / 23.5 = 1.2455 m.
TEST(DepthCamera, WallAndFloorDepthsWithoutUpperCutoff) {
  auto w = world_with_cube(wall_world(), depth_sensor());
  const CameraOut c = one_frame(*w);
  ASSERT_TRUE(c.has_depth);
  ASSERT_EQ(c.width, 64);
  const Eigen::Isometry3d s = w->link_pose("cube", "base") * Eigen::Translation3d(0.1, 0, 0.4);
  const double dx = 6.0 - s.translation().x(), zs = s.translation().z();
  const double f = 64 / (2 * std::tan(0.5));
  EXPECT_NEAR(c.f, f, 1e-9);
  for (int v : {0, 10, 23, 28})
    for (int u = 0; u < 64; ++u) EXPECT_NEAR(c.depth[v * 64 + u], dx, 1e-4) << "row " << v << " col " << u;
  for (int u = 0; u < 64; ++u) EXPECT_NEAR(c.depth[47 * 64 + u], zs * f / 23.5, 1e-4) << "col " << u;
  // points in the optical frame: x = d (u - cx) / f, y = d (v - cy) / f
  EXPECT_NEAR(c.points[3 * (10 * 64 + 0)], dx * (0 - 31.5) / f, 1e-4);
  EXPECT_NEAR(c.points[3 * (10 * 64 + 0) + 1], dx * (10 - 23.5) / f, 1e-4);
}

// pointCloudCutoff 3 m: the floor rows nearer than 3 m (depth 0.5 f / (v - 23.5) <= 3: v >= 33.3) are NaN, the
// wall stays.
TEST(DepthCamera, DepthAtOrBelowTheCutoffIsNaN) {
  auto w = world_with_cube(wall_world(), depth_sensor("<pointCloudCutoff>3</pointCloudCutoff>"));
  const CameraOut c = one_frame(*w);
  for (int u = 0; u < 64; ++u) {
    EXPECT_TRUE(std::isnan(c.depth[47 * 64 + u])) << u;
    EXPECT_TRUE(std::isnan(c.points[3 * (47 * 64 + u) + 2])) << u;
    EXPECT_TRUE(std::isnan(c.depth[34 * 64 + u])) << u;
    EXPECT_FALSE(std::isnan(c.depth[33 * 64 + u])) << u;  // 0.5 f / 9.5 = 3.08 m
    EXPECT_FALSE(std::isnan(c.depth[10 * 64 + u])) << u;
  }
}

TEST(DepthCamera, UnknownImageFormatIsALoadError) {
  std::string s = depth_sensor();
  s.replace(s.find("R8G8B8"), 6, "XYZ");
  try {
    World w(wall_world());
    w.spawn(load_urdf_string(cube_robot(s), "cube"), "cube", at(0, 0, 0));
    FAIL() << "no error";
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("sensor[depth]/camera/image/format"), std::string::npos) << e.what();
  }
}
