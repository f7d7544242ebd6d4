// Simulation islands are joined by contact (docs/COMPAT-physics.md "Islands"), as ODE joins bodies through contact
// joints in Gazebo: a resting object stays asleep while a robot passes within its bounding box without touching it,
// and wakes when the robot touches it. (Bullet's own rule joins objects whose bounding boxes overlap, so a robot
// passing by wakes everything it comes near.)
#include <gtest/gtest.h>

#include <btBulletDynamicsCommon.h>

#include <cstring>

#include "physics_fixtures.hpp"

using namespace car_sim;
using namespace car_sim::test_physics;

namespace {

// The ground and a 0.5 m crate of 10 kg resting on it at the origin.
WorldDescription crate_world() {
  const std::string xml =
      "<?xml version=\"1.0\"?><sdf version=\"1.7\"><world name=\"w\">" + fmt("<gravity>0 0 %g</gravity>", -kG) +
      "<physics type=\"ode\"><max_step_size>0.001</max_step_size></physics>"
      "<model name=\"ground\"><static>true</static><link name=\"l\"><collision name=\"c\"><geometry><plane>"
      "<normal>0 0 1</normal><size>100 100</size></plane></geometry></collision></link></model>"
      "<model name=\"crate\"><pose>0 0 0.25 0 0 0</pose><link name=\"l\"><inertial><mass>10</mass><inertia>"
      "<ixx>0.4167</ixx><iyy>0.4167</iyy><izz>0.4167</izz><ixy>0</ixy><ixz>0</ixz><iyz>0</iyz></inertia></inertial>"
      "<collision name=\"c\"><geometry><box><size>0.5 0.5 0.5</size></box></geometry></collision></link></model>"
      "</world></sdf>";
  return load_world_string(xml, "islands-test.world");
}

struct Scene {
  WorldDescription desc = crate_world();  // the Physics reads its world models from it
  physics::Physics p{desc, options(), {}};
  // a 0.2 m cube, resting on the ground
  physics::Robot& probe = p.add_robot(block(1.0, 0.2, 0.2, 0.2, ""), "probe", pose(-1.0, 0.0, 0.1), {});
};

bool asleep(Scene& s) { return s.p.world_model_body("crate", 0)->getActivationState() == ISLAND_SLEEPING; }

// Puts the probe at (x, y) on the ground, at rest.
void place(Scene& s, double x, double y) {
  ModelState st;
  st.pose = pose(x, y, 0.1);
  st.linear.setZero();
  st.angular.setZero();
  s.probe.set_root_state(st);
}

std::vector<double> crate_state(Scene& s) {
  const ModelState m = *s.p.world_model_state("crate");
  std::vector<double> v(m.pose.linear().data(), m.pose.linear().data() + 9);
  for (int i = 0; i < 3; ++i) v.push_back(m.pose.translation()[i]);
  return v;
}

}  // namespace

TEST(Islands, RobotPassingWithinTheBoundingBoxLeavesARestingObjectAsleep) {
  Scene s;
  // [m]: the probe's side 3 cm from the crate's: beyond the manifold's contact threshold (2 % of the probe's
  // bounding radius, 3.5 mm, plus the margins), while both bounding boxes (each grown by Bullet's 2 cm) overlap
  const double y = 0.25 + 0.1 + 0.03;
  place(s, -1.0, y);
  run(s.p, 2500);
  ASSERT_TRUE(asleep(s)) << "the crate did not fall asleep at rest within 2.5 s";
  const std::vector<double> before = crate_state(s);
  // past the crate at 1 m/s, 1 mm a step
  for (int i = 0; i <= 2000; ++i) {
    place(s, -1.0 + 0.001 * i, y);
    s.p.step(kDt);
    ASSERT_TRUE(asleep(s)) << "woken with the probe at x = " << -1.0 + 0.001 * i << " m, 3 cm from it";
  }
  const std::vector<double> after = crate_state(s);
  EXPECT_EQ(std::memcmp(before.data(), after.data(), before.size() * sizeof(double)), 0);
}

TEST(Islands, TouchWakesARestingObject) {
  Scene s;
  place(s, -1.0, 0.0);
  run(s.p, 2500);
  ASSERT_TRUE(asleep(s)) << "the crate did not fall asleep at rest within 2.5 s";
  // the probe's face 1 mm into the crate's
  place(s, -0.25 - 0.1 + 0.001, 0.0);
  s.p.step(kDt);
  EXPECT_FALSE(asleep(s));
}
