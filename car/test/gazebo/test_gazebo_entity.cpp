// physics::Base and Entity, World::EntityByName / BaseByName, ResetTime and ResetEntities, and Joint::SetPosition's
// limits (docs/PLUGINS.md "Entities"), through the test plug-in test/gazebo/plugins/entity.cc loaded by the world's
// plug-in table. Values by hand; dt = 0.001 s, no gravity. The arm: base (1 kg) at the spawn pose (1, 2, 0.5),
// upper (1 kg) 0.5 m above it on the revolute joint elbow (about z, limits [-1, 1] rad), tool fixed on upper (merged
// into it, as Gazebo's URDF import does).
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <map>
#include <sstream>
#include <string>

#include "car_sim/world.hpp"

using namespace car_sim;

namespace {

const std::string kDir = CAR_GAZEBO_TEST_PLUGINS;

std::unique_ptr<World> arm_with(const std::string& mode) {
  const std::string urdf = R"(<?xml version="1.0"?>
<robot name="arm">
  <link name="base">
    <inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  </link>
  <link name="upper">
    <inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
  </link>
  <link name="tool">
    <inertial><mass value="0.1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="elbow" type="revolute"><parent link="base"/><child link="upper"/><origin xyz="0 0 0.5"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="10" velocity="10"/></joint>
  <joint name="grip" type="fixed"><parent link="upper"/><child link="tool"/><origin xyz="0.1 0 0"/></joint>
  <gazebo><plugin name="e" filename=")" + kDir + R"(/libentity.so"><mode>)" + mode + R"(</mode></plugin></gazebo>
</robot>)";
  auto w = std::make_unique<World>(empty_world());
  w->set_gravity(Eigen::Vector3d::Zero());
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(1, 2, 0.5);
  w->spawn(load_urdf_string(urdf, "arm"), "arm", pose);
  return w;
}

// What the plug-in logged since the last call.
std::string entity_log() {
  void* h = dlopen((kDir + "/libentity.so").c_str(), RTLD_LAZY | RTLD_NOLOAD);
  if (!h) return "<not loaded>";
  auto log = reinterpret_cast<const char* (*)()>(dlsym(h, "car_test_entity_log"));
  std::string s = log();
  dlclose(h);
  return s;
}

// The lookup mode's KEY=VALUE log as a map.
std::map<std::string, std::string> lookup() {
  entity_log();
  auto w = arm_with("lookup");
  std::map<std::string, std::string> out;
  std::istringstream in(entity_log());
  std::string kv;
  while (in >> kv) {
    const size_t eq = kv.find('=');
    if (eq != std::string::npos) out[kv.substr(0, eq)] = kv.substr(eq + 1);
  }
  return out;
}

}  // namespace

// EntityByName("arm") is the plug-in's own model; "arm::upper" is a Link (dynamic_pointer_cast<Link> works,
// <Model> gives null), named upper, scoped arm::upper and default::arm::upper (empty_world's name is default).
TEST(GazeboEntity, EntityByNameGivesTheModelAndALinkByScopedName) {
  auto log = lookup();
  EXPECT_EQ(log["model"], "1");
  EXPECT_EQ(log["link"], "upper");
  EXPECT_EQ(log["link_is_model"], "0");
  EXPECT_EQ(log["scoped"], "arm::upper");
  EXPECT_EQ(log["world_scoped"], "default::arm::upper");
}

// Gazebo's Base::GetByName matches the plain name too: "upper" is the same handle as "arm::upper".
TEST(GazeboEntity, APlainNameFindsTheSameLink) { EXPECT_EQ(lookup()["plain_same"], "1"); }

// A link's GetParentModel and GetParent are its model; its type bits are LINK and ENTITY, not MODEL.
TEST(GazeboEntity, ALinksParentModelIsItsModel) {
  auto log = lookup();
  EXPECT_EQ(log["parent_model"], "arm");
  EXPECT_EQ(log["parent"], "arm");
  EXPECT_EQ(log["link_type"], "110");
}

// A joint is a Base, not an Entity (Gazebo 11): EntityByName gives null, BaseByName the joint, typed JOINT and
// HINGE_JOINT (a revolute joint), not SLIDER_JOINT, not ENTITY.
TEST(GazeboEntity, AJointIsABaseNotAnEntity) {
  auto log = lookup();
  EXPECT_EQ(log["joint_entity"], "0");
  EXPECT_EQ(log["joint_base"], "elbow");
  EXPECT_EQ(log["joint_type"], "1100");
}

// The fixed-joint link tool is merged into upper (not a link of car's model), and "nothing" is nowhere: null.
TEST(GazeboEntity, AMergedLinkAndAnUnknownNameGiveNull) {
  auto log = lookup();
  EXPECT_EQ(log["merged"], "0");
  EXPECT_EQ(log["none"], "0");
}

// The world's name gives the root element (a Base, so EntityByName's null): named default, without a parent; it is
// the model's parent, and a model's GetParentModel is the model itself.
TEST(GazeboEntity, TheWorldsNameGivesTheRootElementTheModelsParent) {
  auto log = lookup();
  EXPECT_EQ(log["root_entity"], "0");
  EXPECT_EQ(log["root"], "default");
  EXPECT_EQ(log["root_parent"], "0");
  EXPECT_EQ(log["model_parent"], "default");
  EXPECT_EQ(log["self_model"], "1");
}

// Through the EntityPtr: upper's pose is the spawn pose plus 0.5 m up, (1, 2, 1); SetWorldPose (0, 0, 3) on it
// moves the whole arm rigidly, the model frame (base) 0.5 m below, at (0, 0, 2.5).
TEST(GazeboEntity, WorldPoseAndSetWorldPoseDispatchToTheLink) {
  entity_log();
  auto w = arm_with("pose");
  EXPECT_EQ(entity_log(), "before=1 2 1 after=0 0 3 model=0 0 2.5");
}

// ResetTime in the 3rd WorldUpdateBegin is done at that step's end: tick 3 -> 0, then steps 4 and 5: tick 2. The
// arm, given 1 m/s along x, keeps it: 5 steps of 0.001 s from x = 1 m: x = 1.005 m.
TEST(GazeboWorld, ResetTimeTakesTimeToZeroAndKeepsTheModels) {
  auto w = arm_with("reset_time");
  ModelState s = w->model_state("arm");
  s.linear = Eigen::Vector3d(1, 0, 0);
  w->set_model_state("arm", s);
  w->step(5);
  EXPECT_EQ(w->tick(), 2u);
  EXPECT_NEAR(w->model_state("arm").pose.translation().x(), 1.005, 1e-9);
  EXPECT_NEAR(w->model_state("arm").linear.x(), 1.0, 1e-9);
}

// ResetEntities(MODEL) in the 3rd WorldUpdateBegin, at that step's end: the arm back at x = 1 m at rest (its spawn
// pose), time going on: tick 5.
TEST(GazeboWorld, ResetEntitiesPutsTheModelsBackAndTimeGoesOn) {
  auto w = arm_with("reset_entities");
  ModelState s = w->model_state("arm");
  s.linear = Eigen::Vector3d(1, 0, 0);
  w->set_model_state("arm", s);
  w->step(5);
  EXPECT_EQ(w->tick(), 5u);
  EXPECT_NEAR(w->model_state("arm").pose.translation().x(), 1.0, 1e-12);
  EXPECT_NEAR(w->model_state("arm").linear.x(), 0.0, 1e-12);
}

// A type car cannot reset alone (a link) is refused with the error, and nothing is reset.
TEST(GazeboWorld, ResetEntitiesOfLinksIsRefused) {
  testing::internal::CaptureStderr();
  auto w = arm_with("reset_links");
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("World::ResetEntities(4): car resets whole models only (Base::BASE, Base::ENTITY or "
                     "Base::MODEL); nothing was reset"),
            std::string::npos)
      << err;
}

// SetPosition 2 rad is clamped to the upper limit, 1 rad (Gazebo's SetPositionMaximal), rate 0; with the rate set to
// 0.5 rad/s, SetPosition(0.2, preserve) keeps it; SetPosition(0.3) without makes it 0.
TEST(GazeboJoint, SetPositionClampsToTheLimitsAndPreservesTheRateOnRequest) {
  entity_log();
  auto w = arm_with("set_position");
  EXPECT_EQ(entity_log(), "1/0 0.2/0.5 0.3/0 ");
}
