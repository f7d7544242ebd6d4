// A model included inside a model (docs/COMPAT-sdf.md 16a): flattened into its parent as Gazebo 11's sdformat 9 does
// (addNestedModel, sdf9 src/parser.cc): one model whose links and joints are named `INCLUDED::name`, poses composed,
// the included model's plug-in text renamed; a plug-in car leaves out is never silent. The included model is
// test/data/nested_models/spinner.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "car_sim/description.hpp"
#include "car_sim/sdf_model.hpp"
#include "car_sim/world.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

// GAZEBO_MODEL_PATH set to test/data/nested_models alone for one test, put back after. Its one model, spinner
// (model.config says what it is): base (2 kg) 0.1 m above the model frame, rotor (1 kg) 0.3 m above it on the
// continuous joint axle (about z), Izz 0.5 kg m^2 each; rotor has a 1 Hz imu sensor, the model a joint_state_publisher.
class NestedInclude : public ::testing::Test {
 protected:
  ScopedEnv env_{{"GAZEBO_MODEL_PATH", data_path("nested_models")}};
};

// holder at (1, 2, 0) turned 90 deg about z, with spinner included 0.5 m along its x, and what else `more` adds.
std::string holder(const std::string& more) {
  return R"(<?xml version="1.0"?>
<sdf version="1.6">
  <world name="w">
    <model name="holder">
      <pose>1 2 0 0 0 1.5707963267948966</pose>
      <include><uri>model://spinner</uri><pose>0.5 0 0 0 0 0</pose></include>
      )" + more + R"(
    </model>
  </world>
</sdf>)";
}

std::vector<std::string> link_names(const RobotModel& m) {
  std::vector<std::string> out;
  for (const auto& l : m.links) out.push_back(l.name);
  return out;
}

const Diagnostic* find_diagnostic(const std::vector<Diagnostic>& ds, const std::string& code,
                                  const std::string& element) {
  for (const auto& d : ds)
    if (d.code == code && d.element == element) return &d;
  return nullptr;
}

}  // namespace

// Gazebo 11's World::Models() holds holder alone: spinner is part of it, not a model of its own.
TEST_F(NestedInclude, TheWorldListsTheParentOnly) {
  World w(load_world_string(holder(""), "holder.world"));
  EXPECT_EQ(w.model_names(), std::vector<std::string>{"holder"});
}

// addNestedModel renames spinner's links and joints `spinner::name`, its joint's <parent> and <child> too.
TEST_F(NestedInclude, LinksAndJointsArePrefixedWithTheIncludedModel) {
  const WorldDescription d = load_world_string(holder(""), "holder.world");
  ASSERT_EQ(d.robots.size(), 1u);
  const RobotModel& m = d.robots[0].robot.model;
  EXPECT_EQ(link_names(m), (std::vector<std::string>{"spinner::base", "spinner::rotor"}));
  ASSERT_EQ(m.joints.size(), 1u);
  EXPECT_EQ(m.joints[0].name, "spinner::axle");
  EXPECT_EQ(m.joints[0].parent, "spinner::base");
  EXPECT_EQ(m.joints[0].child, "spinner::rotor");
  EXPECT_EQ(m.joints[0].type, JointType::Continuous);
}

// holder's frame: (1, 2, 0), yaw 90 deg, so its x is the world's y. spinner's frame is (0.5, 0, 0) in holder, its
// base (0, 0, 0.1) in spinner: (0.5, 0, 0.1) in holder, (1 - 0, 2 + 0.5, 0.1) = (1, 2.5, 0.1) in the world; rotor
// 0.2 m above base: (1, 2.5, 0.3). Both keep holder's yaw.
TEST_F(NestedInclude, LinkPosesComposeTheIncludesPose) {
  World w(load_world_string(holder(""), "holder.world"));
  const Eigen::Isometry3d base = w.link_pose("holder", "spinner::base");
  const Eigen::Isometry3d rotor = w.link_pose("holder", "spinner::rotor");
  EXPECT_NEAR(base.translation().x(), 1.0, 1e-12);
  EXPECT_NEAR(base.translation().y(), 2.5, 1e-12);
  EXPECT_NEAR(base.translation().z(), 0.1, 1e-12);
  EXPECT_NEAR(rotor.translation().x(), 1.0, 1e-12);
  EXPECT_NEAR(rotor.translation().y(), 2.5, 1e-12);
  EXPECT_NEAR(rotor.translation().z(), 0.3, 1e-12);
  const Eigen::Vector3d x = rotor.linear() * Eigen::Vector3d::UnitX();  // the link's x in the world: holder's
  EXPECT_NEAR(x.x(), 0.0, 1e-12);
  EXPECT_NEAR(x.y(), 1.0, 1e-12);
}

// The included model's plug-in is the parent's, its text renamed as addNestedModel renames it (>axle< ->
// >spinner::axle<); the sensor sits on the renamed link.
TEST_F(NestedInclude, TheIncludedModelsPluginIsTheParentsWithItsTextRenamed) {
  const WorldDescription d = load_world_string(holder(""), "holder.world");
  ASSERT_EQ(d.robots.size(), 1u);
  const RobotModel& m = d.robots[0].robot.model;
  ASSERT_EQ(m.plugins.size(), 1u);
  EXPECT_EQ(m.plugins[0].name, "states");
  const std::string* joint = find_param(m.plugins[0].params, "jointName");
  ASSERT_NE(joint, nullptr);
  EXPECT_EQ(*joint, "spinner::axle");
  ASSERT_EQ(m.sensors.size(), 1u);
  EXPECT_EQ(m.sensors[0].link, "spinner::rotor");
}

// gazebo_ros get_joint_properties asks each model's GetJoint, which takes the name or the scoped name.
TEST_F(NestedInclude, AJointIsFoundByItsNameAndByItsScopedName) {
  World w(load_world_string(holder(""), "holder.world"));
  EXPECT_EQ(w.joint_properties("spinner::axle").model, "holder");
  EXPECT_EQ(w.joint_properties("holder::spinner::axle").model, "holder");
  EXPECT_EQ(w.find_link("holder::spinner::rotor").link, "spinner::rotor");
}

// The parent's own link and the included base with no joint between them: two trees, which car's robot path cannot
// simulate as one model; the error names the link (rule 7) and says why it is the model's own.
TEST_F(NestedInclude, AForestOfLinksIsRefusedNamingTheLink) {
  const std::string post = R"(<link name="post"><inertial><mass>1</mass><inertia><ixx>1</ixx><iyy>1</iyy><izz>1</izz>
      </inertia></inertial></link>)";
  // post comes first in the document, so it is the first root and spinner::base the second
  const std::string xml = R"(<?xml version="1.0"?>
<sdf version="1.6">
  <world name="w">
    <model name="holder">
      )" + post + R"(
      <include><uri>model://spinner</uri></include>
    </model>
  </world>
</sdf>)";
  try {
    load_world_string(xml, "forest.world");
    FAIL() << "a forest loaded";
  } catch (const LoadError& e) {
    EXPECT_EQ(e.element(), "model[holder]/link[spinner::base]");
    EXPECT_EQ(e.reason(),
              "link 'spinner::base' is joined to no other link (a second free body); car simulates one tree of links "
              "per model (an included model's links are the model's own, as Gazebo 11 flattens an <include>)");
  }
}

// A joint of the parent may join its own link to an included one (`spinner::base`): one tree. post at holder's
// origin, base 0.1 m above it along holder's z (spinner at 0.5 m along holder's x): the joint origin is base in
// post's frame, (0.5, 0, 0.1).
TEST_F(NestedInclude, AParentsJointMayJoinAnIncludedLink) {
  const std::string more = R"(<link name="post"><inertial><mass>1</mass><inertia><ixx>1</ixx><iyy>1</iyy><izz>1</izz>
      </inertia></inertial></link>
      <joint name="mount" type="fixed"><parent>post</parent><child>spinner::base</child></joint>)";
  const WorldDescription d = load_world_string(holder(more), "mount.world");
  ASSERT_EQ(d.robots.size(), 1u);
  const RobotModel& m = d.robots[0].robot.model;
  EXPECT_EQ(link_names(m), (std::vector<std::string>{"spinner::base", "spinner::rotor", "post"}));
  ASSERT_EQ(m.joints.size(), 2u);
  EXPECT_EQ(m.joints[1].name, "mount");
  EXPECT_EQ(m.joints[1].child, "spinner::base");
  EXPECT_TRUE(m.joints[1].origin.translation().isApprox(Eigen::Vector3d(0.5, 0, 0.1), 1e-12));
  EXPECT_EQ(m.root_link, "post");
}

// spawn_sdf_model reads the model with the same code: the include is flattened there too (Gazebo 11's factory reads
// the text with the same sdformat).
TEST_F(NestedInclude, ASpawnedModelFlattensItsIncludeToo) {
  const SdfRobot r = load_sdf_model_string(
      "<sdf version='1.6'><model name='bot'><include><uri>model://spinner</uri></include></model></sdf>", "bot.sdf");
  EXPECT_EQ(link_names(r.model), (std::vector<std::string>{"spinner::base", "spinner::rotor"}));
  EXPECT_EQ(r.model.joints.at(0).name, "spinner::axle");
}

// A <model> written inside the robot stays a model of its own (Gazebo 11's Model::LoadModels): car hoists it, and
// the parent, now world bodies, cannot load its plug-in: a warning names the plug-in, its file and the model.
TEST_F(NestedInclude, APluginOfAModelWithAWrittenNestedModelIsLeftOutWithAWarning) {
  const std::string more = R"(<model name="lamp"><pose>0 0 1 0 0 0</pose><link name="l"/></model>
      <plugin name="spin" filename="libvelocity_pid.so"><velocity>10</velocity></plugin>)";
  const WorldDescription d = load_world_string(holder(more), "lamp.world");
  EXPECT_TRUE(d.robots.empty());
  const Diagnostic* w = find_diagnostic(d.diagnostics, "plugin-not-loaded", "model[holder]/plugin[spin]");
  ASSERT_NE(w, nullptr);
  EXPECT_EQ(w->severity, Severity::Warning);
  EXPECT_EQ(w->message,
            "plug-in 'spin' (libvelocity_pid.so) of model 'holder' is not loaded: car simulates a model with nested "
            "models as world bodies, not as a robot");
}

// The same for a plug-in of the written nested model itself (hoisted as world bodies).
TEST_F(NestedInclude, APluginOfAWrittenNestedModelIsLeftOutWithAWarning) {
  const std::string xml = R"(<?xml version="1.0"?>
<sdf version="1.6">
  <world name="w">
    <model name="shelf">
      <link name="board"/>
      <model name="fan"><link name="l"/><plugin name="push" filename="libmodel_push.so"/></model>
    </model>
  </world>
</sdf>)";
  const WorldDescription d = load_world_string(xml, "fan.world");
  const Diagnostic* w = find_diagnostic(d.diagnostics, "plugin-not-loaded", "model[shelf::fan]/plugin[push]");
  ASSERT_NE(w, nullptr);
  EXPECT_EQ(w->message,
            "plug-in 'push' (libmodel_push.so) of model 'shelf::fan' is not loaded: car simulates a nested model as "
            "world bodies, not as a robot");
}
