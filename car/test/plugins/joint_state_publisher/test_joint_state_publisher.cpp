// libgazebo_ros_joint_state_publisher.so on the seed car (wheel joints left2link, right2link; casters front2link,
// back2link).
#include <gtest/gtest.h>

#include "joint_state_publisher/joint_state_publisher.hpp"
#include "seed_car.hpp"

using namespace car_sim;

namespace {

PluginSpec jsp(const std::string& joints, const std::string& rate) {
  PluginSpec p;
  p.name = "jsp";
  p.filename = "libgazebo_ros_joint_state_publisher.so";
  p.params = {{"jointName", joints}};
  if (!rate.empty()) p.params.emplace_back("updateRate", rate);
  return p;
}

// Only the outputs of the plug-in named "jsp" (the seed car's diff drive publishes odometry too).
std::vector<const JointStatesOut*> jsp_outputs(const OutputQueue& q) {
  std::vector<const JointStatesOut*> out;
  for (const auto& o : q)
    if (o->plugin == "jsp") out.push_back(dynamic_cast<const JointStatesOut*>(o.get()));
  return out;
}

}  // namespace

TEST(JointStatePublisher, SplitsAtCommasAndDropsSpaces) {
  const auto n = split_joint_names(" left2link , right2link");
  ASSERT_EQ(n.size(), 2u);
  EXPECT_EQ(n[0], "left2link");
  EXPECT_EQ(n[1], "right2link");
}

TEST(JointStatePublisher, ListsExactlyItsJointsAtItsRate) {
  // updateRate 25 Hz at 1 ms steps: one message every 40 ticks, so 25 in 1 s, at ticks 40, 80, ..., 1000;
  // each lists the two named joints in the written order, not the casters
  auto w = test_support::world_with_car(false);
  w->attach_plugin("mycar", jsp("right2link,left2link", "25"));
  w->set_plugin_active("mycar", "jsp", true);  // computed while someone listens
  w->take_outputs();
  w->step(1000);
  const OutputQueue q = w->take_outputs();
  const auto out = jsp_outputs(q);
  ASSERT_EQ(out.size(), 25u);
  EXPECT_EQ(out.front()->tick, 40u);
  EXPECT_EQ(out.back()->tick, 1000u);
  ASSERT_EQ(out.back()->joints.size(), 2u);
  EXPECT_EQ(out.back()->joints[0].name, "right2link");
  EXPECT_EQ(out.back()->joints[1].name, "left2link");
}

TEST(JointStatePublisher, ReportsTheJointState) {
  // the message equals the world's joint state at the same tick; the diff drive has the wheel up to
  // 0.5 m/s / 0.0325 m = 15.4 rad/s after 0.25 s of its ramp (1.8 m/s^2 over 0.011 s per 0.01 s update)
  auto w = test_support::world_with_car(false);
  w->attach_plugin("mycar", jsp("left2link", "0"));
  w->set_plugin_active("mycar", "jsp", true);
  w->set_cmd_vel("mycar", 0.5, 0.0);
  w->step(500);
  const OutputQueue q = w->take_outputs();
  const auto out = jsp_outputs(q);
  ASSERT_EQ(out.size(), 500u);  // 0 = every step
  double pos = 0, vel = 0;
  for (const auto& j : w->joint_states("mycar"))
    if (j.name == "left2link") pos = j.position, vel = j.velocity;
  EXPECT_DOUBLE_EQ(out.back()->joints[0].position, pos);
  EXPECT_DOUBLE_EQ(out.back()->joints[0].velocity, vel);
  EXPECT_NEAR(vel, 15.4, 1.0);
}

TEST(JointStatePublisher, UnknownJointIsAnError) {
  auto w = test_support::world_with_car(false);
  try {
    w->attach_plugin("mycar", jsp("left2link, nope", ""));
    FAIL() << "no error";
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("gazebo/plugin[jsp]/jointName: joint 'nope' not found in the model"),
              std::string::npos)
        << e.what();
  }
}

// At 30 Hz the publisher follows UpdateChild's rule (test_update_clock.cpp): ticks 33, 66, 99, 133, 166, 199.
TEST(JointStatePublisher, ThirtyHertzUpdatesByUpdateChildsClock) {
  auto w = test_support::world_with_car(false);
  w->attach_plugin("mycar", jsp("left2link", "30"));
  w->set_plugin_active("mycar", "jsp", true);
  w->take_outputs();
  w->step(200);
  const OutputQueue q = w->take_outputs();
  std::vector<uint64_t> ticks;
  for (const JointStatesOut* o : jsp_outputs(q)) ticks.push_back(o->tick);
  EXPECT_EQ(ticks, (std::vector<uint64_t>{33, 66, 99, 133, 166, 199}));
}

// A negative updateRate gives upstream's update_period_ 0: every step, warned (warn_negative_rate), not refused.
TEST(JointStatePublisher, NegativeUpdateRateIsEveryStepAndWarned) {
  auto w = test_support::world_with_car(false);
  w->attach_plugin("mycar", jsp("left2link", "-5"));
  w->set_plugin_active("mycar", "jsp", true);
  w->take_outputs();
  w->step(10);
  const OutputQueue q = w->take_outputs();
  EXPECT_EQ(jsp_outputs(q).size(), 10u);
  std::vector<std::string> messages;
  for (const Diagnostic& d : w->robot("mycar").config.diagnostics)
    if (d.element == "gazebo/plugin[jsp]/updateRate") messages.push_back(d.message);
  EXPECT_EQ(messages, std::vector<std::string>{"<updateRate> -5 is not > 0: the plug-in updates every step, as upstream"});
}

// Without <jointName> upstream's ROS_ASSERT checks a string literal and passes: empty joint states at its rate.
TEST(JointStatePublisher, WithoutJointNameItPublishesEmptyJointStates) {
  auto w = test_support::world_with_car(false);
  PluginSpec p = jsp("", "10");
  p.params.erase(p.params.begin());  // no <jointName> at all
  w->attach_plugin("mycar", p);
  w->set_plugin_active("mycar", "jsp", true);
  w->take_outputs();
  w->step(200);
  const OutputQueue q = w->take_outputs();
  const auto out = jsp_outputs(q);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_TRUE(out.back()->joints.empty());
}
