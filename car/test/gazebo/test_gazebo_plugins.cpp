// Users' own Gazebo plug-ins (docs/PLUGINS.md): model plug-ins written against car's Gazebo 11 headers in the style
// of Gazebo's tutorials (test/gazebo/plugins/), built as .so files by the test build, found on GAZEBO_PLUGIN_PATH
// and loaded through the world's plug-in table; Gazebo's call order and its error messages. Values by hand, in zero
// gravity (only what the plug-in does acts); dt = 0.001 s.
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <string>

#include "car_sim/shared_plugin.hpp"
#include "car_sim/world.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

const std::string kDir = CAR_GAZEBO_TEST_PLUGINS;

// The search path set to the test plug-ins' folder alone for one test, and put back after.
class GazeboPlugins : public ::testing::Test {
 protected:
  ScopedEnv env_{{"GAZEBO_PLUGIN_PATH", kDir}, {"CMAKE_PREFIX_PATH", "/nowhere/a"}, {"LD_LIBRARY_PATH", "/nowhere/b"}};
};

// A 2 kg box (Izz 0.5) with (wheel true) a 1 kg wheel (Izz 0.5) on a continuous joint about z through both coms,
// and the given plug-in block.
std::string box(const std::string& plugin, bool wheel = true) {
  const std::string wheel_xml = R"(
  <link name="wheel">
    <inertial><mass value="1"/><inertia ixx="0.5" iyy="0.5" izz="0.5" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><cylinder radius="0.1" length="0.05"/></geometry></collision>
  </link>
  <joint name="axle" type="continuous"><parent link="body"/><child link="wheel"/><origin xyz="0 0 1"/>
    <axis xyz="0 0 1"/><limit effort="100" velocity="100"/></joint>)";
  return R"(<?xml version="1.0"?>
<robot name="box">
  <link name="body">
    <inertial><mass value="2"/><inertia ixx="0.5" iyy="0.5" izz="0.5" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  </link>)" + (wheel ? wheel_xml : std::string()) + R"(
  <gazebo>)" + plugin + R"(</gazebo>
</robot>)";
}

// The box at (0, 0, 5) in an empty world without gravity.
std::unique_ptr<World> world_with(const std::string& plugin, bool wheel = true) {
  auto w = std::make_unique<World>(empty_world());
  w->set_gravity(Eigen::Vector3d::Zero());
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(0, 0, 5);
  w->spawn(load_urdf_string(box(plugin, wheel), "box"), "box", pose);
  return w;
}

// The diagnostics of a code on the box, as "message" lines.
std::vector<std::string> diags(const World& w, const std::string& code) {
  std::vector<std::string> out;
  for (const auto& d : w.robot("box").config.diagnostics)
    if (d.code == code) out.push_back(d.message);
  return out;
}

// The forces plug-in's log (test/gazebo/plugins/forces.cc), read from the loaded library.
std::string forces_log() {
  void* h = dlopen((kDir + "/libforces.so").c_str(), RTLD_LAZY | RTLD_NOLOAD);
  if (!h) return "<not loaded>";
  auto log = reinterpret_cast<const char* (*)()>(dlsym(h, "car_test_forces_log"));
  auto clear = reinterpret_cast<void (*)()>(dlsym(h, "car_test_forces_clear"));
  std::string s = log();
  clear();
  dlclose(h);
  return s;
}

}  // namespace

TEST_F(GazeboPlugins, AFileOnTheSearchPathIsAPluginFromALibrary) {
  EXPECT_EQ(plugin_kind("libmodel_push.so"), "shared_library");
  EXPECT_EQ(plugin_kind("libgazebo_ros_diff_drive.so"), "diff_drive");  // car's own kind keeps the file
  EXPECT_EQ(plugin_kind("libnot_there.so"), "");
}

TEST_F(GazeboPlugins, HelloWorldPrintsOnLoad) {
  testing::internal::CaptureStdout();
  auto w = world_with(R"(<plugin name="hello" filename="libhello_world.so"/>)");
  EXPECT_EQ(testing::internal::GetCapturedStdout(), "Hello World! I am model 'box'\n");
  EXPECT_TRUE(diags(*w, "plugin-not-loaded").empty());
}

// SetLinearVel(0.3, 0, 0) at every WorldUpdateBegin: 0.3 m in 1 s.
TEST_F(GazeboPlugins, ModelPushMovesTheModelAtItsVelocity) {
  auto w = world_with(R"(<plugin name="push" filename="libmodel_push.so"/>)");
  w->step(1000);
  const ModelState s = w->model_state("box");
  EXPECT_NEAR(s.linear.x(), 0.3, 1e-12);
  EXPECT_NEAR(s.pose.translation().x(), 0.3, 1e-9);
}

// <velocity>0.7</velocity>: 0.7 m in 1 s; without it, the plug-in's default 0.
TEST_F(GazeboPlugins, ParametersReadTheirElementFromTheSdf) {
  auto w = world_with(R"(<plugin name="p" filename="libparameters.so"><velocity>0.7</velocity></plugin>)");
  w->step(1000);
  EXPECT_NEAR(w->model_state("box").pose.translation().x(), 0.7, 1e-9);
  auto still = world_with(R"(<plugin name="p" filename="libparameters.so"/>)");
  still->step(10);
  EXPECT_EQ(still->model_state("box").pose.translation().x(), 0.0);
}

// The joint controller's P controller (p 0.1) towards 10 rad/s, updated after WorldUpdateBegin each step with the
// joint speed v_k the step starts from: effort 0.1 (10 - v_k); box and wheel (Izz 0.5 each) turn apart, so the joint
// speeds up by 4 x effort x dt: v_k+1 = v_k + 0.0004 (10 - v_k), v_n = 10 (1 - 0.9996^n).
TEST_F(GazeboPlugins, JointControllerTurnsTheJointTowardsItsTarget) {
  auto w = world_with(R"(<plugin name="spin" filename="libvelocity_pid.so"><velocity>10</velocity></plugin>)");
  w->step(1000);
  EXPECT_NEAR(w->joint_velocity("box", "axle"), 10.0 * (1.0 - std::pow(0.9996, 1000)), 1e-9);  // 3.297 rad/s
  w->step(19000);
  EXPECT_NEAR(w->joint_velocity("box", "axle"), 10.0 * (1.0 - std::pow(0.9996, 20000)), 1e-9);  // 9.997 rad/s
}

// Link::AddForce (1 N, world x) every WorldUpdateBegin on the 2 kg box alone: 0.5 m/s after 1 s, and
// x = sum of v_k dt, v_k = 0.5 k dt, k = 1..1000: 0.5 dt^2 1000 1001 / 2 = 0.25025 m.
TEST_F(GazeboPlugins, LinkForceEachStepAccelerates) {
  forces_log();
  auto w = world_with(R"(<plugin name="f" filename="libforces.so"/>)", false);
  w->step(1000);
  EXPECT_NEAR(w->model_state("box").linear.x(), 0.5, 1e-9);
  EXPECT_NEAR(w->model_state("box").pose.translation().x(), 0.25025, 1e-9);
}

// Gazebo's order: Load, Init at the spawn (time 0); each step WorldUpdateBegin and BeforePhysicsUpdate with the
// step's end as sim time, then WorldUpdateEnd at the time reached; Reset on a reset; deleted with its model.
TEST_F(GazeboPlugins, CallsComeInGazebosOrder) {
  forces_log();
  auto w = world_with(R"(<plugin name="f" filename="libforces.so"/>)");
  EXPECT_EQ(forces_log(), "load@0 init@0");
  w->step(2);
  EXPECT_EQ(forces_log(), "begin@0.001/0.001 before@0.001/0.001 end@0.001 begin@0.002/0.002 before@0.002/0.002 end@0.002");
  w->reset_poses();
  EXPECT_EQ(forces_log(), "reset@0.002");
  w->reset();
  EXPECT_EQ(forces_log(), "reset@0");
  w->remove("box");
  EXPECT_EQ(forces_log(), "unload@0");
  w->step(1);
  EXPECT_EQ(forces_log(), "");
}

// The model loads without a plug-in whose file is nowhere, with Gazebo's message and the folders searched.
TEST_F(GazeboPlugins, AMissingFileIsAWarningWithThePathsSearched) {
  auto w = world_with(R"(<plugin name="gone" filename="libnot_there.so"/>)");
  EXPECT_EQ(diags(*w, "plugin-unknown"),
            std::vector<std::string>{"Failed to load plugin libnot_there.so: not one car simulates, and no such file "
                                     "in GAZEBO_PLUGIN_PATH, the ROS library folders or LD_LIBRARY_PATH (searched: " +
                                     kDir + ":/nowhere/a/lib:/nowhere/b); ignored"});
  EXPECT_TRUE(w->plugins().empty());
  w->step(1);
}

// A Load that throws: an error naming plug-in and model; the model stays and the world goes on.
TEST_F(GazeboPlugins, AnExceptionInLoadIsAnErrorAndTheWorldGoesOn) {
  auto w = world_with(R"(<plugin name="bad" filename="libthrows_in_load.so"/>)");
  EXPECT_EQ(diags(*w, "plugin-not-loaded"),
            std::vector<std::string>{"plug-in 'bad' of model 'box' failed to load: Load threw: no <link> given; the "
                                     "model goes on without it"});
  w->step(10);
  EXPECT_EQ(w->tick(), 10u);
}

// A library without RegisterPlugin: Gazebo's "Failed to resolve", no crash.
TEST_F(GazeboPlugins, ALibraryWithoutRegisterPluginIsAnError) {
  auto w = world_with(R"(<plugin name="nosym" filename="libno_register.so"/>)");
  const std::string path = kDir + "/libno_register.so";
  EXPECT_EQ(diags(*w, "plugin-not-loaded"),
            std::vector<std::string>{"Failed to resolve RegisterPlugin: " + path +
                                     ": undefined symbol: RegisterPlugin (plug-in 'nosym', " + path +
                                     "); model 'box' goes on without it"});
  w->step(1);
}

// Two boxes, each with its own plug-in instance: each pushes its own model only.
TEST_F(GazeboPlugins, EachModelHasItsOwnInstance) {
  auto w = world_with(R"(<plugin name="push" filename="libmodel_push.so"/>)");
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(0, 3, 5);
  w->spawn(load_urdf_string(box(""), "other"), "other", pose);
  w->step(100);
  EXPECT_NEAR(w->model_state("box").pose.translation().x(), 0.03, 1e-9);
  EXPECT_EQ(w->model_state("other").pose.translation().x(), 0.0);
}

// A model plug-in in an SDF world's model: the model is one of the world's robots from the start, and the plug-in
// pushes it as in a URDF (0.3 m in 1 s).
TEST_F(GazeboPlugins, APluginInAWorldFilesModelRuns) {
  World w(load_world_string(R"(<?xml version="1.0"?>
<sdf version="1.6"><world name="lab"><gravity>0 0 0</gravity>
  <model name="crate"><pose>0 0 5 0 0 0</pose>
    <link name="body">
      <inertial><mass>2</mass><inertia><ixx>0.5</ixx><iyy>0.5</iyy><izz>0.5</izz></inertia></inertial>
      <collision name="c"><geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision>
    </link>
    <plugin name="push" filename="libmodel_push.so"/>
  </model>
</world></sdf>)"));
  w.step(1000);
  EXPECT_NEAR(w.model_state("crate").pose.translation().x(), 0.3, 1e-9);
}

// A model deleted while another model's plug-in goes on: its joint controller is dropped, the world steps on.
TEST_F(GazeboPlugins, DeletingAControlledModelLeavesTheOthersRunning) {
  auto w = world_with(R"(<plugin name="spin" filename="libvelocity_pid.so"><velocity>10</velocity></plugin>)");
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(0, 3, 5);
  w->spawn(load_urdf_string(box(R"(<plugin name="push" filename="libmodel_push.so"/>)"), "other"), "other", pose);
  w->step(10);
  w->remove("box");
  w->step(90);
  EXPECT_NEAR(w->model_state("other").pose.translation().x(), 0.03, 1e-9);
}

// A folder on two of the paths is searched once, where it first comes.
TEST_F(GazeboPlugins, AFolderOnTwoPathsIsSearchedOnce) {
  env_.set("LD_LIBRARY_PATH", "/nowhere/a/lib:" + kDir + ":/nowhere/b");
  EXPECT_EQ(shared_plugin_search_path(), (std::vector<std::string>{kDir, "/nowhere/a/lib", "/nowhere/b"}));
}

// A file name car simulates natively keeps car's kind; listed in CAR_UPSTREAM_PLUGINS, the library of that name on the
// search path loads instead (the test build's model push, built as libgazebo_ros_planar_move.so, pushes at 0.3 m/s).
TEST_F(GazeboPlugins, TheSwitchLoadsTheLibraryForANativeName) {
  EXPECT_EQ(plugin_kind("libgazebo_ros_planar_move.so"), "planar_move");
  std::unique_ptr<World> w;
  {
    // the switch is read at load: the world keeps the library after the variable is gone
    ScopedEnv upstream{{"CAR_UPSTREAM_PLUGINS", "libfoo.so,libgazebo_ros_planar_move.so"}};
    EXPECT_EQ(plugin_kind("libgazebo_ros_planar_move.so"), "shared_library");
    EXPECT_EQ(plugin_kind("libgazebo_ros_diff_drive.so"), "diff_drive");  // not listed
    w = world_with(R"(<plugin name="move" filename="libgazebo_ros_planar_move.so"/>)");
  }
  w->step(1000);
  EXPECT_NEAR(w->model_state("box").pose.translation().x(), 0.3, 1e-9);
}
