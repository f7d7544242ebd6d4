// What a model plug-in sees of fixed joints, the link `world` and static models (docs/PLUGINS.md "Fixed joints, the
// world link and static models"), through the test plug-in test/gazebo/plugins/joint_list.cc. Upstream: Gazebo
// 11.10.1's Model.cc (GetJoints, GetJointCount, GetLink("canonical"), IsStatic), Joint.cc, ode/ODEJoint.cc and
// ode/ODEFixedJoint.cc (a fixed joint's DOF 0, its answers and messages).
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <sstream>
#include <string>

#include "car_sim/world.hpp"

using namespace car_sim;

namespace {

const std::string kDir = CAR_GAZEBO_TEST_PLUGINS;

// What the plug-in logged since the last call.
std::string joint_log() {
  void* h = dlopen((kDir + "/libjoint_list.so").c_str(), RTLD_LAZY | RTLD_NOLOAD);
  if (!h) return "<not loaded>";
  auto log = reinterpret_cast<const char* (*)()>(dlsym(h, "car_test_joint_list_log"));
  std::string s = log();
  dlclose(h);
  return s;
}

// The log's KEY=VALUE words as a map.
std::map<std::string, std::string> words(const std::string& log) {
  std::map<std::string, std::string> out;
  std::istringstream in(log);
  std::string kv;
  while (in >> kv) {
    const size_t eq = kv.find('=');
    if (eq != std::string::npos) out[kv.substr(0, eq)] = kv.substr(eq + 1);
  }
  return out;
}

std::string plugin(const std::string& probe = "") {
  return "<plugin name=\"list\" filename=\"" + kDir + "/libjoint_list.so\">" +
         (probe.empty() ? "" : "<probe>" + probe + "</probe>") + "</plugin>";
}

// An SDF world with one model "rig" and the plug-in: links a, b (0.5 m above a on the revolute joint hinge, about z,
// limits +-1 rad, effort 10, velocity 2) and c (welded to b by the fixed joint weld); `is_static` its <static>.
std::unique_ptr<World> rig(bool is_static, const std::string& probe = "") {
  const std::string link = R"(<inertial><mass>1</mass><inertia><ixx>0.1</ixx><iyy>0.1</iyy><izz>0.1</izz></inertia>
      </inertial>)";
  auto w = std::make_unique<World>(load_world_string(R"(<?xml version="1.0"?>
<sdf version="1.6"><world name="w"><gravity>0 0 0</gravity>
  <model name="rig"><static>)" + std::string(is_static ? "true" : "false") + R"(</static>
    <link name="a">)" + link + R"(</link>
    <link name="b"><pose>0 0 0.5 0 0 0</pose>)" + link + R"(</link>
    <link name="c"><pose>0.2 0 0.5 0 0 0</pose>)" + link + R"(</link>
    <joint name="hinge" type="revolute"><parent>a</parent><child>b</child>
      <axis><xyz>0 0 1</xyz><limit><lower>-1</lower><upper>1</upper><effort>10</effort><velocity>2</velocity></limit>
      </axis></joint>
    <joint name="weld" type="fixed"><parent>b</parent><child>c</child></joint>
    )" + plugin(probe) + R"(
  </model>
</world></sdf>)", "rig.world"));
  return w;
}

// A URDF robot anchored by the fixed joint fix from the link world: base, arm on the continuous joint spin, tool on
// arm by the fixed joint grip (kept: <preserveFixedJoint>), marker on base by the fixed joint mark (lumped).
std::unique_ptr<World> anchored() {
  const std::string inertial =
      R"(<inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>)";
  const std::string urdf = R"(<?xml version="1.0"?>
<robot name="anchored">
  <link name="world"/>
  <link name="base">)" + inertial + R"(</link>
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint>
  <link name="arm">)" + inertial + R"(</link>
  <joint name="spin" type="continuous"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/></joint>
  <link name="tool">)" + inertial + R"(</link>
  <joint name="grip" type="fixed"><parent link="arm"/><child link="tool"/><origin xyz="0.1 0 0"/></joint>
  <link name="marker">)" + inertial + R"(</link>
  <joint name="mark" type="fixed"><parent link="base"/><child link="marker"/></joint>
  <gazebo reference="grip"><preserveFixedJoint>true</preserveFixedJoint></gazebo>
  <gazebo>)" + plugin() + R"(</gazebo>
</robot>)";
  auto w = std::make_unique<World>(empty_world());
  w->spawn(load_urdf_string(urdf, "anchored"), "anchored", Eigen::Isometry3d::Identity());
  return w;
}

}  // namespace

// Model::GetJoints lists every joint the model loaded, the fixed one too, in the SDF's order; GetJointCount counts
// it. (car left fixed joints out before: joints=hinge, count=1.)
TEST(GazeboFixedJoints, AnSdfModelsFixedJointIsListed) {
  joint_log();
  auto w = rig(false);
  const auto m = words(joint_log());
  EXPECT_EQ(m.at("joints"), "hinge,weld");
  EXPECT_EQ(m.at("count"), "2");
}

// A fixed joint has no axis (FixedJoint::DOF 0) and the type bit FIXED_JOINT; its parent and child are its links.
TEST(GazeboFixedJoints, AFixedJointHasNoAxisAndItsLinks) {
  joint_log();
  auto w = rig(false);
  const auto m = words(joint_log());
  EXPECT_EQ(m.at("weld.dof"), "0");
  EXPECT_EQ(m.at("weld.fixed"), "1");
  EXPECT_EQ(m.at("weld.parent"), "b");
  EXPECT_EQ(m.at("weld.child"), "c");
  EXPECT_EQ(m.at("hinge.dof"), "1");
  EXPECT_EQ(m.at("hinge.fixed"), "0");
}

// Each Joint call on a fixed joint answers as Gazebo 11's ODE fixed joint: NaN position, 0 velocity, SetPosition
// false, GetForce 0 after a SetForce, NaN limits, 0 effort and velocity limits, no axis, SetParam("vel") true with
// GetParam 0.
TEST(GazeboFixedJoints, AFixedJointAnswersAsODEsFixedJoint) {
  joint_log();
  testing::internal::CaptureStderr();
  auto w = rig(false, "weld");
  testing::internal::GetCapturedStderr();
  const auto m = words(joint_log());
  EXPECT_EQ(m.at("position"), "nan");
  EXPECT_EQ(m.at("velocity"), "0");
  EXPECT_EQ(m.at("set_position"), "0");
  EXPECT_EQ(m.at("force"), "0");
  EXPECT_EQ(m.at("lower"), "nan");
  EXPECT_EQ(m.at("upper"), "nan");
  EXPECT_EQ(m.at("effort"), "0");
  EXPECT_EQ(m.at("vel_limit"), "0");
  EXPECT_EQ(m.at("axis"), "0,0,0");
  EXPECT_EQ(m.at("set_param"), "1");
  EXPECT_EQ(m.at("get_param"), "0");
}

// ... with upstream's messages, in the order of the calls (ODEFixedJoint.cc's warnings, Joint.cc's and
// ODEJoint.cc's index checks against DOF 0).
TEST(GazeboFixedJoints, AFixedJointSaysWhatUpstreamSays) {
  joint_log();
  testing::internal::CaptureStderr();
  auto w = rig(false, "weld");
  const std::string err = testing::internal::GetCapturedStderr();
  size_t at = 0;
  for (const std::string& line :
       {"ODEFixedJoint: called method PositionImpl that is not valid for joints of type fixed.",
        "ODEFixedJoint: called method GetVelocity that is not valid for joints of type fixed.",
        "ODEFixedJoint: called method SetVelocity that is not valid for joints of type fixed.",
        "Joint axis index [0] larger than DOF count [0].", "Calling Joint::SetForce with an index [0] out of range",
        "Something's wrong, joint [rig::weld] index [0] out of range.",
        "ODEFixedJoint: called method SetForceImpl that is not valid for joints of type fixed.",
        "Invalid joint index [0] when trying to get force", "requesting lower limit of joint index out of bound",
        "requesting upper limit of joint index out of bound", "GetEffortLimit index[0] out of range",
        "GetVelocityLimit index[0] out of range"}) {
    const size_t found = err.find(line, at);
    ASSERT_NE(found, std::string::npos) << "not found after offset " << at << ": " << line << "\n" << err;
    at = found + line.size();
  }
}

// The weld is a weld: the calls above moved nothing (c stays 0.2 m from b along b's x).
TEST(GazeboFixedJoints, CallsOnAFixedJointMoveNothing) {
  testing::internal::CaptureStderr();
  auto w = rig(false, "weld");
  w->step(100);
  testing::internal::GetCapturedStderr();
  const Eigen::Isometry3d b = w->link_pose("rig", "b"), c = w->link_pose("rig", "c");
  EXPECT_NEAR((b.inverse() * c).translation().x(), 0.2, 1e-9);
  EXPECT_NEAR((b.inverse() * c).translation().z(), 0.0, 1e-9);
}

// A static model: IsStatic true; its links are its own (car's anchor link `world` is not one), the first canonical;
// car's anchor joint (world_static_a) is not listed; a fixed joint's Position reads 0, without a warning.
TEST(GazeboFixedJoints, AStaticModelIsStaticAndListsItsOwnLinksAndJoints) {
  joint_log();
  testing::internal::CaptureStderr();
  auto w = rig(true, "weld");
  const std::string err = testing::internal::GetCapturedStderr();
  const auto m = words(joint_log());
  EXPECT_EQ(m.at("static"), "1");
  EXPECT_EQ(m.at("links"), "a,b,c");
  EXPECT_EQ(m.at("canonical"), "a");
  EXPECT_EQ(m.at("joints"), "hinge,weld");
  EXPECT_EQ(m.at("position"), "0");
  EXPECT_EQ(err.find("PositionImpl"), std::string::npos) << err;
}

// A moving model is not static.
TEST(GazeboFixedJoints, AModelThatMovesIsNotStatic) {
  joint_log();
  auto w = rig(false);
  EXPECT_EQ(words(joint_log()).at("static"), "0");
}

// A URDF robot with the link world: Gazebo's URDF import drops that link (base is canonical), keeps the joint fix
// from it (no parent link) and the preserved fixed joint grip; the lumped joint mark is gone.
TEST(GazeboFixedJoints, AUrdfsWorldLinkIsNoLinkAndItsJointIsListed) {
  joint_log();
  auto w = anchored();
  const auto m = words(joint_log());
  EXPECT_EQ(m.at("links"), "base,arm,tool");
  EXPECT_EQ(m.at("canonical"), "base");
  EXPECT_EQ(m.at("joints"), "fix,spin,grip");
  EXPECT_EQ(m.at("fix.parent"), "null");
  EXPECT_EQ(m.at("fix.child"), "base");
  EXPECT_EQ(m.at("grip.dof"), "0");
}
