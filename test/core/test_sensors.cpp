// Sensors in box_house, against distances worked out from the world's geometry.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "car_sim/world.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

std::string car_xml(bool noise) {
  std::string xml = read_text("test/data/car_camera_lidar04.urdf");
  if (!noise) xml.replace(xml.find("<type>gaussian</type>"), 21, "<type>none</type>");
  return xml;
}

std::unique_ptr<World> world_with_car(bool noise, double x = 0, double y = 0, double yaw = 0, uint64_t seed = 0) {
  WorldOptions o;
  o.seed = seed;
  auto w = std::make_unique<World>(load_world_file(std::string(CAR_SOURCE_DIR) + "/worlds/box_house.world"), o);
  w->spawn(load_urdf_string(car_xml(noise), "car"), "mycar", at(x, y, yaw));
  return w;
}

// Distance along a horizontal ray (origin o, angle th) to the nearest upright box or cylinder of the world.
double analytic_range(const WorldDescription& d, const Eigen::Vector2d& o, double th, double t_min, double t_max) {
  const Eigen::Vector2d dir(std::cos(th), std::sin(th));
  double best = std::numeric_limits<double>::infinity();
  for (const auto& m : d.models)
    for (const auto& l : m.links)
      for (const auto& c : l.collisions) {
        const Eigen::Isometry3d T = m.pose * l.pose * c.shape.origin;
        const Eigen::Matrix2d R = T.linear().topLeftCorner<2, 2>();
        const Eigen::Vector2d p = R.transpose() * (o - T.translation().head<2>());
        const Eigen::Vector2d v = R.transpose() * dir;
        double t = std::numeric_limits<double>::infinity();
        if (c.shape.type == ShapeType::Box) {
          // slabs in the box frame
          double lo = -1e18, hi = 1e18;
          for (int k = 0; k < 2; ++k) {
            const double h = c.shape.size[k] / 2;
            if (std::abs(v[k]) < 1e-15) {
              if (std::abs(p[k]) > h) lo = 1e18;
              continue;
            }
            double a = (-h - p[k]) / v[k], b = (h - p[k]) / v[k];
            if (a > b) std::swap(a, b);
            lo = std::max(lo, a);
            hi = std::min(hi, b);
          }
          if (lo <= hi && lo > t_min) t = lo;
        } else if (c.shape.type == ShapeType::Cylinder) {
          const double b = p.dot(v), cc = p.squaredNorm() - c.shape.radius * c.shape.radius;
          const double disc = b * b - cc;
          if (disc >= 0 && -b - std::sqrt(disc) > t_min) t = -b - std::sqrt(disc);
        }
        best = std::min(best, t);
      }
  return best <= t_max ? best : std::numeric_limits<double>::infinity();
}

LaserScanOut one_scan(World& w) {
  w.set_sensor_active("mycar", "gazebo_rplidar", true);
  w.step(200);  // 1 / 5.5 Hz = 182 ms
  const auto out = w.take_sensor_outputs();
  EXPECT_FALSE(out.scans.empty());
  return out.scans.back();
}

CameraOut one_image(World& w) {
  w.set_sensor_active("mycar", "kinect_camera_controller", true);
  w.step(60);  // 20 Hz
  const auto out = w.take_sensor_outputs();
  EXPECT_FALSE(out.images.empty());
  return out.images.back();
}

}  // namespace

TEST(Lidar, ScanGeometryFromTheSensorBlock) {
  auto w = world_with_car(false);
  const LaserScanOut s = one_scan(*w);
  ASSERT_EQ(s.ranges.size(), 360u);
  EXPECT_FLOAT_EQ(s.angle_min, -3.0f);
  EXPECT_FLOAT_EQ(s.angle_max, 3.0f);
  EXPECT_FLOAT_EQ(s.angle_increment, 6.0f / 359.0f);
  EXPECT_FLOAT_EQ(s.range_min, 0.1f);
  EXPECT_FLOAT_EQ(s.range_max, 30.0f);
}

TEST(Lidar, EveryBeamIsTheAnalyticDistanceWithoutNoise) {
  auto w = world_with_car(false, 0.5, -0.5, 0.3);
  const LaserScanOut s = one_scan(*w);
  const Eigen::Isometry3d laser = w->link_pose("mycar", "laser");
  const double yaw = std::atan2(laser.linear()(1, 0), laser.linear()(0, 0));
  for (int i = 0; i < 360; ++i) {
    const double th = yaw - 3.0 + i * 6.0 / 359.0;
    const double expected = analytic_range(w->description(), laser.translation().head<2>(), th, 0.1, 30.0);
    // float32 ranges from a float32 ray kernel: to 0.1 mm (grazing beams lose a few ulps)
    EXPECT_NEAR(s.ranges[i], expected, 1e-4) << "beam " << i;
  }
}

// Gaussian noise of stddev 0.01 m: every beam within 5 sigma (360 beams all fall within 4 sigma only 98 % of the
// time), the spread as configured, no bias.
TEST(Lidar, NoiseIsGaussianWithTheConfiguredSpread) {
  auto w = world_with_car(true, 0.5, -0.5, 0.3);
  const LaserScanOut s = one_scan(*w);
  const Eigen::Isometry3d laser = w->link_pose("mycar", "laser");
  const double yaw = std::atan2(laser.linear()(1, 0), laser.linear()(0, 0));
  double sum = 0.0, sum2 = 0.0;
  int differ = 0;
  for (int i = 0; i < 360; ++i) {
    const double expected = analytic_range(w->description(), laser.translation().head<2>(), yaw - 3.0 + i * 6.0 / 359.0,
                                           0.1, 30.0);
    const double e = s.ranges[i] - expected;
    EXPECT_LE(std::abs(e), 5 * 0.01) << "beam " << i;
    sum += e;
    sum2 += e * e;
    differ += std::abs(e) > 1e-6;
  }
  EXPECT_GT(differ, 340);
  EXPECT_LT(std::abs(sum / 360), 4 * 0.01 / std::sqrt(360.0));
  EXPECT_NEAR(std::sqrt(sum2 / 360), 0.01, 0.002);
}

TEST(Lidar, RateIs5p5HzInSimTime) {
  auto w = world_with_car(false);
  w->set_sensor_active("mycar", "gazebo_rplidar", true);
  w->step(10000);
  EXPECT_NEAR(static_cast<double>(w->take_sensor_outputs().scans.size()), 55.0, 55.0 * 0.05);
}

TEST(Lidar, NothingWhenNobodyListens) {
  auto w = world_with_car(false);
  w->step(1000);
  EXPECT_TRUE(w->take_sensor_outputs().scans.empty());
}

TEST(Lidar, SameSeedSameNoisyScans) {
  auto a = world_with_car(true, 0, 0, 0, 7), b = world_with_car(true, 0, 0, 0, 7);
  const LaserScanOut sa = one_scan(*a), sb = one_scan(*b);
  EXPECT_EQ(0, std::memcmp(sa.ranges.data(), sb.ranges.data(), sa.ranges.size() * sizeof(float)));
  auto c = world_with_car(true, 0, 0, 0, 8);
  EXPECT_NE(0, std::memcmp(sa.ranges.data(), one_scan(*c).ranges.data(), sa.ranges.size() * sizeof(float)));
}

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

namespace {

std::unique_ptr<World> world_with_imu_car() {
  // the seed car with an IMU on base_link (libgazebo_ros_imu_sensor.so), no noise
  std::string xml = car_xml(false);
  xml.insert(xml.rfind("</robot>"),
             "<gazebo reference=\"base_link\"><sensor type=\"imu\" name=\"imu\"><update_rate>100</update_rate>"
             "<plugin name=\"imu_plugin\" filename=\"libgazebo_ros_imu_sensor.so\"><topicName>imu</topicName>"
             "</plugin></sensor></gazebo>");
  auto w = std::make_unique<World>(load_world_file(std::string(CAR_SOURCE_DIR) + "/worlds/box_house.world"));
  w->spawn(load_urdf_string(xml, "car"), "mycar", Eigen::Isometry3d::Identity());
  w->set_sensor_active("mycar", "imu_plugin", true);
  return w;
}

}  // namespace

TEST(Imu, AtRestReadsGravityUp) {
  auto w = world_with_imu_car();
  w->step(1000);
  const auto out = w->take_sensor_outputs();
  ASSERT_FALSE(out.imus.empty());
  const ImuOut& m = out.imus.back();
  EXPECT_NEAR(m.linear_acceleration.z(), 9.8, 0.05);  // specific force: -g
  EXPECT_NEAR(m.angular_velocity.norm(), 0.0, 1e-3);
}

TEST(Imu, TurningOnTheSpotReadsTheYawRate) {
  auto w = world_with_imu_car();
  w->set_cmd_vel("mycar", 0.0, 1.0);
  w->step(2000);
  const auto out = w->take_sensor_outputs();
  ASSERT_FALSE(out.imus.empty());
  EXPECT_NEAR(out.imus.back().angular_velocity.z(), 1.0, 0.02);
  EXPECT_EQ(out.imus.size(), 200u);  // 100 Hz for 2 s
}

TEST(Lidar, NoHitIsPlusInfinity) {
  // the empty world: level beams at z = 0.27 m never meet the ground plane
  World w(empty_world());
  w.spawn(load_urdf_string(car_xml(false), "car"), "mycar", Eigen::Isometry3d::Identity());
  const LaserScanOut s = one_scan(w);
  for (float r : s.ranges) EXPECT_TRUE(std::isinf(r) && r > 0);
}

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
  const auto out = w.take_sensor_outputs();
  ASSERT_EQ(out.images.size(), 2u);  // 10 Hz for 0.2 s
  const CameraOut& c = out.images.back();
  EXPECT_EQ(c.encoding, "mono8");
  EXPECT_EQ(c.image.size(), 64u * 48u);
  EXPECT_FALSE(c.has_depth);
  EXPECT_NEAR(c.f, 64 / (2 * std::tan(0.5)), 1e-9);
  // the brick wall ahead in the ambient light: luminance of (63, 33, 24)
  EXPECT_EQ(c.image[24 * 64 + 32], static_cast<uint8_t>(0.299f * 63 + 0.587f * 33 + 0.114f * 24 + 0.5f));
}
