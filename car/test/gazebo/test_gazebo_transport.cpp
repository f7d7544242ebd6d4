// car's transport within a world (docs/PLUGINS.md "Transport"): msgs::Vector3d published and subscribed by the test
// plug-in test/gazebo/plugins/transport_probe.cc, delivered at the end of the step it was published in. dt = 0.001 s.
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <string>

#include "car_sim/world.hpp"

using namespace car_sim;

namespace {

const std::string kDir = CAR_GAZEBO_TEST_PLUGINS;

std::unique_ptr<World> box_with(const std::string& mode) {
  const std::string urdf = R"(<?xml version="1.0"?>
<robot name="box"><link name="body">
  <inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
  <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <gazebo><plugin name="t" filename=")" + kDir + R"(/libtransport_probe.so"><mode>)" + mode +
                           R"(</mode></plugin></gazebo>
</robot>)";
  auto w = std::make_unique<World>(empty_world());
  w->set_gravity(Eigen::Vector3d::Zero());
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(0, 0, 1);
  w->spawn(load_urdf_string(urdf, "box"), "box", pose);
  return w;
}

std::string transport_log() {
  void* h = dlopen((kDir + "/libtransport_probe.so").c_str(), RTLD_LAZY | RTLD_NOLOAD);
  if (!h) return "<not loaded>";
  auto log = reinterpret_cast<const char* (*)()>(dlsym(h, "car_test_transport_log"));
  std::string s = log();
  dlclose(h);
  return s;
}

}  // namespace

// Published in WorldUpdateBegin of steps 1 and 2: not inside Publish ("sent" first), each at the end of its step,
// when Iterations is 1, then 2.
TEST(GazeboTransport, AMessageArrivesAtTheEndOfTheStepItWasPublishedIn) {
  transport_log();
  auto w = box_with("deliver");
  w->step(3);
  EXPECT_EQ(transport_log(), "sent N1@1 sent N2@2 ");
}

// x = 5 published in Load with no subscriber: only the latching subscriber made after it gets it, at the end of the
// first step.
TEST(GazeboTransport, OnlyALatchingSubscriberGetsTheLastMessage) {
  transport_log();
  auto w = box_with("latch");
  w->step(2);
  EXPECT_EQ(transport_log(), "L5@1 ");
}

// A SubscriberPtr let go unsubscribes: nothing is delivered.
TEST(GazeboTransport, ALetGoSubscriberGetsNothing) {
  transport_log();
  auto w = box_with("unsubscribe");
  w->step(2);
  EXPECT_EQ(transport_log(), "sent ");
}
