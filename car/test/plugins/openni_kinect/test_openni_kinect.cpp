// The Kinect (libgazebo_ros_openni_kinect.so) in box_house: depth, points and colour against the geometry.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "camera/camera.hpp"
#include "seed_car.hpp"

using namespace car_sim;
using namespace car_sim::test_support;

namespace {

CameraOut one_image(World& w) {
  w.set_sensor_active("mycar", "kinect_camera_controller", true);
  w.step(60);  // 20 Hz
  const auto images = w.take_outputs<CameraOut>();
  EXPECT_FALSE(images.empty());
  return images.back();
}

}  // namespace

TEST(Depth, CentrePixelFacingWall2ReadsItsDistance) {
  // the support link (camera frame) sits above the car's origin; Wall_2's inner face is at x = 4.44857 - 0.075
  auto w = world_with_car(false, 0.0, 0.059964, 0.0);
  const CameraOut c = one_image(*w);
  const double x_cam = w->link_pose("mycar", "support").translation().x();
  // the centre of a 640 x 480 image lies between four pixels; they all see the wall head on
  EXPECT_NEAR(c.depth[239 * 640 + 319], 4.37357 - x_cam, 1e-3);
  EXPECT_NEAR(c.depth[240 * 640 + 320], 4.37357 - x_cam, 1e-3);
}

TEST(Depth, CameraModelFromTheSensorBlock) {
  auto w = world_with_car(false);
  const CameraOut c = one_image(*w);
  EXPECT_NEAR(c.f, 640 / (2 * std::tan(30.0 * 3.1415927 / 180.0)), 1e-6);  // 554.26
  EXPECT_DOUBLE_EQ(c.cx, 319.5);
  EXPECT_DOUBLE_EQ(c.cy, 239.5);
  EXPECT_EQ(c.encoding, "rgb8");
}

TEST(Depth, NearerThanTheCutoffIsNaN) {
  // 0.3 m from Wall_2: inside pointCloudCutoff 0.4
  auto w = world_with_car(false, 4.37357 - 0.3, 0.059964, 0.0);
  const CameraOut c = one_image(*w);
  EXPECT_TRUE(std::isnan(c.depth[240 * 640 + 320]));
}

TEST(Depth, BeyondTheCutoffMaxIsNaN) {
  // facing Wall_4 (x = -8.32643) along y = -1, clear of the cylinders and boxes: 8.3 m > pointCloudCutoffMax 5
  auto w = world_with_car(false, 0.0, -1.0, M_PI);
  const CameraOut c = one_image(*w);
  EXPECT_TRUE(std::isnan(c.depth[240 * 640 + 320]));
  EXPECT_TRUE(std::isnan(c.points[3 * (240 * 640 + 320) + 2]));
}

TEST(Depth, WallColourIsBricksInTheAmbientLight) {
  // Gazebo/Bricks (0.62 0.32 0.24) on a face turned away from the sun: lit by the ambient 0.4 only
  auto w = world_with_car(false, 0.0, 0.059964, 0.0);
  const CameraOut c = one_image(*w);
  const size_t i = 240 * 640 + 320;
  EXPECT_EQ(c.point_rgb[3 * i], std::lround(0.62 * 0.4 * 255));
  EXPECT_EQ(c.point_rgb[3 * i + 1], std::lround(0.32 * 0.4 * 255));
  EXPECT_EQ(c.point_rgb[3 * i + 2], std::lround(0.24 * 0.4 * 255));
}

TEST(Depth, PointsFollowTheOpticalConvention) {
  auto w = world_with_car(false, 0.0, 0.059964, 0.0);
  const CameraOut c = one_image(*w);
  // pixel (u, v) = (400, 100): x = d (u - cx) / f right, y = d (v - cy) / f down, z = d
  const size_t i = 100 * 640 + 400;
  const float d = c.depth[i];
  ASSERT_TRUE(std::isfinite(d));
  EXPECT_FLOAT_EQ(c.points[3 * i], d * (400 - 319.5f) / static_cast<float>(c.f));
  EXPECT_FLOAT_EQ(c.points[3 * i + 1], d * (100 - 239.5f) / static_cast<float>(c.f));
  EXPECT_FLOAT_EQ(c.points[3 * i + 2], d);
}

TEST(Depth, SameSeedSameClouds) {
  auto a = world_with_car(true, 0, 0, 0, 3), b = world_with_car(true, 0, 0, 0, 3);
  const CameraOut ca = one_image(*a), cb = one_image(*b);
  EXPECT_EQ(0, std::memcmp(ca.points.data(), cb.points.data(), ca.points.size() * sizeof(float)));
  EXPECT_EQ(ca.image, cb.image);
}
