// A depth camera makes only the parts of its frames someone takes (Plugin::set_parts, issue 13 item 5): the seed
// car's Kinect in box_house, driving a curve for 0.6 s (12 frames at 20 Hz), with all parts and with some. A part
// that is made is the same bytes as in the full frame (NaN bits included); a part left out is empty.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "camera/camera.hpp"
#include "seed_car.hpp"

using namespace car_sim;
using namespace car_sim::test_support;

namespace {

// The Kinect's frames with `parts` set before the first step.
std::vector<CameraOut> frames(uint32_t parts) {
  World w(load_world_file(std::string(CAR_SOURCE_DIR) + "/worlds/box_house.world"));
  w.spawn(load_urdf_string(car_xml(false), "car"), "mycar", at(-1.0, 0.5, 0.3));
  w.set_cmd_vel("mycar", 1.0, 0.8);
  w.set_sensor_active("mycar", "kinect_camera_controller", true);
  w.plugin("mycar", "kinect_camera_controller")->set_parts(parts);
  w.step(600);
  return w.take_outputs<CameraOut>();
}

template <class V>
bool same_bytes(const V& a, const V& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
}

}  // namespace

// Depth alone: each frame's depth is the full frame's; no image, no cloud.
TEST(KinectParts, DepthAloneIsTheFullFramesDepthAndNothingElse) {
  const std::vector<CameraOut> all = frames(~0u), depth = frames(kCameraDepth);
  ASSERT_EQ(all.size(), 12u);
  ASSERT_EQ(depth.size(), all.size());
  for (size_t i = 0; i < all.size(); ++i) {
    ASSERT_EQ(depth[i].depth.size(), 640u * 480u);
    EXPECT_TRUE(same_bytes(depth[i].depth, all[i].depth)) << "frame " << i;
    EXPECT_TRUE(depth[i].image.empty());
    EXPECT_TRUE(depth[i].points.empty());
    EXPECT_TRUE(depth[i].point_rgb.empty());
  }
}

// The colour image alone: each frame's image is the full frame's; no depth, no cloud.
TEST(KinectParts, ImageAloneIsTheFullFramesImageAndNothingElse) {
  const std::vector<CameraOut> all = frames(~0u), image = frames(kCameraImage);
  ASSERT_EQ(image.size(), all.size());
  for (size_t i = 0; i < all.size(); ++i) {
    ASSERT_EQ(image[i].image.size(), 3u * 640u * 480u);
    EXPECT_TRUE(same_bytes(image[i].image, all[i].image)) << "frame " << i;
    EXPECT_TRUE(image[i].depth.empty());
    EXPECT_TRUE(image[i].points.empty());
  }
}

// The cloud needs depth and colour: with it every part is made, as in the full frame.
TEST(KinectParts, CloudMakesEveryPart) {
  const std::vector<CameraOut> all = frames(~0u), cloud = frames(kCameraCloud);
  ASSERT_EQ(cloud.size(), all.size());
  for (size_t i = 0; i < all.size(); ++i) {
    EXPECT_TRUE(same_bytes(cloud[i].points, all[i].points)) << "frame " << i;
    EXPECT_TRUE(same_bytes(cloud[i].point_rgb, all[i].point_rgb)) << "frame " << i;
    EXPECT_TRUE(same_bytes(cloud[i].depth, all[i].depth)) << "frame " << i;
    EXPECT_TRUE(same_bytes(cloud[i].image, all[i].image)) << "frame " << i;
  }
}

// No part the camera knows (0): everything, rather than frames with nothing in them.
TEST(KinectParts, NoKnownPartMakesEverything) {
  const std::vector<CameraOut> none = frames(0u);
  ASSERT_EQ(none.size(), 12u);
  EXPECT_EQ(none[0].image.size(), 3u * 640u * 480u);
  EXPECT_EQ(none[0].depth.size(), 640u * 480u);
  EXPECT_EQ(none[0].points.size(), 3u * 640u * 480u);
}
