// hector's GPS (libhector_gazebo_ros_gps.so) on the cube: latitude and longitude from the position on the WGS84
// ellipsoid's local radii.
#include <gtest/gtest.h>

#include <cmath>

#include "../range/ray_world.hpp"
#include "hector_gps/hector_gps.hpp"

using namespace car_sim;
using namespace car_sim::test_support;

namespace {

std::string with_plugin(const std::string& keys) {
  std::string xml = cube_robot("");
  xml.insert(xml.rfind("</robot>"),
             "<gazebo><plugin name='gps' filename='libhector_gazebo_ros_gps.so'>" + keys + "</plugin></gazebo>");
  return xml;
}

std::vector<GpsOut> fixes(const std::string& keys, double x, double y, uint64_t steps = 1000) {
  World w(ray_world(""));
  Eigen::Isometry3d p = at(x, y, 0);
  p.translation().z() = 0.1;
  w.spawn(load_urdf_string(with_plugin(keys), "cube"), "cube", p);
  w.set_plugin_active("cube", "gps", true);
  w.step(steps);
  return w.take_outputs<GpsOut>();
}

// The radii at 49.9 deg (WGS84: a = 6378137 m, e^2 = 2f - f^2 with f = 1/298.257223563):
// t = 1 / (1 - e^2 sin^2 49.9) = 1.00393232, N = a sqrt(t) = 6390665.1 m,
// R_north = N (1 - e^2) t = 6372845.5 m, R_east = N cos 49.9 = 4116378.4 m.
constexpr double kRNorth = 6372845.5, kREast = 4116378.4;

}  // namespace

// At 4 Hz by default; at (10, 20) with heading 0 (x north, y west): lat = 49.9 + 10 / R_north rad,
// lon = 8.9 - 20 / R_east rad, alt = the link's height 0.1 m; at rest the velocity is zero.
TEST(HectorGps, PositionToLatitudeAndLongitude) {
  const auto fs = fixes("", 10, 20);
  ASSERT_EQ(fs.size(), 4u);
  const GpsOut& f = fs.back();
  EXPECT_NEAR(f.latitude, 49.9 + 10 / kRNorth * 180 / M_PI, 1e-9);
  EXPECT_NEAR(f.longitude, 8.9 - 20 / kREast * 180 / M_PI, 1e-9);
  EXPECT_NEAR(f.altitude, 0.1, 2e-3);
  EXPECT_NEAR(f.velocity.norm(), 0.0, 1e-3);
  EXPECT_EQ(f.status, 0);  // STATUS_FIX
}

// referenceHeading 90 deg turns the frame: lat = lat0 + y / R_north, lon = lon0 + x / R_east (east-north-up).
TEST(HectorGps, ReferenceHeadingNinetyIsEastNorthUp) {
  const GpsOut f = fixes("<referenceHeading>90</referenceHeading><referenceLatitude>49.9</referenceLatitude>"
                         "<referenceAltitude>100</referenceAltitude>",
                         10, 20)
                       .back();
  EXPECT_NEAR(f.latitude, 49.9 + 20 / kRNorth * 180 / M_PI, 1e-9);
  EXPECT_NEAR(f.longitude, 8.9 + 10 / kREast * 180 / M_PI, 1e-9);
  EXPECT_NEAR(f.altitude, 100.1, 2e-3);
}

// An offset of (1, 0, 0) m in the position model moves the fix 1 m north; the variance is drift^2 + noise^2.
TEST(HectorGps, PositionModelOffsetAndVariance) {
  const GpsOut f = fixes("<offset>1 0 0</offset><gaussianNoise>0 0 0</gaussianNoise><drift>0.5 0 0</drift>"
                         "<driftFrequency>0 0 0</driftFrequency>",
                         0, 0)
                       .back();
  EXPECT_NEAR(f.position_variance.x(), 0.25, 1e-12);
  // the drift starts at N(0, 0.5) and stays (frequency 0), so only the offset is known exactly: the fix is
  // 1 m + drift north of the origin; the drift is what the same seed gives again
  const GpsOut g = fixes("<offset>1 0 0</offset><gaussianNoise>0 0 0</gaussianNoise><drift>0.5 0 0</drift>"
                         "<driftFrequency>0 0 0</driftFrequency>",
                         0, 0)
                       .back();
  EXPECT_EQ(f.latitude, g.latitude);
  const GpsOut h = fixes("<offset>1 0 0</offset>", 0, 0).back();
  EXPECT_NEAR(h.latitude, 49.9 + 1 / kRNorth * 180 / M_PI, 1e-9);
}

TEST(HectorGps, UpdateRateSetsTheRate) { EXPECT_EQ(fixes("<updateRate>20</updateRate>", 0, 0).size(), 20u); }

TEST(HectorGps, NonNumericVectorIsALoadError) {
  try {
    resolve_plugins(load_urdf_string(with_plugin("<velocityDrift>a b c</velocityDrift>"), "cube"));
    FAIL() << "no error";
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("plugin[gps]/velocityDrift"), std::string::npos) << e.what();
  }
}
