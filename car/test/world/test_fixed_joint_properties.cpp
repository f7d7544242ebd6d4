// gazebo_ros's get_model_properties and get_joint_properties for fixed joints and static models (docs/COMPAT.md):
// upstream's joint_names are Model::GetJoints (fixed joints too), is_static Model::IsStatic, and a joint's position
// Joint::Position(0) (a fixed joint: NaN, 0 on a static model). car's anchors of a static SDF model are not joints.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "car_sim/world.hpp"

using namespace car_sim;

namespace {

// A world with the model "rig" (a plug-in-less model with joints is a robot, docs/COMPAT-sdf.md 16): links a, b on
// the revolute joint hinge, c welded to b by the fixed joint weld; `is_static` its <static>.
std::unique_ptr<World> rig(bool is_static) {
  const std::string link =
      "<inertial><mass>1</mass><inertia><ixx>0.1</ixx><iyy>0.1</iyy><izz>0.1</izz></inertia></inertial>";
  return std::make_unique<World>(load_world_string(R"(<?xml version="1.0"?>
<sdf version="1.6"><world name="w"><gravity>0 0 0</gravity>
  <model name="rig"><static>)" + std::string(is_static ? "true" : "false") + R"(</static>
    <link name="a">)" + link + R"(</link>
    <link name="b"><pose>0 0 0.5 0 0 0</pose>)" + link + R"(</link>
    <link name="c"><pose>0.2 0 0.5 0 0 0</pose>)" + link + R"(</link>
    <joint name="hinge" type="revolute"><parent>a</parent><child>b</child><axis><xyz>0 0 1</xyz></axis></joint>
    <joint name="weld" type="fixed"><parent>b</parent><child>c</child></joint>
  </model>
</world></sdf>)", "rig.world"));
}

}  // namespace

TEST(FixedJointProperties, ModelPropertiesListTheFixedJoint) {
  auto w = rig(false);
  EXPECT_EQ(w->model_properties("rig").joints, (std::vector<std::string>{"hinge", "weld"}));
}

TEST(FixedJointProperties, AStaticModelIsStaticWithoutCarsAnchorJoint) {
  auto w = rig(true);
  const ModelProperties p = w->model_properties("rig");
  EXPECT_TRUE(p.is_static);
  EXPECT_EQ(p.joints, (std::vector<std::string>{"hinge", "weld"}));
}

TEST(FixedJointProperties, AModelThatMovesIsNotStatic) { EXPECT_FALSE(rig(false)->model_properties("rig").is_static); }

TEST(FixedJointProperties, AFixedJointsPropertiesAreItsTypeNaNPositionAndNoRate) {
  auto w = rig(false);
  const JointProperties p = w->joint_properties("rig::weld");
  EXPECT_EQ(p.type, JointType::Fixed);
  EXPECT_TRUE(std::isnan(p.position));
  EXPECT_EQ(p.velocity, 0.0);
}

TEST(FixedJointProperties, AFixedJointOfAStaticModelIsAtZero) {
  EXPECT_EQ(rig(true)->joint_properties("rig::weld").position, 0.0);
}

// car's anchor of the static model is no joint of it: "no robot has a joint named 'world_static_a'".
TEST(FixedJointProperties, CarsAnchorJointIsNotFound) {
  auto w = rig(true);
  try {
    w->joint_properties("world_static_a");
    FAIL() << "world_static_a was found";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "no robot has a joint named 'world_static_a'");
  }
}

// apply_joint_effort still takes moving joints only: "no robot has a moving joint named 'weld'".
TEST(FixedJointProperties, AnEffortOnAFixedJointIsRefused) {
  auto w = rig(false);
  try {
    w->apply_joint_effort("weld", 1.0, 0.0, 1.0);
    FAIL() << "an effort on weld was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "no robot has a moving joint named 'weld'");
  }
}
