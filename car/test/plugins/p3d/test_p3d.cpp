// libgazebo_ros_p3d.so: ground truth equals the world's model state; offsets and noise as upstream.
#include <gtest/gtest.h>

#include <cmath>

#include "p3d/p3d.hpp"
#include "seed_car.hpp"

using namespace car_sim;

namespace {

PluginSpec p3d(const ParamList& extra) {
  PluginSpec p;
  p.name = "truth";
  p.filename = "libgazebo_ros_p3d.so";
  p.params = {{"bodyName", "base_footprint"}, {"topicName", "truth"}};
  for (const auto& kv : extra) p.params.push_back(kv);
  return p;
}

std::vector<const P3dOut*> p3d_outputs(const OutputQueue& q) {
  std::vector<const P3dOut*> out;
  for (const auto& o : q)
    if (o->plugin == "truth") out.push_back(dynamic_cast<const P3dOut*>(o.get()));
  return out;
}

}  // namespace

TEST(P3d, EqualsTheModelStateAtTheSameTick) {
  // the seed car driving a circle (1 m/s, 1 rad/s): the root link base_footprint in the world frame is exactly
  // what get_model_state reports for the model
  auto w = test_support::world_with_car(false, 0.5, -0.5, 0.3);
  w->attach_plugin("mycar", p3d({}));
  w->set_plugin_active("mycar", "truth", true);
  w->set_cmd_vel("mycar", 1.0, 1.0);
  w->step(1500);
  const OutputQueue q = w->take_outputs();
  const auto out = p3d_outputs(q);
  ASSERT_EQ(out.size(), 1500u);  // updateRate 0: every step
  const ModelState s = w->model_state("mycar");
  const P3dOut& o = *out.back();
  EXPECT_EQ(o.tick, 1500u);
  EXPECT_TRUE(o.pose.isApprox(s.pose, 1e-12));
  EXPECT_TRUE(o.linear.isApprox(s.linear, 1e-12));
  EXPECT_TRUE(o.angular.isApprox(s.angular, 1e-12));
  EXPECT_GT(o.linear.norm(), 0.9);  // really moving: about 1 m/s
}

TEST(P3d, OffsetsShiftThePositionAndTurnTheOrientation) {
  // at rest at (0, 0, yaw 0): xyzOffset 1 2 3 adds to the position; rpyOffset 0 0 pi/2 turns the orientation by
  // 90 deg about z, so the reported x axis is the world's y axis
  auto w = test_support::world_with_car(false);
  w->attach_plugin("mycar", p3d({{"xyzOffset", "1 2 3"}, {"rpyOffset", "0 0 1.5707963267948966"}, {"updateRate", "10"}}));
  w->set_plugin_active("mycar", "truth", true);
  w->step(100);
  const OutputQueue q = w->take_outputs();
  const auto out = p3d_outputs(q);
  ASSERT_EQ(out.size(), 1u);  // 10 Hz over 0.1 s
  const ModelState s = w->model_state("mycar");
  EXPECT_TRUE(out[0]->pose.translation().isApprox(s.pose.translation() + Eigen::Vector3d(1, 2, 3), 1e-12));
  const Eigen::Vector3d x_axis = out[0]->pose.linear().col(0);
  EXPECT_NEAR(x_axis.y(), 1.0, 1e-3);
}

TEST(P3d, GaussianNoiseOnTheTwistHasItsStddev) {
  // gaussianNoise 0.1 on each twist component of a car at rest (true twist ~1e-6): 2000 samples of linear.x have
  // a standard deviation within 5 % of 0.1 (the sampling error of a stddev is 0.1 / sqrt(2 * 2000) = 1.6 %)
  auto w = test_support::world_with_car(false);
  w->attach_plugin("mycar", p3d({{"gaussianNoise", "0.1"}}));
  w->set_plugin_active("mycar", "truth", true);
  w->step(2000);
  const OutputQueue q = w->take_outputs();
  const auto out = p3d_outputs(q);
  double sum = 0, sum2 = 0;
  for (const P3dOut* o : out) sum += o->linear.x(), sum2 += o->linear.x() * o->linear.x();
  const double n = static_cast<double>(out.size());
  const double sd = std::sqrt(sum2 / n - (sum / n) * (sum / n));
  EXPECT_NEAR(sd, 0.1, 0.005);
  // the pose has no noise
  EXPECT_TRUE(out.back()->pose.translation().isApprox(w->model_state("mycar").pose.translation(), 1e-12));
}

// Attached alone (the node's attach), a plug-in that does not load is a LoadError with upstream's message.
TEST(P3d, UnknownFrameIsAnErrorWhenAttached) {
  auto w = test_support::world_with_car(false);
  try {
    w->attach_plugin("mycar", p3d({{"frameName", "nowhere"}}));
    FAIL() << "no error";
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "frameName: gazebo_ros_p3d plugin: frameName: nowhere does not exist, will not publish pose"),
              std::string::npos)
        << e.what();
  }
}

// In a model, upstream's Load logs and returns: the model loads without the plug-in, with a warning.
TEST(P3d, UnknownBodyLeavesThePluginOutOfTheModel) {
  std::string xml = test_support::car_xml(false);
  xml.insert(xml.rfind("</robot>"), "<gazebo><plugin name='truth' filename='libgazebo_ros_p3d.so'><bodyName>nope"
                                    "</bodyName><topicName>t</topicName></plugin></gazebo>");
  const ModelConfig c = resolve_plugins(load_urdf_string(xml, "car"));
  bool warned = false;
  for (const auto& d : c.diagnostics)
    warned = warned || (d.code == "plugin-not-loaded" && d.element == "gazebo/plugin[truth]/bodyName" &&
                        d.message == "gazebo_ros_p3d plugin error: bodyName: nope does not exist; the plug-in is "
                                     "not loaded");
  EXPECT_TRUE(warned);
  for (const auto& p : c.plugins) EXPECT_NE(p.name, "truth");
}

// Nobody subscribed until tick 105: car keeps the grid from the load (20, 40, ...) while the plug-in is off, so the
// first message is at 120. Upstream's p3d leaves last alone while nobody subscribes and would publish at the first
// call after the subscription; car keeps the grid so that a run's stamps do not depend on when a subscriber came
// (docs/COMPAT-plugins.md, p3d "When").
TEST(P3d, KeepsItsGridWhileNobodySubscribes) {
  auto w = test_support::world_with_car(false);
  w->attach_plugin("mycar", p3d({{"updateRate", "50"}}));
  w->step(105);
  w->set_plugin_active("mycar", "truth", true);
  w->step(95);
  const OutputQueue q = w->take_outputs();
  std::vector<uint64_t> ticks;
  for (const P3dOut* o : p3d_outputs(q)) ticks.push_back(o->tick);
  EXPECT_EQ(ticks, (std::vector<uint64_t>{120, 140, 160, 180, 200}));
}

// At 30 Hz upstream's rate control publishes every 34 ms (test_update_clock.cpp): 34, 68, 102, 136, 170.
TEST(P3d, ThirtyHertzIsEveryThirtyFourMilliseconds) {
  auto w = test_support::world_with_car(false);
  w->attach_plugin("mycar", p3d({{"updateRate", "30"}}));
  w->set_plugin_active("mycar", "truth", true);
  w->step(200);
  const OutputQueue q = w->take_outputs();
  std::vector<uint64_t> ticks;
  for (const P3dOut* o : p3d_outputs(q)) ticks.push_back(o->tick);
  EXPECT_EQ(ticks, (std::vector<uint64_t>{34, 68, 102, 136, 170}));
}
