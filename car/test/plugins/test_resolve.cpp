// Plug-in configuration resolved from the seed car's <gazebo> blocks, with defaults per docs/COMPAT-spec.md.
#include <gtest/gtest.h>

#include "car_sim/plugins.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

const std::string& car_xml() {
  static const std::string xml = read_text("test/data/car_camera_lidar04.urdf");
  return xml;
}

const ModelConfig& car_config() {
  static const ModelConfig c = resolve_plugins(load_urdf_string(car_xml(), "car04"));
  return c;
}

const PluginConfig& plugin(const std::string& kind) {
  for (const auto& p : car_config().plugins)
    if (p.kind == kind) return p;
  throw std::runtime_error("no plug-in of kind " + kind);
}

bool has_diag(const std::vector<Diagnostic>& ds, const std::string& code, const std::string& element) {
  for (const auto& d : ds)
    if (d.code == code && d.element == element) return true;
  return false;
}

// The seed car with the last occurrence of a text replaced (the kinect's, where camera01.xacro's duplicate
// sensor has the same text); fails the test if the text is not there.
std::string car_with(const std::string& from, const std::string& to) {
  std::string xml = car_xml();
  const auto pos = xml.rfind(from);
  EXPECT_NE(pos, std::string::npos) << from;
  if (pos != std::string::npos) xml.replace(pos, from.size(), to);
  return xml;
}

std::string config_error(const std::string& xml) {
  try {
    resolve_plugins(load_urdf_string(xml, "car04"));
  } catch (const LoadError& e) {
    return e.element() + ": " + e.reason();
  }
  return "";
}

}  // namespace

TEST(Plugins, SeedCarHasDiffDriveLaserAndKinect) {
  ASSERT_EQ(car_config().plugins.size(), 3u);
  EXPECT_EQ(car_config().plugins[0].kind, "diff_drive");
  EXPECT_EQ(car_config().plugins[1].kind, "laser");
  EXPECT_EQ(car_config().plugins[2].kind, "openni_kinect");
}

TEST(Plugins, DiffDriveValuesFromMoveXacro) {
  const auto& p = plugin("diff_drive");
  EXPECT_DOUBLE_EQ(p.number("wheelSeparation"), 0.2);   // base_radius * 2
  EXPECT_DOUBLE_EQ(p.number("wheelDiameter"), 0.065);   // wheel_radius * 2
  EXPECT_DOUBLE_EQ(p.number("wheelTorque"), 30.0);
  EXPECT_DOUBLE_EQ(p.number("wheelAcceleration"), 1.8);
  EXPECT_EQ(p.text("leftJoint"), "left2link");
  EXPECT_TRUE(p.flag("publishTf"));                     // written as "1"
  EXPECT_TRUE(p.flag("publishWheelJointState"));
}

TEST(Plugins, DiffDriveDefaultsFilledIn) {
  const auto& p = plugin("diff_drive");
  EXPECT_EQ(p.text("odometrySource"), "world");
  EXPECT_TRUE(p.param("odometrySource").from_default);
  EXPECT_TRUE(p.flag("publishOdomTF"));
  EXPECT_FALSE(p.param("wheelTorque").from_default);
  EXPECT_EQ(p.param("wheelTorque").unit, "N m");
}

TEST(Plugins, LaserScanParameters) {
  const auto& p = plugin("laser");
  EXPECT_EQ(p.sensor, "rplidar");
  // the sensor's link 'laser' is on a fixed joint: lumped into the root, as sdformat does (COMPAT-spawn.md)
  EXPECT_EQ(p.link, "base_footprint");
  EXPECT_DOUBLE_EQ(p.number("ray/scan/horizontal/samples"), 360);
  EXPECT_DOUBLE_EQ(p.number("ray/scan/horizontal/min_angle"), -3.0);
  EXPECT_DOUBLE_EQ(p.number("ray/scan/horizontal/max_angle"), 3.0);
  EXPECT_DOUBLE_EQ(p.number("ray/range/max"), 30.0);
  EXPECT_DOUBLE_EQ(p.number("ray/noise/stddev"), 0.01);
  EXPECT_DOUBLE_EQ(p.number("update_rate"), 5.5);
  EXPECT_EQ(p.text("topicName"), "/scan");
  EXPECT_EQ(p.text("frameName"), "laser");
}

TEST(Plugins, KinectFrameAndCutoffs) {
  const auto& p = plugin("openni_kinect");
  EXPECT_EQ(p.text("frameName"), "support_depth");
  EXPECT_DOUBLE_EQ(p.number("pointCloudCutoff"), 0.4);
  EXPECT_DOUBLE_EQ(p.number("pointCloudCutoffMax"), 5.0);
  EXPECT_TRUE(p.param("pointCloudCutoffMax").from_default);
  EXPECT_NEAR(p.number("camera/horizontal_fov"), 60.0 * 3.1415927 / 180.0, 1e-12);
  EXPECT_EQ(p.text("pointCloudTopicName"), "depth/points");
}

TEST(Plugins, MisspelledDistortionKeyIsWarnedWithSuggestion) {
  bool found = false;
  for (const auto& d : car_config().diagnostics)
    if (d.code == "key-unknown" && d.element == "sensor[camera]/plugin[kinect_camera_controller]/distortion_k1") {
      found = true;
      EXPECT_NE(d.message.find("did you mean <distortionK1>?"), std::string::npos) << d.message;
    }
  EXPECT_TRUE(found);
}

TEST(Plugins, BaselineIsNotedAsUnread) {
  EXPECT_TRUE(has_diag(car_config().diagnostics, "key-ignored",
                       "sensor[camera]/plugin[kinect_camera_controller]/baseline"));
}

TEST(Plugins, FlagsAcceptAnyCase) {
  bool b = false;
  EXPECT_TRUE(parse_flag("TRUE", &b) && b);
  EXPECT_TRUE(parse_flag("0", &b) && !b);
  EXPECT_TRUE(parse_flag(" False ", &b) && !b);
  EXPECT_FALSE(parse_flag("yes", &b));
}

TEST(Plugins, UnknownPluginIsWarned) {
  const auto c = resolve_plugins(load_urdf_string(
      car_with("libgazebo_ros_diff_drive.so", "libgazebo_ros_no_such_plugin.so"), "car04"));
  EXPECT_TRUE(has_diag(c.diagnostics, "plugin-unknown", "gazebo/plugin[differential_drive_controller]"));
}

// ---- bad plug-in blocks: errors name the plug-in or sensor and the key ------------------------------

TEST(PluginErrors, MissingWheelJoint) {
  EXPECT_EQ(config_error(car_with("<leftJoint>left2link</leftJoint>", "<leftJoint>left_joint</leftJoint>")),
            "gazebo/plugin[differential_drive_controller]/leftJoint: joint 'left_joint' not found in the model "
            "(plug-in 'differential_drive_controller', libgazebo_ros_diff_drive.so)");
}

TEST(PluginErrors, NonNumericWheelSeparation) {
  EXPECT_EQ(config_error(car_with("<wheelSeparation>0.2</wheelSeparation>", "<wheelSeparation>wide</wheelSeparation>")),
            "gazebo/plugin[differential_drive_controller]/wheelSeparation: 'wide' is not a number");
}

// Issue 29 item 4: a negative wheel diameter is what Gazebo 11 loads (the wheels turn the other way): a warning;
// 0 is refused (the drive divides by it).
TEST(PluginErrors, NegativeWheelDiameterIsAWarning) {
  const ModelConfig r = resolve_plugins(
      load_urdf_string(car_with("<wheelDiameter>0.065</wheelDiameter>", "<wheelDiameter>-0.065</wheelDiameter>"), "car04"));
  const Diagnostic* d = nullptr;
  for (const auto& x : r.diagnostics)
    if (x.code == "wheel-negative") d = &x;
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->element, "gazebo/plugin[differential_drive_controller]/wheelDiameter");
  EXPECT_EQ(d->message, "is negative (-0.065 m): the wheels turn the other way, as in Gazebo 11");
}

TEST(PluginErrors, ZeroWheelDiameterIsRefused) {
  EXPECT_EQ(config_error(car_with("<wheelDiameter>0.065</wheelDiameter>", "<wheelDiameter>0</wheelDiameter>")),
            "gazebo/plugin[differential_drive_controller]/wheelDiameter: must not be 0 (the drive divides by it)");
}

TEST(PluginErrors, ZeroSamples) {
  EXPECT_EQ(config_error(car_with("<samples>360</samples>", "<samples>0</samples>")),
            "sensor[rplidar]/ray/scan/horizontal/samples: samples must be >= 1");
}

TEST(PluginErrors, MinAngleAboveMaxAngle) {
  EXPECT_EQ(config_error(car_with("<min_angle>-3</min_angle>", "<min_angle>4</min_angle>")),
            "sensor[rplidar]/ray/scan/horizontal/min_angle: min_angle 4 > max_angle 3");
}

TEST(PluginErrors, NearNotBelowFar) {
  EXPECT_EQ(config_error(car_with("<near>0.05</near>", "<near>9</near>")),
            "sensor[camera]/camera/clip/near: near 9 >= far 8.0");
}

TEST(PluginErrors, UnknownImageFormat) {
  EXPECT_EQ(config_error(car_with("<format>R8G8B8</format>", "<format>YUV</format>")), "sensor[camera]/camera/image/format: unknown format 'YUV' (known: L8, L16, R8G8B8, B8G8R8, R16G16B16)");
}
