// The range sensor (libgazebo_ros_range.so): the nearest hit of its cone of rays, against a wall's geometry.
#include <gtest/gtest.h>

#include <cmath>

#include "range/range.hpp"
#include "ray_world.hpp"

using namespace car_sim;
using namespace car_sim::test_support;

namespace {

// A wall 0.2 m thick, 4 m wide, 1 m high, its near face on the plane x = 2.0 m.
WorldDescription wall_world() { return ray_world(box_model("wall", 2.1, 0, 0.5, 0.2, 4, 1)); }

// A sonar 0.1 m ahead of the cube's centre and 0.4 m above it (z = 0.5 m over the ground): 5 x 5 rays over
// +-0.15 rad both ways, range 0.02..3 m.
std::string sonar(const std::string& extra = "", const std::string& rmax = "3") {
  return ray_sensor("ray", "sonar", "0.1 0 0.4 0 0 0", scan_axis(5, -0.15, 0.15), scan_axis(5, -0.15, 0.15), 0.02,
                    std::stod(rmax),
                    "<plugin name='sonar_plugin' filename='libgazebo_ros_range.so'><topicName>sonar</topicName>"
                    "<frameName>sonar_link</frameName><fov>0.3</fov>" + extra + "</plugin>");
}

RangeOut one_range(World& w) {
  w.set_sensor_active("cube", "sonar_plugin", true);
  w.step(100);  // 10 Hz at 1 ms
  const auto rs = w.take_outputs<RangeOut>();
  EXPECT_FALSE(rs.empty());
  return rs.back();
}

// [m] distance from the sonar to the wall's plane along the world's x
double to_wall(World& w) {
  const Eigen::Isometry3d s = w.link_pose("cube", "base") * Eigen::Translation3d(0.1, 0, 0.4);
  return 2.0 - s.translation().x();
}

}  // namespace

// Facing the wall: the middle ray (yaw 0, pitch 0) is the nearest, d = 2.0 - 0.1 = 1.9 m.
TEST(Range, FacingTheWallReadsThePerpendicularDistance) {
  auto w = world_with_cube(wall_world(), sonar());
  const RangeOut r = one_range(*w);
  EXPECT_NEAR(to_wall(*w), 1.9, 2e-3);  // the cube rests where it was put
  EXPECT_NEAR(r.range, to_wall(*w), 1e-4);
  EXPECT_FLOAT_EQ(r.min_range, 0.02f);
  EXPECT_FLOAT_EQ(r.max_range, 3.0f);
  EXPECT_FLOAT_EQ(r.field_of_view, 0.3f);
  EXPECT_EQ(r.radiation, 0);  // ultrasound by default
}

// Turned by yaw 0.1 rad: ray yaws relative to the wall's normal are 0.1 + {-0.15, -0.075, 0, 0.075, 0.15} =
// {-0.05, 0.025, 0.1, 0.175, 0.25}; the nearest hit is the pitch-0 ray at 0.025 rad: d / cos(0.025).
TEST(Range, TheNearestRayOfTheConeWins) {
  auto w = world_with_cube(wall_world(), sonar(), 0, 0, 0.1);
  const RangeOut r = one_range(*w);
  const Eigen::Isometry3d s = w->link_pose("cube", "base") * Eigen::Translation3d(0.1, 0, 0.4);
  const double yaw = std::atan2(s.linear()(1, 0), s.linear()(0, 0));
  EXPECT_NEAR(yaw, 0.1, 1e-3);
  EXPECT_NEAR(r.range, (2.0 - s.translation().x()) / std::cos(yaw - 0.075), 1e-4);
}

// Facing away from the wall, nothing within 3 m (the lowest rays, pitch -0.15 from z = 0.5 m, meet the ground at
// 0.5 / sin(0.15) = 3.35 m): every ray reads range.max, so does the sensor.
TEST(Range, NothingInViewReadsMaxRange) {
  auto w = world_with_cube(wall_world(), sonar(), 0, 0, M_PI);
  EXPECT_FLOAT_EQ(one_range(*w).range, 3.0f);
}

TEST(Range, RadiationOtherThanUltrasoundIsInfrared) {
  auto w = world_with_cube(wall_world(), sonar("<radiation>infrared</radiation>"));
  EXPECT_EQ(one_range(*w).radiation, 1);
}

// gaussianNoise sigma = 0.01 m: n = 200 readings (world seed fixed: the same draw every run; the bands say how often
// another seed would fail) spread by sigma around the distance to the wall. The mean's sigma is sigma / sqrt(n) =
// 0.71 mm, the band 4 of them (2.8 mm; P 6e-5); the standard deviation estimate's sigma is about sigma / sqrt(2 n) =
// 0.5 mm, the band 2 mm (20 % of sigma) is 4 of them: this seed reads 0.0107 m, and a spread 30 % off fails.
TEST(Range, NoiseHasTheConfiguredSpread) {
  auto w = world_with_cube(wall_world(), sonar("<gaussianNoise>0.01</gaussianNoise>"));
  w->set_sensor_active("cube", "sonar_plugin", true);
  w->step(20000);
  const auto rs = w->take_outputs<RangeOut>();
  ASSERT_EQ(rs.size(), 200u);
  const double d = to_wall(*w);
  double sum = 0, sum2 = 0;
  for (const auto& r : rs) {
    sum += r.range - d;
    sum2 += (r.range - d) * (r.range - d);
  }
  EXPECT_LT(std::abs(sum / 200), 4 * 0.01 / std::sqrt(200.0));
  EXPECT_NEAR(std::sqrt(sum2 / 200), 0.01, 0.002);
}

TEST(Range, ZeroSamplesIsALoadErrorNamingTheKey) {
  std::string s = sonar();
  s.replace(s.find("<samples>5</samples>"), 20, "<samples>0</samples>");
  try {
    World w(wall_world());
    w.spawn(load_urdf_string(cube_robot(s), "cube"), "cube", at(0, 0, 0));
    FAIL() << "no error";
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("sensor[sonar]/ray/scan/horizontal/samples"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("samples must be >= 1"), std::string::npos) << e.what();
  }
}

// An axis of one sample looks straight ahead whatever its min_angle (Gazebo's MultiRayShape::Init: yaw and pitch
// 0 for one sample): one ray with min_angle -0.5 reads the perpendicular 1.9 m, not 1.9 / cos 0.5 = 2.17 m.
TEST(Range, OneSampleLooksStraightAhead) {
  const std::string one = ray_sensor(
      "ray", "sonar", "0.1 0 0.4 0 0 0", scan_axis(1, -0.5, 0.5), scan_axis(1, -0.3, 0.3), 0.02, 3.0,
      "<plugin name='sonar_plugin' filename='libgazebo_ros_range.so'><topicName>sonar</topicName>"
      "<frameName>sonar_link</frameName></plugin>");
  auto w = world_with_cube(wall_world(), one);
  EXPECT_NEAR(one_range(*w).range, to_wall(*w), 1e-4);
}

// A gpu_ray sensor is no RaySensor: upstream's RayPlugin::Load throws "RayPlugin requires a Ray Sensor as its parent". The model loads without the plug-in.
TEST(Range, OnAGpuRaySensorThePluginDoesNotLoad) {
  EXPECT_EQ(not_loaded_on("gpu_ray", "<plugin name='p' filename='libgazebo_ros_range.so'/>"),
            "libgazebo_ros_range.so needs a sensor of type ray, not 'gpu_ray'; the plug-in is not loaded");
}
