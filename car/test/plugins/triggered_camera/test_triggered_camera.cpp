// The triggered camera (libgazebo_ros_triggered_camera.so) and the 16-bit image formats, on a bare camera link in
// a world with nothing to see but its background (0.2, 0.4, 0.6).
#include <gtest/gtest.h>

#include "camera/camera.hpp"
#include "car_sim/world.hpp"
#include "test_util.hpp"
#include "triggered_camera/triggered_camera.hpp"

using namespace car_sim;

namespace {

const char* kWorld =
    "<sdf version='1.6'><world name='w'><gravity>0 0 0</gravity>"
    "<scene><background>0.2 0.4 0.6 1</background></scene></world></sdf>";

// One link without collision holding a camera sensor with the given format and plug-in file; lens: a
// <distortion> block for the camera, plugin_extra: more plug-in keys.
std::string eye_urdf(const std::string& format, const std::string& file, const std::string& lens = "",
                     const std::string& plugin_extra = "") {
  return "<robot name='eye'><link name='cam'><inertial><mass value='1'/>"
         "<inertia ixx='0.01' iyy='0.01' izz='0.01' ixy='0' ixz='0' iyz='0'/></inertial></link>"
         "<gazebo reference='cam'><sensor type='camera' name='eye'><update_rate>10</update_rate>"
         "<camera><horizontal_fov>1.0</horizontal_fov><image><width>8</width><height>6</height><format>" +
         format + "</format></image><clip><near>0.02</near><far>20</far></clip>" + lens + "</camera>"
                  "<plugin name='eye_camera' filename='" + file + "'><cameraName>eye</cameraName>" + plugin_extra +
         "</plugin>"
                  "</sensor></gazebo></robot>";
}

std::unique_ptr<World> eye_world(const std::string& format, const std::string& file, const std::string& lens = "",
                                 const std::string& plugin_extra = "") {
  auto w = std::make_unique<World>(load_world_string(kWorld));
  w->spawn(load_urdf_string(eye_urdf(format, file, lens, plugin_extra), "eye"), "eye", at(0, 0, 0));
  return w;
}

uint16_t le16(const uint8_t* p) { return static_cast<uint16_t>(p[0] | (p[1] << 8)); }

}  // namespace

TEST(TriggeredCamera, RendersNothingWithoutATrigger) {
  // upstream's sensor rate is DBL_MIN while no trigger is pending: <update_rate> 10 Hz gives no frame in 1 s
  auto w = eye_world("R8G8B8", "libgazebo_ros_triggered_camera.so");
  w->step(1000);
  EXPECT_TRUE(w->take_outputs<CameraOut>().empty());
}

TEST(TriggeredCamera, OneFramePerTriggerInTheNextStep) {
  // nobody listens (the sensor is never switched on): each trigger is used up all the same
  auto w = eye_world("R8G8B8", "libgazebo_ros_triggered_camera.so");
  auto* cam = dynamic_cast<CameraTrigger*>(w->plugin("eye", "eye_camera"));
  ASSERT_NE(cam, nullptr);
  w->step(10);
  cam->trigger();
  w->step(1);
  auto frames = w->take_outputs<CameraOut>();
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].tick, 11u);
  w->step(1000);
  EXPECT_TRUE(w->take_outputs<CameraOut>().empty());
  // two triggers close together: a frame each, in two consecutive steps
  cam->trigger();
  cam->trigger();
  w->step(5);
  frames = w->take_outputs<CameraOut>();
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0].tick, 1012u);
  EXPECT_EQ(frames[1].tick, 1013u);
}

TEST(TriggeredCamera, ResetDropsPendingTriggers) {
  auto w = eye_world("R8G8B8", "libgazebo_ros_triggered_camera.so");
  auto* cam = dynamic_cast<CameraTrigger*>(w->plugin("eye", "eye_camera"));
  ASSERT_NE(cam, nullptr);
  cam->trigger();
  w->reset();
  w->step(100);
  EXPECT_TRUE(w->take_outputs<CameraOut>().empty());
}

TEST(Camera16, Rgb16IsTheBackgroundTimes65535LittleEndian) {
  // R16G16B16: rgb16, 6 bytes a pixel; (0.2, 0.4, 0.6) -> round(x * 65535) = 13107, 26214, 39321
  auto w = eye_world("R16G16B16", "libgazebo_ros_camera.so");
  w->set_sensor_active("eye", "eye_camera", true);
  w->step(100);
  const auto frames = w->take_outputs<CameraOut>();
  ASSERT_EQ(frames.size(), 1u);
  const CameraOut& c = frames[0];
  EXPECT_EQ(c.encoding, "rgb16");
  EXPECT_EQ(c.step(), 8u * 6u);
  ASSERT_EQ(c.image.size(), 8u * 6u * 6u);
  const uint8_t* px = &c.image[6 * (3 * 8 + 4)];
  EXPECT_EQ(le16(px), 13107);
  EXPECT_EQ(le16(px + 2), 26214);
  EXPECT_EQ(le16(px + 4), 39321);
}

TEST(Camera16, Mono16IsTheGreyOfThe16BitChannels) {
  // L16: mono16, 0.299 * 13107 + 0.587 * 26214 + 0.114 * 39321 = 23789.2 -> 23789
  auto w = eye_world("L16", "libgazebo_ros_camera.so");
  w->set_sensor_active("eye", "eye_camera", true);
  w->step(100);
  const auto frames = w->take_outputs<CameraOut>();
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].encoding, "mono16");
  ASSERT_EQ(frames[0].image.size(), 8u * 6u * 2u);
  EXPECT_EQ(le16(&frames[0].image[2 * 20]), 23789);
}

TEST(Camera16, UnknownFormatIsRefusedWithTheKnownNames) {
  try {
    eye_world("R32G32B32", "libgazebo_ros_camera.so");
    FAIL() << "no error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("unknown format 'R32G32B32' (known: L8, L16, R8G8B8, B8G8R8, R16G16B16)"),
              std::string::npos)
        << e.what();
  }
}

// Lens distortion on the 8 x 6 camera: f = 8 / (2 tan 0.5) = 7.3205 px, centre (3.5, 2.5) px.
TEST(CameraLens, BarrelDistortionBlackensTheCornersOnly) {
  // k1 = -0.2: corner q = (0, 0) is (-0.478, -0.341) normalised, |q| = 0.5874; its pinhole point p solves
  // |p| (1 - 0.2 |p|^2) = |q|: |p| = 0.6398, p = 1.0892 q = (-0.521, -0.372) -> u = -0.31 px, outside: black.
  // The centre pixel (4, 3) (q = (0.068, 0.068)) stays the background (51, 102, 153).
  auto w = eye_world("R8G8B8", "libgazebo_ros_camera.so", "<distortion><k1>-0.2</k1></distortion>");
  w->set_sensor_active("eye", "eye_camera", true);
  w->step(100);
  const auto frames = w->take_outputs<CameraOut>();
  ASSERT_EQ(frames.size(), 1u);
  const auto& im = frames[0].image;
  EXPECT_EQ(im[0], 0);
  EXPECT_EQ(im[1], 0);
  EXPECT_EQ(im[2], 0);
  const size_t c = 3 * (3 * 8 + 4);
  EXPECT_EQ(im[c], 51);
  EXPECT_EQ(im[c + 1], 102);
  EXPECT_EQ(im[c + 2], 153);
}

TEST(CameraLens, PincushionKeepsEveryPixelInsideTheFrame) {
  // k1 = +0.5 pulls each pinhole point towards the centre: the whole image is the background
  auto w = eye_world("R8G8B8", "libgazebo_ros_camera.so", "<distortion><k1>0.5</k1></distortion>");
  w->set_sensor_active("eye", "eye_camera", true);
  w->step(100);
  const auto frames = w->take_outputs<CameraOut>();
  ASSERT_EQ(frames.size(), 1u);
  for (size_t i = 0; i < frames[0].image.size(); i += 3) ASSERT_EQ(frames[0].image[i], 51) << "pixel " << i / 3;
}

TEST(CameraLens, AutoDistortionPutsTheLensIntoTheCameraInfoKeys) {
  // camera_info's D = [k1, k2, p1, p2, k3] from distortionK1, K2, T1, T2, K3
  auto w = eye_world("R8G8B8", "libgazebo_ros_camera.so",
                     "<distortion><k1>-0.1</k1><k2>-0.2</k2><k3>-0.3</k3><p1>0.01</p1><p2>0.02</p2></distortion>",
                     "<autoDistortion>true</autoDistortion><distortionK1>0.7</distortionK1>");
  const auto sensors = w->sensors();
  ASSERT_EQ(sensors.size(), 1u);
  const PluginConfig& c = sensors[0].config;
  EXPECT_EQ(c.number("distortionK1"), -0.1);
  EXPECT_EQ(c.number("distortionK2"), -0.2);
  EXPECT_EQ(c.number("distortionK3"), -0.3);
  EXPECT_EQ(c.number("distortionT1"), 0.01);
  EXPECT_EQ(c.number("distortionT2"), 0.02);
}
