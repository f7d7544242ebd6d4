// Convex shapes on a plane (physics/plane_collision.cpp: SpherePlaneAlgorithm, ConvexPlaneAlgorithm, BoxPlaneAlgorithm;
// docs/COMPAT-physics.md "Contact points"): a sphere touches at one point under its centre along the plane's
// normal, and a shape whose narrow phase is skipped while it is clearly above the plane still lands on it. g = 10
// m/s^2, dt = 1 ms; expected values by hand in the comments.
#include <gtest/gtest.h>

#include "physics_fixtures.hpp"

using namespace car_sim;
using namespace car_sim::test_physics;

namespace {

// A one-link robot of 1 kg whose collision is `geometry` (inertia of a 0.2 m cube: the contacts do not depend on it).
RobotModel body(const std::string& geometry) {
  return load_urdf_string("<robot name=\"body\"><link name=\"base\">" + box_inertial(1.0, 0.2, 0.2, 0.2) +
                              "<collision><geometry>" + geometry + "</geometry></collision></link></robot>",
                          "body.urdf");
}

// The world's ground plane with the given normal, through the collision frame's origin at height z0.
WorldDescription plane(const std::string& normal, double z0) {
  return world(fmt("<collision name=\"c\"><pose>0 0 %g 0 0 0</pose>", z0) + "<geometry><plane><normal>" + normal +
               "</normal><size>100 100</size></plane></geometry></collision>");
}

// Steps p n times; the lowest height [m] r's root reached.
double lowest_height(physics::Physics& p, physics::Robot& r, int n) {
  double lowest = r.root_state().pose.translation().z();
  for (int i = 0; i < n; ++i) {
    p.step(kDt);
    lowest = std::min(lowest, r.root_state().pose.translation().z());
  }
  return lowest;
}

}  // namespace

TEST(PlaneContacts, ABallRestsOnOnePointUnderItsCentre) {
  // r = 0.1 m at (0.3, -0.2): one point at (0.3, -0.2, 0) carrying m g = 10 N, the centre at r
  physics::Physics p(flat(), options(), {});
  physics::Robot& r = p.add_robot(body("<sphere radius=\"0.1\"/>"), "ball", pose(0.3, -0.2, 0.1), {});
  run(p, 500);
  const std::vector<Contact> c = p.contacts(kDt);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].position.x(), 0.3, 1e-9);
  EXPECT_NEAR(c[0].position.y(), -0.2, 1e-9);
  EXPECT_NEAR(c[0].position.z(), 0.0, 1e-9);
  EXPECT_NEAR((c[0].normal - Eigen::Vector3d::UnitZ()).norm(), 0.0, 1e-12);
  EXPECT_NEAR(c[0].normal_force, 10.0, 0.1);
  EXPECT_NEAR(r.root_state().pose.translation().z(), 0.1, 1e-3);
}

TEST(PlaneContacts, ABallTouchesATiltedPlaneAlongItsNormal) {
  // normal n = (0.6, 0, 0.8) through (0, 0, 0.5): the plane n.x = 0.4. p0 = (1, 2, -0.25) lies on it; a ball of
  // r = 0.1 centred at p0 + r n = (1.06, 2, -0.17) touches it at p0, pushed by gravity along -n
  physics::Physics p(plane("0.6 0 0.8", 0.5), options(), {});
  p.add_robot(body("<sphere radius=\"0.1\"/>"), "ball", pose(1.06, 2.0, -0.17), {});
  run(p, 1);
  const std::vector<Contact> c = p.contacts(kDt);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR((c[0].normal - Eigen::Vector3d(0.6, 0, 0.8)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((c[0].position - Eigen::Vector3d(1.0, 2.0, -0.25)).norm(), 0.0, 1e-4);
}

TEST(PlaneContacts, ADroppedCylinderLandsOnThePlane) {
  // lying on its side (axis along x), r = 0.05 m, dropped from 0.3 m: it comes to rest with its axis at r
  physics::Physics p(flat(), options(), {});
  Eigen::Isometry3d T = pose(0, 0, 0.3);
  T.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  physics::Robot& r = p.add_robot(body("<cylinder radius=\"0.05\" length=\"0.2\"/>"), "can", T, {});
  // its contact is found before it reaches the plane (2.3 m/s: 2.3 mm a step): it lands about 1 mm deep at most, as
  // with Bullet's convex-plane algorithm alone (found 20 mm late, it sinks 27 mm)
  const double lowest = lowest_height(p, r, 1500);
  EXPECT_GT(lowest, 0.05 - 2e-3);
  EXPECT_NEAR(r.root_state().pose.translation().z(), 0.05, 1e-3);
}

TEST(PlaneContacts, ADroppedBoxLandsOnThePlane) {
  // a 0.2 m cube dropped from 0.5 m rests with its centre at 0.1 m
  physics::Physics p(flat(), options(), {});
  physics::Robot& r = p.add_robot(body("<box size=\"0.2 0.2 0.2\"/>"), "cube", pose(0, 0, 0.5), {});
  // it lands without sinking in (2.8 m/s: 2.8 mm a step)
  const double lowest = lowest_height(p, r, 1500);
  EXPECT_GT(lowest, 0.1 - 1e-3);
  EXPECT_NEAR(r.root_state().pose.translation().z(), 0.1, 1e-3);
}

TEST(PlaneContacts, ACompoundRestsOnTheCornersOfEachChild) {
  // one link, two 0.1 m cubes centred at x = +-0.1 (a compound shape), dropped from 0.3 m: it rests with its
  // origin at 0.05 m on bottom corners of both cubes (the solver may leave one of the eight without load), which
  // carry m g = 10 N together
  physics::Physics p(flat(), options(), {});
  const RobotModel m = load_urdf_string(
      "<robot name=\"pair\"><link name=\"base\">" + box_inertial(1.0, 0.3, 0.1, 0.1) +
          "<collision><origin xyz=\"0.1 0 0\"/><geometry><box size=\"0.1 0.1 0.1\"/></geometry></collision>"
          "<collision><origin xyz=\"-0.1 0 0\"/><geometry><box size=\"0.1 0.1 0.1\"/></geometry></collision>"
          "</link></robot>",
      "pair.urdf");
  physics::Robot& r = p.add_robot(m, "pair", pose(0, 0, 0.3), {});
  run(p, 1500);
  EXPECT_NEAR(r.root_state().pose.translation().z(), 0.05, 1e-3);
  const std::vector<Contact> c = p.contacts(kDt);
  ASSERT_GE(c.size(), 3u);
  ASSERT_LE(c.size(), 8u);
  double force = 0, right = 0, moment_x = 0, moment_y = 0;
  for (const Contact& k : c) {
    // a corner: x at 0.05 or 0.15 from the middle, y at 0.05
    const double x = std::abs(k.position.x());
    EXPECT_NEAR(std::min(std::abs(x - 0.05), std::abs(x - 0.15)), 0.0, 1e-4) << k.position.transpose();
    EXPECT_NEAR(std::abs(k.position.y()), 0.05, 1e-4) << k.position.transpose();
    force += k.normal_force;
    if (k.position.x() > 0) right += k.normal_force;
    moment_x += k.normal_force * k.position.x();
    moment_y += k.normal_force * k.position.y();
  }
  EXPECT_NEAR(force, 10.0, 0.1);
  // at rest about its centre of mass (the split between the corners is the solver's: the rest is statically
  // indeterminate), on both cubes
  EXPECT_NEAR(moment_x, 0.0, 0.01);
  EXPECT_NEAR(moment_y, 0.0, 0.01);
  EXPECT_GT(right, 0.5);
  EXPECT_GT(force - right, 0.5);
}
