// libgazebo_ros_f3d.so: reports the wrench the force plug-in adds, world frame.
#include <gtest/gtest.h>

#include "f3d/f3d.hpp"
#include "force/force.hpp"
#include "../force/wrench_box.hpp"

using namespace car_sim;

TEST(F3d, ReportsTheAppliedWrenchEveryStepWhileListened) {
  // force (3, -4, 0) N and torque (0, 0, 0.2) N m held by the force plug-in: every f3d message reads exactly
  // those (force at the centre of mass adds no moment); 10 steps listened -> 10 messages
  auto w = test_support::wrench_box();
  Wrench f;
  f.force = Eigen::Vector3d(3, -4, 0);
  f.torque = Eigen::Vector3d(0, 0, 0.2);
  dynamic_cast<WrenchCommand*>(w->plugin("box", "push"))->set_wrench(f);
  w->step(5);  // not listened: nothing
  EXPECT_TRUE(w->take_outputs().empty());
  w->set_plugin_active("box", "felt", true);
  w->step(10);
  const OutputQueue q = w->take_outputs();
  ASSERT_EQ(q.size(), 10u);
  const auto& o = dynamic_cast<const WrenchOut&>(*q.back());
  EXPECT_TRUE(o.wrench.force.isApprox(Eigen::Vector3d(3, -4, 0), 1e-9));
  EXPECT_NEAR((o.wrench.torque - Eigen::Vector3d(0, 0, 0.2)).norm(), 0.0, 1e-9);
}

TEST(F3d, ZeroWhenNothingPushes) {
  // gravity and the ground's contact are not external wrenches of plug-ins: f3d reads 0
  auto w = test_support::wrench_box();
  w->set_plugin_active("box", "felt", true);
  w->step(3);
  const OutputQueue q = w->take_outputs();
  ASSERT_EQ(q.size(), 3u);
  EXPECT_TRUE(dynamic_cast<const WrenchOut&>(*q.back()).wrench.force.isZero());
}
