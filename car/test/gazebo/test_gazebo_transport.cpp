// car's transport within a world (docs/PLUGINS.md "Transport"): msgs::Vector3d published and subscribed by the test
// plug-in test/gazebo/plugins/transport_probe.cc, delivered at the end of the step it was published in, and
// msgs::ImageStamped by test/gazebo/plugins/camera_transport.cc. dt = 0.001 s.
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <string>

#include "car_sim/world.hpp"

using namespace car_sim;

namespace {

const std::string kDir = CAR_GAZEBO_TEST_PLUGINS;

// The box with the plug-in lib<plugin>.so in the given mode.
std::unique_ptr<World> box_with(const std::string& mode, const std::string& plugin = "transport_probe") {
  const std::string urdf = R"(<?xml version="1.0"?>
<robot name="box"><link name="body">
  <inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
  <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <gazebo><plugin name="t" filename=")" + kDir + "/lib" + plugin + R"(.so"><mode>)" + mode +
                           R"(</mode></plugin></gazebo>
</robot>)";
  auto w = std::make_unique<World>(empty_world());
  w->set_gravity(Eigen::Vector3d::Zero());
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(0, 0, 1);
  w->spawn(load_urdf_string(urdf, "box"), "box", pose);
  return w;
}

// What the plug-in lib<plugin>.so logged since the last call (its function car_test_<log>_log).
std::string transport_log(const std::string& plugin = "transport_probe", const std::string& log_name = "transport") {
  void* h = dlopen((kDir + "/lib" + plugin + ".so").c_str(), RTLD_LAZY | RTLD_NOLOAD);
  if (!h) return "<not loaded>";
  auto log = reinterpret_cast<const char* (*)()>(dlsym(h, ("car_test_" + log_name + "_log").c_str()));
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

// Gazebo 11's Image::ConvertPixelFormat: the older names (L8, L_UINT16, R8G8B8, FLOAT32) and the enum's own
// (BGR_INT8 8, BAYER_GRBG8 18), anything else UNKNOWN_PIXEL_FORMAT 0; msgs::Convert keeps sec and nsec.
TEST(GazeboImage, ConvertPixelFormatTakesGazebosNamesAndOldOnes) {
  transport_log("camera_transport", "camera_transport");
  auto w = box_with("image", "camera_transport");
  EXPECT_EQ(transport_log("camera_transport", "camera_transport"),
            "L8=1 L_UINT16=2 R8G8B8=3 BGR_INT8=8 FLOAT32=13 BAYER_GRBG8=18 RGB=0 time=3.250 ");
}

// Published in the first WorldUpdateBegin (sim time 0.001 s: sec 0, nsec 1000000): it arrives whole at the end of
// step 1, R8G8B8 as RGB_INT8 (3).
TEST(GazeboTransport, AnImageStampedArrivesWithItsStampAndPixels) {
  transport_log("camera_transport", "camera_transport");
  auto w = box_with("image", "camera_transport");
  transport_log("camera_transport", "camera_transport");
  w->step(2);
  EXPECT_EQ(transport_log("camera_transport", "camera_transport"),
            "image=2x1 format=3 step=6 stamp=0.1000000 data=abcdef at=1");
}
