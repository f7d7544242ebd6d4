// Gazebo 11's free functions and static calls that plug-ins use (docs/PLUGINS.md): physics::get_world and has_world,
// common::Time's wall clock and sleeps, through the test plug-in test/gazebo/plugins/free_functions.cc, which logs
// what it saw in Load.
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <string>

#include "car_sim/world.hpp"

using namespace car_sim;

namespace {

const std::string kDir = CAR_GAZEBO_TEST_PLUGINS;

// The plug-in's log from a box spawned with it in the empty world (world "default"); stderr in *err.
std::string spawn_and_log(std::string* err = nullptr) {
  const std::string urdf = R"(<?xml version="1.0"?>
<robot name="box"><link name="body">
  <inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <gazebo><plugin name="f" filename=")" + kDir + R"(/libfree_functions.so"/></gazebo>
</robot>)";
  World w(empty_world());
  testing::internal::CaptureStderr();
  w.spawn(load_urdf_string(urdf, "box"), "box", Eigen::Isometry3d::Identity());
  const std::string e = testing::internal::GetCapturedStderr();
  if (err) *err = e;
  void* h = dlopen((kDir + "/libfree_functions.so").c_str(), RTLD_LAZY | RTLD_NOLOAD);
  if (!h) return "<not loaded>";
  auto log = reinterpret_cast<const char* (*)()>(dlsym(h, "car_test_free_functions_log"));
  std::string s = log();
  dlclose(h);
  return s;
}

}  // namespace

// get_world() and get_world("default") give the plug-in's world; a name no world has: has_world false, and
// get_world throws upstream's text after its gzerr line.
TEST(GazeboPhysicsIface, GetWorldFindsThePluginsWorldAndThrowsForAnotherName) {
  std::string err;
  const std::string log = spawn_and_log(&err);
  EXPECT_NE(log.find("world=1 has=1 missing=0 threw=Unable to find world by name in physics::get_world(world_name)"),
            std::string::npos)
      << log;
  EXPECT_NE(err.find("Unable to find world by name in physics::get_world[nowhere]"), std::string::npos) << err;
}

// GetWallTime lies between two CLOCK_REALTIME readings around it; the ISO string is 26 characters
// ("2026-11-29T11:55:00.123456").
TEST(GazeboTime, GetWallTimeIsTheRealTimeClock) {
  const std::string log = spawn_and_log();
  EXPECT_NE(log.find("wall=1 iso=26"), std::string::npos) << log;
}

// MSleep(2) sleeps at least 2 ms and returns zero; Sleep of a negative time returns zero at once.
TEST(GazeboTime, MSleepSleepsAndANegativeSleepDoesNot) {
  const std::string log = spawn_and_log();
  EXPECT_NE(log.find("msleep=1 skip=1"), std::string::npos) << log;
}
