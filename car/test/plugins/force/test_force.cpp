// libgazebo_ros_force.so: a held wrench on a frictionless box, motion worked out by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "force/force.hpp"
#include "wrench_box.hpp"

using namespace car_sim;

TEST(Force, HeldForceAcceleratesTheBox) {
  // F = 10 N along x on m = 10 kg: a = 1 m/s^2. Bullet's semi-implicit Euler at dt = 1 ms gives after N = 1000
  // steps x = a dt^2 N (N + 1) / 2 = 0.5005 m and v = a N dt = 1 m/s.
  auto w = test_support::wrench_box();
  Wrench f;
  f.force = Eigen::Vector3d(10, 0, 0);
  dynamic_cast<WrenchCommand*>(w->plugin("box", "push"))->set_wrench(f);
  w->step(1000);
  const ModelState s = w->model_state("box");
  EXPECT_NEAR(s.pose.translation().x(), 0.5005, 1e-4);
  // the iterative contact solver leaves the sliding box a small residual
  EXPECT_NEAR(s.linear.x(), 1.0, 1e-3);
  // through the centre of mass: no turning about z
  EXPECT_NEAR(s.angular.z(), 0.0, 1e-6);
  std::printf("force: v %.9f m/s, angular %.3g %.3g %.3g rad/s\n", s.linear.x(), s.angular.x(), s.angular.y(), s.angular.z());
}

TEST(Force, HeldForceThroughTheCentreDoesNotRockTheBox) {
  // The push acts through the centre of mass and the box slides without friction, so nothing turns it: its four
  // bottom corners carry it every step (docs/COMPAT-physics.md "Contact points") and it stays level. A step on
  // fewer corners (stale points dropped as it slides) tips it about y; the reported velocity is the link origin's,
  // 0.1 m under the centre of mass, so a rocking rate w adds 0.1 w to x. The first step's sequential solve of the
  // four new corners leaves a turn of 1.3e-5 rad/s that decays by 0.8 per step (below 1e-12 rad/s after 0.1 s):
  // measured from step 100 on, while the box slides.
  auto w = test_support::wrench_box();
  Wrench f;
  f.force = Eigen::Vector3d(10, 0, 0);
  dynamic_cast<WrenchCommand*>(w->plugin("box", "push"))->set_wrench(f);
  double worst = 0;  // [rad/s]
  w->step(100);
  for (int i = 100; i < 1000; ++i) {
    w->step(1);
    worst = std::max(worst, w->model_state("box").angular.norm());
  }
  EXPECT_LT(worst, 1e-6) << "fastest turn of the box";
}

TEST(Force, HeldTorqueSpinsTheBox) {
  // tau = 0.1 N m about z on izz = 0.1 kg m^2: alpha = 1 rad/s^2, so after 1000 steps yaw = 0.5005 rad
  auto w = test_support::wrench_box();
  Wrench t;
  t.torque = Eigen::Vector3d(0, 0, 0.1);
  dynamic_cast<WrenchCommand*>(w->plugin("box", "push"))->set_wrench(t);
  w->step(1000);
  const Eigen::Matrix3d R = w->model_state("box").pose.linear();
  EXPECT_NEAR(std::atan2(R(1, 0), R(0, 0)), 0.5005, 1e-4);
  EXPECT_NEAR(w->model_state("box").pose.translation().head<2>().norm(), 0.0, 1e-6);
}

TEST(Force, MissingBodyIsAnError) {
  PluginSpec p;
  p.name = "bad";
  p.filename = "libgazebo_ros_force.so";
  p.params = {{"bodyName", "nope"}, {"topicName", "x"}};
  auto w = test_support::wrench_box();
  try {
    w->attach_plugin("box", p);
    FAIL() << "no error";
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("gazebo/plugin[bad]/bodyName: gazebo_ros_force plugin error: link named: nope does not exist"),
              std::string::npos)
        << e.what();
  }
}
