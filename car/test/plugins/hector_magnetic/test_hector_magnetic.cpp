// hector's magnetometer (libhector_gazebo_ros_magnetic.so) on the cube: the reference field, turned into the
// body frame, through the sensor model.
#include <gtest/gtest.h>

#include <cmath>

#include "../range/ray_world.hpp"
#include "hector_magnetic/hector_magnetic.hpp"

using namespace car_sim;
using namespace car_sim::test_support;

namespace {

std::string with_plugin(const std::string& keys) {
  std::string xml = cube_robot("");
  xml.insert(xml.rfind("</robot>"), "<gazebo><plugin name='mag' filename='libhector_gazebo_ros_magnetic.so'>"
                                    "<updateRate>10</updateRate>" + keys + "</plugin></gazebo>");
  return xml;
}

MagneticOut reading(const std::string& keys, double yaw = 0) {
  World w(ray_world(""));
  Eigen::Isometry3d p = at(0, 0, yaw);
  p.translation().z() = 0.1;
  w.spawn(load_urdf_string(with_plugin(keys), "cube"), "cube", p);
  w.set_plugin_active("cube", "mag", true);
  w.step(500);
  const auto rs = w.take_outputs<MagneticOut>();
  EXPECT_EQ(rs.size(), 5u);  // 10 Hz
  return rs.back();
}

}  // namespace

// Defaults: magnitude 1, inclination 60 deg, declination and heading 0: field (cos 60, 0, -sin 60) =
// (0.5, 0, -0.866) in the world, and in the body frame of a cube that has not turned.
TEST(HectorMagnetic, DefaultFieldPointsDownAlongX) {
  const MagneticOut m = reading("");
  EXPECT_NEAR(m.field.x(), 0.5, 1e-4);
  EXPECT_NEAR(m.field.y(), 0.0, 1e-4);
  EXPECT_NEAR(m.field.z(), -std::sqrt(3.0) / 2, 1e-4);
}

// Turned by yaw 90 deg, the body's x is the world's y and its y the world's -x: the field reads (0, -0.5, -0.866).
TEST(HectorMagnetic, TurningTheBodyTurnsTheField) {
  const MagneticOut m = reading("", M_PI / 2);
  EXPECT_NEAR(m.field.x(), 0.0, 1e-3);
  EXPECT_NEAR(m.field.y(), -0.5, 1e-3);
  EXPECT_NEAR(m.field.z(), -std::sqrt(3.0) / 2, 1e-4);
}

// magnitude 2, declination 10 deg, inclination 30 deg, offset (0.1, 0, 0):
// 2 (cos 30 cos(-10), cos 30 sin(-10), -sin 30) + (0.1, 0, 0) = (1.8058, -0.3008, -1.0).
TEST(HectorMagnetic, DeclinationInclinationMagnitudeAndOffset) {
  const MagneticOut m = reading("<magnitude>2</magnitude><declination>10</declination><inclination>30</inclination>"
                                "<offset>0.1 0 0</offset>");
  const double d = 10 * M_PI / 180, i = 30 * M_PI / 180;
  EXPECT_NEAR(m.field.x(), 2 * std::cos(i) * std::cos(-d) + 0.1, 1e-4);
  EXPECT_NEAR(m.field.y(), 2 * std::cos(i) * std::sin(-d), 1e-4);
  EXPECT_NEAR(m.field.z(), -2 * std::sin(i), 1e-4);
}

// One number for a vector key is what hector's plug-in cannot read: a warning naming the key, the default kept.
TEST(HectorMagnetic, OneNumberForAVectorKeyIsWarnedAndIgnored) {
  const ModelConfig cfg = resolve_plugins(load_urdf_string(with_plugin("<offset>0.3</offset>"), "cube"));
  bool warned = false;
  for (const auto& d : cfg.diagnostics) warned = warned || d.element.find("offset") != std::string::npos;
  EXPECT_TRUE(warned);
  EXPECT_NEAR(reading("<offset>0.3</offset>").field.x(), 0.5, 1e-4);
}

// Upstream's Load logs and returns: the model loads without the plug-in, with a warning.
TEST(HectorMagnetic, UnknownBodyLeavesThePluginOut) {
  const ModelConfig c = resolve_plugins(load_urdf_string(with_plugin("<bodyName>nope</bodyName>"), "cube"));
  EXPECT_TRUE(c.plugins.empty());
  ASSERT_FALSE(c.diagnostics.empty());
  const Diagnostic& d = c.diagnostics.back();
  EXPECT_EQ(d.code, "plugin-not-loaded");
  EXPECT_EQ(d.element, "gazebo/plugin[mag]/bodyName");
  EXPECT_EQ(d.message, "GazeboRosMagnetic plugin error: bodyName: nope does not exist; the plug-in is not loaded");
}
