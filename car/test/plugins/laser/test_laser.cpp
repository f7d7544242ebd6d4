// The lidar (libgazebo_ros_laser.so) in box_house, against distances worked out from the world's geometry.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "laser/laser.hpp"
#include "laser/ziggurat.hpp"
#include "../range/ray_world.hpp"
#include "seed_car.hpp"

using namespace car_sim;
using namespace car_sim::test_support;

namespace {

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
  const auto scans = w.take_outputs<LaserScanOut>();
  EXPECT_FALSE(scans.empty());
  return scans.back();
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

// Gaussian noise of stddev sigma = 0.01 m on n = 360 beams (world seed fixed: the same draw every run; the bands
// say how often another seed would fail):
// - every beam within 5 sigma: P(|z| > 5) = 5.7e-7 a beam, 2e-4 a scan (4 sigma would fail 2 % of scans);
// - noise on more than 340 beams: a noisy beam lands within 1e-6 m of the truth with probability 8e-5;
// - no bias: the mean's sigma is sigma / sqrt(n) = 0.53 mm, the band 4 of them (2.1 mm; P 6e-5), far above the
//   0.1 mm the analytic ranges and float32 leave; a bias of one sigma (0.01 m) is 19 of them;
// - the spread: the standard deviation estimate's sigma is about sigma / sqrt(2 n) = 0.37 mm, the band 2 mm (20 % of
//   sigma) is 5.4 of them: this seed reads 0.0099 m, and a spread 20 % off (0.012 m) fails.
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
  // Scans at ticks ceil(k * 2000 / 11), k = 1, 2, ... (5.5 Hz at 1 ms: a period of 2000/11 ticks, Schedule): over
  // ticks 1..10000, k * 2000 / 11 <= 10000 gives k <= 55, exactly 55 scans.
  EXPECT_EQ(w->take_outputs<LaserScanOut>().size(), 55u);
}

TEST(Lidar, NothingWhenNobodyListens) {
  auto w = world_with_car(false);
  w->step(1000);
  EXPECT_TRUE(w->take_outputs<LaserScanOut>().empty());
}

TEST(Lidar, SameSeedSameNoisyScans) {
  auto a = world_with_car(true, 0, 0, 0, 7), b = world_with_car(true, 0, 0, 0, 7);
  const LaserScanOut sa = one_scan(*a), sb = one_scan(*b);
  EXPECT_EQ(0, std::memcmp(sa.ranges.data(), sb.ranges.data(), sa.ranges.size() * sizeof(float)));
  auto c = world_with_car(true, 0, 0, 0, 8);
  EXPECT_NE(0, std::memcmp(sa.ranges.data(), one_scan(*c).ranges.data(), sa.ranges.size() * sizeof(float)));
}

TEST(Lidar, NoHitIsPlusInfinity) {
  // the empty world: level beams at z = 0.27 m never meet the ground plane
  World w(empty_world());
  w.spawn(load_urdf_string(car_xml(false), "car"), "mycar", Eigen::Isometry3d::Identity());
  const LaserScanOut s = one_scan(w);
  for (float r : s.ranges) EXPECT_TRUE(std::isinf(r) && r > 0);
}

// The ziggurat the lidar's noise comes from, against N(0, 1) over 2 000 000 samples: mean 0 and variance 1 (to
// 5 standard errors: 0.0035 and 0.005), the fractions beyond 1, 2 and 3 sigma 0.3173, 0.0455 and 0.0027 (the tail
// path beyond 3.44), and symmetric; the same seed gives the same samples.
TEST(Lidar, ZigguratSamplesTheStandardNormal) {
  const Ziggurat z;
  std::mt19937_64 rng(42);
  const int n = 2000000;
  double sum = 0, sum2 = 0;
  int beyond1 = 0, beyond2 = 0, beyond3 = 0, beyond_r = 0, negative = 0;
  for (int i = 0; i < n; ++i) {
    const double x = z.standard(rng);
    sum += x;
    sum2 += x * x;
    beyond1 += std::abs(x) > 1;
    beyond2 += std::abs(x) > 2;
    beyond3 += std::abs(x) > 3;
    beyond_r += std::abs(x) > 3.5;
    negative += x < 0;
  }
  EXPECT_NEAR(sum / n, 0.0, 0.0035);
  EXPECT_NEAR(sum2 / n, 1.0, 0.005);
  EXPECT_NEAR(beyond1 / double(n), 0.31731, 0.0017);
  EXPECT_NEAR(beyond2 / double(n), 0.04550, 0.0007);
  EXPECT_NEAR(beyond3 / double(n), 0.00270, 0.00019);
  EXPECT_NEAR(beyond_r / double(n), 0.000465, 0.00008);  // 2 (1 - Phi(3.5)), drawn by the tail method
  EXPECT_NEAR(negative / double(n), 0.5, 0.0018);
  std::mt19937_64 a(7), b(7);
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(z.standard(a), z.standard(b));
}

// Several vertical rows: Gazebo's RaySensor scans every row, index j * 3 + i (rows outer), and gazebo_ros_laser
// copies all nine ranges into the LaserScan, whose angles stay the horizontal ones. The layout is observable: the
// 3 x 3 rays have yaws h_i = 0, 0.2, 0.4 rad and pitches v_j = -0.2, -0.1, 0 rad (different spans, neither
// symmetric about 0), from 0.1 m ahead of the cube's centre and 0.4 m above it (z = 0.5 m), facing a wall whose
// face is the plane x = 2.0 m and which spans only y in [-0.1, 2.0] m and z in [0, 0.55] m. Ray (i, j) meets it at
// 1.9 / (cos v_j cos h_i) m (to 1.9 tan 0.4 = 0.80 m left and 1.9 tan 0.2 = 0.39 m down). So columns outer
// (index i * 3 + j) puts cos 0.2 where cos 0.1 belongs (ray 1: 1.9 / (cos 0.2 cos 0.2) = 1.978 m against
// 1.9 / (cos 0.1 cos 0) = 1.910 m), a reversed order swaps cos 0 and cos 0.4 (0.17 m), and a mirrored axis misses
// the wall: yaw -0.2 passes its edge at y = -0.1 m (y = -0.39 m), pitch +0.1 its top (z = 0.69 m). 1e-4 m: float32
// directions and ranges (as for the single row above).
TEST(Lidar, SeveralRowsGiveEveryRayRowsOuter) {
  const std::string sensor = ray_sensor(
      "ray", "lidar", "0.1 0 0.4 0 0 0", scan_axis(3, 0.0, 0.4), scan_axis(3, -0.2, 0.0), 0.05, 5.0,
      "<plugin name='lidar' filename='libgazebo_ros_laser.so'><topicName>scan</topicName></plugin>");
  auto w = world_with_cube(ray_world(box_model("wall", 2.1, 0.95, 0.275, 0.2, 2.1, 0.55)), sensor);
  w->set_sensor_active("cube", "lidar", true);
  w->step(200);
  const auto scans = w->take_outputs<LaserScanOut>();
  ASSERT_FALSE(scans.empty());
  const LaserScanOut& s = scans.back();
  EXPECT_FLOAT_EQ(s.angle_min, 0.0f);
  EXPECT_FLOAT_EQ(s.angle_max, 0.4f);
  EXPECT_FLOAT_EQ(s.angle_increment, 0.2f);
  ASSERT_EQ(s.ranges.size(), 9u);
  ASSERT_EQ(s.intensities.size(), 9u);
  const double h[3] = {0.0, 0.2, 0.4}, v[3] = {-0.2, -0.1, 0.0};
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      EXPECT_NEAR(s.ranges[j * 3 + i], 1.9 / (std::cos(v[j]) * std::cos(h[i])), 1e-4) << "ray " << i << ", row " << j;
}
