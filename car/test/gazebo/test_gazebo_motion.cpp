// car's Gazebo 11 API beyond the tutorials (docs/PLUGINS.md): Joint::SetParam/GetParam (ODE's motor),
// Link::SetGravityMode, WorldForce/WorldTorque, RelativePose, Model::SetLinkWorldPose, World::SetPhysicsEnabled and
// gzthrow, through the test plug-in test/gazebo/plugins/motion.cc, and Link::SetEnabled through
// test/gazebo/plugins/link_enabled.cc, loaded by the world's plug-in table. Values by
// hand; dt = 0.001 s. The box (2 kg, Izz 0.5) and its wheel (1 kg, Izz 0.5) on the continuous joint axle turn apart
// about one axis: a joint torque tau changes the joint's rate at tau (1/0.5 + 1/0.5) = 4 tau [rad/s^2].
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "car_sim/world.hpp"

using namespace car_sim;

namespace {

const std::string kDir = CAR_GAZEBO_TEST_PLUGINS;

// The box with (wheel true) its wheel 1 m above on axle, the plug-in lib<plugin>.so (default: the motion plug-in) in
// the given mode (and extra elements), at (0, 0, 5) in an empty world with gravity g [m/s^2] along -z.
std::unique_ptr<World> box_with(const std::string& mode, const std::string& extra = "", bool wheel = true,
                                double g = 0.0, const std::string& axle = "continuous",
                                const std::string& plugin = "motion") {
  const std::string limits = axle == "revolute" ? R"(lower="-1" upper="1" )" : "";
  const std::string wheel_xml = R"(
  <link name="wheel">
    <inertial><mass value="1"/><inertia ixx="0.5" iyy="0.5" izz="0.5" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><cylinder radius="0.1" length="0.05"/></geometry></collision>
  </link>
  <joint name="axle" type=")" + axle + R"("><parent link="body"/><child link="wheel"/><origin xyz="0 0 1"/>
    <axis xyz="0 0 1"/><limit )" + limits + R"(effort="100" velocity="100"/></joint>)";
  const std::string urdf = R"(<?xml version="1.0"?>
<robot name="box">
  <link name="body">
    <inertial><mass value="2"/><inertia ixx="0.5" iyy="0.5" izz="0.5" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  </link>)" + (wheel ? wheel_xml : std::string()) +
                           R"(
  <gazebo><plugin name="m" filename=")" + kDir + "/lib" + plugin + R"(.so"><mode>)" + mode + "</mode>" + extra +
                           R"(</plugin></gazebo>
</robot>)";
  auto w = std::make_unique<World>(empty_world());
  w->set_gravity(Eigen::Vector3d(0, 0, -g));
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(0, 0, 5);
  w->spawn(load_urdf_string(urdf, "box"), "box", pose);
  return w;
}

// What the plug-in lib<plugin>.so logged since the last call (its function car_test_<plugin>_log).
std::string plugin_log(const std::string& plugin) {
  void* h = dlopen((kDir + "/lib" + plugin + ".so").c_str(), RTLD_LAZY | RTLD_NOLOAD);
  if (!h) return "<not loaded>";
  auto log = reinterpret_cast<const char* (*)()>(dlsym(h, ("car_test_" + plugin + "_log").c_str()));
  std::string s = log();
  dlclose(h);
  return s;
}

std::string motion_log() { return plugin_log("motion"); }

std::vector<std::string> diags(const World& w, const std::string& code) {
  std::vector<std::string> out;
  for (const auto& d : w.robot("box").config.diagnostics)
    if (d.code == code) out.push_back(d.message);
  return out;
}

}  // namespace

// fmax 0.1 N m, vel 100 rad/s (as gazebo_ros_diff_drive sets them): the motor cannot reach 100 rad/s, the joint
// speeds up at 4 x 0.1 = 0.4 rad/s^2: 0.4 rad/s after 1 s. GetParam reads back fmax, vel 0 before the first update,
// and friction (ODE's fmax).
TEST(GazeboJointParam, FmaxAndVelDriveTheJointAsODEsMotor) {
  motion_log();
  auto w = box_with("motor", "<fmax>0.1</fmax><vel>100</vel>");
  EXPECT_EQ(motion_log(), "fmax=0.1 vel=0 friction=0.1");
  w->step(1000);
  EXPECT_NEAR(w->joint_velocity("box", "axle"), 0.4, 1e-9);
}

// fmax 1000 N m is more than the 2 x 0.25 / 0.001 = 500 N m that 2 rad/s takes in one step: there after one step.
TEST(GazeboJointParam, EnoughFmaxReachesVelInOneStep) {
  auto w = box_with("motor", "<fmax>1000</fmax><vel>2</vel>");
  w->step();
  EXPECT_NEAR(w->joint_velocity("box", "axle"), 2.0, 1e-9);
}

// A key car does not offer and a value that is not a double: false and Gazebo's errors, nothing set.
TEST(GazeboJointParam, AnUnknownKeyAndANonDoubleValueAreRefused) {
  motion_log();
  testing::internal::CaptureStderr();
  auto w = box_with("bad_param");
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(motion_log(), "erp=0 int=0");
  EXPECT_NE(err.find("Unable to handle joint attribute[erp] (car offers \"vel\", \"fmax\" and \"friction\")"),
            std::string::npos)
      << err;
  EXPECT_NE(err.find("SetParam(fmax) boost any_cast error:"), std::string::npos) << err;
  EXPECT_EQ(w->joint_motor("box", "axle").max_effort, 0.0);
}

// Gravity 3 m/s^2, the box's gravity switched off in Load: it keeps its height for 1 s.
TEST(GazeboLink, SetGravityModeFalseKeepsTheLinksHeight) {
  motion_log();
  auto w = box_with("gravity", "", false, 3.0);
  EXPECT_EQ(motion_log(), "gravity=0");
  w->step(1000);
  EXPECT_NEAR(w->model_state("box").pose.translation().z(), 5.0, 1e-12);
}

// AddForce (1, 0, 0) and AddTorque (0, 0, 2) in each WorldUpdateBegin: WorldForce and WorldTorque then read them,
// once per step (the sum starts afresh each step).
TEST(GazeboLink, WorldForceAndTorqueAreWhatThisStepAdded) {
  motion_log();
  auto w = box_with("force", "", false);
  w->step(2);
  EXPECT_EQ(motion_log(), "f=1 t=2 f=1 t=2 ");
}

// The wheel put at (1, 2, 3): the model follows rigidly, the wheel stays 1 m above the model frame.
TEST(GazeboModel, SetLinkWorldPoseMovesTheModelSoThatTheLinkLandsThere) {
  motion_log();
  auto w = box_with("pose");
  EXPECT_EQ(motion_log(), "world=1 2 3 relative=0 0 1");
  EXPECT_NEAR(w->model_state("box").pose.translation().z(), 2.0, 1e-12);
}

// Physics off in Load, gravity 3 m/s^2: 100 steps advance time, the box does not fall.
TEST(GazeboWorld, SetPhysicsEnabledFalseStopsTheMotionNotTheTime) {
  auto w = box_with("physics_off", "", false, 3.0);
  EXPECT_FALSE(w->physics_enabled());
  w->step(100);
  EXPECT_EQ(w->tick(), 100u);
  EXPECT_EQ(w->model_state("box").pose.translation().z(), 5.0);
}

// gzthrow in Load (a gazebo::common::Exception, not a std::exception): the loader's error with its text.
TEST(GazeboLoad, GzthrowInLoadIsAnErrorWithItsText) {
  testing::internal::CaptureStderr();
  auto w = box_with("gzthrow", "", false);
  testing::internal::GetCapturedStderr();
  EXPECT_EQ(diags(*w, "plugin-not-loaded"),
            std::vector<std::string>{"plug-in 'm' of model 'box' failed to load: Load threw: no <bodyName> given; the "
                                     "model goes on without it"});
}

// Joint::SetPosition (Gazebo's Joint::SetPositionMaximal): _preserveWorldVelocity true keeps the 2 rad/s the joint
// had (the wheel's angular velocity about the axle: upstream's tricycle steers so every update); false zeroes it.
TEST(GazeboJoint, SetPositionPreservingTheWorldVelocityKeepsTheJointSpeed) {
  motion_log();
  auto w = box_with("set_position", "<position>0.5</position><preserve>true</preserve>");
  EXPECT_EQ(motion_log(), "ok=1 position=0.5 velocity=2");
}

TEST(GazeboJoint, SetPositionWithoutPreservingZeroesTheJointSpeed) {
  motion_log();
  auto w = box_with("set_position", "<position>0.5</position><preserve>false</preserve>");
  EXPECT_EQ(motion_log(), "ok=1 position=0.5 velocity=0");
}

// A position beyond the joint's limits [-1, 1] rad is held at the limit, as SetPositionMaximal clamps it.
TEST(GazeboJoint, SetPositionHoldsThePositionWithinTheLimits) {
  motion_log();
  auto w = box_with("set_position", "<position>1.5</position><preserve>true</preserve>", true, 0.0, "revolute");
  EXPECT_EQ(motion_log(), "ok=1 position=1 velocity=2");
}

// ---- Link::SetEnabled, as ODE's dBodyDisable under Gazebo 11 (test/gazebo/plugins/link_enabled.cc) -------------

// The wheel disabled in Load, the box enabled: ODE's islands enable the wheel again in the first physics step, so it
// reads 0 until then (WorldUpdateBegin) and 1 from that step's WorldUpdateEnd on.
TEST(GazeboLinkEnabled, ADisabledLinkJoinedToAnEnabledOneIsEnabledInTheNextStep) {
  plugin_log("link_enabled");
  auto w = box_with("joined", "", true, 0.0, "continuous", "link_enabled");
  w->step(2);
  EXPECT_EQ(plugin_log("link_enabled"), "load=0 begin=0 end=1 begin=1 end=1 ");
}

// The box alone, its only link disabled: nothing enables it, and car says it simulates it anyway (Gazebo's ODE would
// hold it still): gravity 3 m/s^2 moves it.
TEST(GazeboLinkEnabled, AModelWithEveryLinkDisabledStaysDisabledAndCarSaysItStillMoves) {
  plugin_log("link_enabled");
  testing::internal::CaptureStderr();
  auto w = box_with("alone", "", false, 3.0, "continuous", "link_enabled");
  const std::string err = testing::internal::GetCapturedStderr();
  w->step(2);
  EXPECT_EQ(plugin_log("link_enabled"), "load=0 begin=0 end=0 begin=0 end=0 ");
  EXPECT_NE(err.find("car: every link of model [box] is disabled (Link::SetEnabled(false)); Gazebo 11's ODE holds "
                     "such a model still until a contact or a force enables a link, car goes on simulating it "
                     "(docs/PLUGINS.md)"),
            std::string::npos)
      << err;
  EXPECT_LT(w->model_state("box").pose.translation().z(), 5.0);
}

// AddForce on the disabled link enables it at once, as ODELink's (even a zero force).
TEST(GazeboLinkEnabled, AForceOnADisabledLinkEnablesIt) {
  plugin_log("link_enabled");
  testing::internal::CaptureStderr();
  auto w = box_with("alone_force", "", false, 0.0, "continuous", "link_enabled");
  testing::internal::GetCapturedStderr();
  w->step(2);
  EXPECT_EQ(plugin_log("link_enabled"), "load=0 begin=0 end=0 begin=1 end=1 ");
}

// Both links disabled; Joint::SetForce on the axle enables both, as ODEJoint's.
TEST(GazeboLinkEnabled, SetForceOnAJointEnablesBothOfItsLinks) {
  plugin_log("link_enabled");
  testing::internal::CaptureStderr();
  auto w = box_with("joint_force", "", true, 0.0, "continuous", "link_enabled");
  testing::internal::GetCapturedStderr();
  w->step(2);
  EXPECT_EQ(plugin_log("link_enabled"), "load=00 begin=00 end=00 begin=11 end=11 ");
}
