// The plain camera (libgazebo_ros_camera.so).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "camera/camera.hpp"
#include "seed_car.hpp"

using namespace car_sim;
using namespace car_sim::test_support;

TEST(Camera, PlainCameraPluginGivesAnImageOnly) {
  // libgazebo_ros_camera.so on a camera sensor: an L8 (mono8) image, no depth
  std::string xml = car_xml(false);
  xml.insert(xml.rfind("</robot>"),
             "<gazebo reference=\"camera\"><sensor type=\"camera\" name=\"front\"><update_rate>10</update_rate>"
             "<camera><horizontal_fov>1.0</horizontal_fov><image><width>64</width><height>48</height>"
             "<format>L8</format></image><clip><near>0.02</near><far>20</far></clip></camera>"
             "<plugin name=\"front_camera\" filename=\"libgazebo_ros_camera.so\"><cameraName>front</cameraName>"
             "<frameName>camera</frameName></plugin></sensor></gazebo>");
  World w(load_world_file(std::string(CAR_SOURCE_DIR) + "/worlds/box_house.world"));
  w.spawn(load_urdf_string(xml, "car"), "mycar", at(0.0, 0.059964, 0.0));
  w.set_sensor_active("mycar", "front_camera", true);
  w.step(200);
  const auto images = w.take_outputs<CameraOut>();
  ASSERT_EQ(images.size(), 2u);  // 10 Hz for 0.2 s
  const CameraOut& c = images.back();
  EXPECT_EQ(c.encoding, "mono8");
  EXPECT_EQ(c.image.size(), 64u * 48u);
  EXPECT_FALSE(c.has_depth);
  EXPECT_NEAR(c.f, 64 / (2 * std::tan(0.5)), 1e-9);
  // the brick wall ahead in the ambient light: luminance of (63, 33, 24)
  EXPECT_EQ(c.image[24 * 64 + 32], static_cast<uint8_t>(0.299f * 63 + 0.587f * 33 + 0.114f * 24 + 0.5f));
}

namespace {

// [bytes] this process's resident memory (/proc/self/statm: pages)
size_t resident_bytes() {
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  unsigned long size = 0, resident = 0;
  if (f) {
    if (std::fscanf(f, "%lu %lu", &size, &resident) != 2) resident = 0;
    std::fclose(f);
  }
  return resident * 4096;
}

}  // namespace

TEST(Camera, AnUnsubscribedCameraTakesNoPerPixelMemory) {
  // 20 seed cars, each with the Kinect's 640 x 480 camera that nobody takes: its per-pixel arrays (about 10 MB a
  // camera) are made at its first frame, so the spawns add far less than 20 x 10 MB
  World w(empty_world());
  const RobotModel car = load_urdf_file(std::string(CAR_SOURCE_DIR) + "/test/data/car_camera_lidar04.urdf");
  const size_t before = resident_bytes();
  ASSERT_GT(before, 0u) << "/proc/self/statm unreadable";
  for (int i = 0; i < 20; ++i) w.spawn(car, "car" + std::to_string(i), at(2.0 * i, 0.0, 0.0));
  w.step(100);
  const double grown = (resident_bytes() - static_cast<double>(before)) / 1e6;  // [MB]
  EXPECT_LT(grown, 50.0) << "resident memory grew by " << grown << " MB for 20 cars";
}
