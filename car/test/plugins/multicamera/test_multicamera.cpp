// The multicamera (libgazebo_ros_multicamera.so): a stereo pair 0.14 m apart sees a red pole 3 m ahead at the
// columns its baseline predicts, both frames at the same tick.
#include <gtest/gtest.h>

#include <cmath>

#include "../range/ray_world.hpp"
#include "multicamera/multicamera.hpp"

using namespace car_sim;
using namespace car_sim::test_support;

namespace {

// A grey wall (face x = 6 m) and a red pole 0.1 m square, 2 m high, centred at (3, 0).
WorldDescription pole_world() {
  return ray_world(box_model("wall", 6.1, 0, 5, 0.2, 20, 10) +
                   "<model name='pole'><static>true</static><pose>3 0 1 0 0 0</pose><link name='l'>"
                   "<collision name='c'><geometry><box><size>0.1 0.1 2</size></box></geometry></collision>"
                   "<visual name='v'><geometry><box><size>0.1 0.1 2</size></box></geometry><material>"
                   "<diffuse>1 0 0 1</diffuse><ambient>1 0 0 1</ambient></material></visual></link></model>");
}

// 160 x 120, hfov 1.0 rad (f = 160 / (2 tan 0.5) = 146.35 px, cx = 79.5); the pair 0.4 m above the cube's
// centre (z = 0.5 m), 0.1 m ahead, at y = +-0.07 m.
std::string stereo(const std::string& left = "left_cam", const std::string& right = "right_cam") {
  auto cam = [](const std::string& name, const char* y) {
    return "<camera name='" + name + "'><pose>0 " + y + " 0 0 0 0</pose><horizontal_fov>1.0</horizontal_fov><image>"
           "<width>160</width><height>120</height><format>R8G8B8</format></image><clip><near>0.05</near>"
           "<far>20</far></clip></camera>";
  };
  return "<sensor type='multicamera' name='stereo'><pose>0.1 0 0.4 0 0 0</pose><update_rate>10</update_rate>" +
         cam(left, "0.07") + cam(right, "-0.07") +
         "<plugin name='stereo_plugin' filename='libgazebo_ros_multicamera.so'><cameraName>stereo</cameraName>"
         "<frameName>stereo_optical</frameName><hackBaseline>0.14</hackBaseline></plugin></sensor>";
}

// Mean column of the red pixels in row v.
double red_centre(const CameraOut& c, int v) {
  double sum = 0;
  int n = 0;
  for (int u = 0; u < c.width; ++u) {
    const uint8_t* p = &c.image[3 * (v * c.width + u)];
    if (p[0] > 100 && p[1] < 60 && p[2] < 60) {
      sum += u;
      ++n;
    }
  }
  EXPECT_GT(n, 0);
  return n ? sum / n : -1;
}

}  // namespace

// The pole (y = 0) is 0.07 m to the left camera's right: its centre at u = cx + f 0.07 / dx, dx = 3 - 0.1 =
// 2.9 m: 79.5 + 3.53; in the right camera at 79.5 - 3.53. Pixels whose centre ray hits the pole's face
// (0.1 m wide: 5.0 px) average to within half a pixel of that.
TEST(MultiCamera, StereoPairSeesThePoleAtItsDisparity) {
  auto w = world_with_cube(pole_world(), stereo());
  w->set_sensor_active("cube", "stereo_plugin", true);
  w->step(100);
  const auto outs = w->take_outputs<MultiCameraOut>();
  ASSERT_EQ(outs.size(), 1u);
  const MultiCameraOut& o = outs[0];
  ASSERT_EQ(o.sides, (std::vector<std::string>{"left", "right"}));
  const double f = 160 / (2 * std::tan(0.5));
  const Eigen::Isometry3d s = w->link_pose("cube", "base") * Eigen::Translation3d(0.1, 0, 0.4);
  const double dx = 3.0 - 0.05 - s.translation().x();  // to the pole's front face
  EXPECT_NEAR(red_centre(o.frames[0], 60), 79.5 + f * 0.07 / dx, 0.6);
  EXPECT_NEAR(red_centre(o.frames[1], 60), 79.5 - f * 0.07 / dx, 0.6);
  EXPECT_EQ(o.frames[0].width, 160);
  EXPECT_NEAR(o.frames[1].f, f, 1e-9);
}

// Only cameras named with "left" / "right" count, as upstream: two others give a warning and nothing.
TEST(MultiCamera, CamerasWithoutLeftOrRightAreNotPublished) {
  const ModelConfig cfg = resolve_plugins(load_urdf_string(cube_robot(stereo("a", "b")), "cube"));
  bool warned = false;
  for (const auto& d : cfg.diagnostics) warned = warned || d.code == "multicamera-unnamed";
  EXPECT_TRUE(warned);
  auto w = world_with_cube(pole_world(), stereo("a", "b"));
  w->set_sensor_active("cube", "stereo_plugin", true);
  w->step(100);
  const auto outs = w->take_outputs<MultiCameraOut>();
  ASSERT_EQ(outs.size(), 1u);
  EXPECT_TRUE(outs[0].frames.empty());
}

TEST(MultiCamera, BadCameraWidthIsALoadErrorNamingTheCamera) {
  std::string s = stereo();
  s.replace(s.find("<width>160</width>"), 18, "<width>0</width>");
  try {
    resolve_plugins(load_urdf_string(cube_robot(s), "cube"));
    FAIL() << "no error";
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("sensor[stereo]/camera[left_cam]/image/width"), std::string::npos) << e.what();
  }
}
