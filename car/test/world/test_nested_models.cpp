// Nested models in a world file (docs/COMPAT-sdf.md rule 16a): car hoists each nested model into a model of its own,
// "parent::child"; a parent with no link of its own follows its canonical link, as in Gazebo 11.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "car_sim/world.hpp"

using namespace car_sim;

namespace {

// shelf at (1, 0, 0) holds only the nested model board, 0.5 m above it; a 1 kg box in free fall (no ground)
const char* kShelf = R"(<?xml version="1.0"?>
<sdf version="1.7">
  <world name="w">
    <model name="shelf">
      <pose>1 0 0 0 0 0</pose>
      <model name="board">
        <pose>0 0 0.5 0 0 0</pose>
        <link name="l">
          <inertial><mass>1</mass><inertia><ixx>0.1667</ixx><iyy>0.1667</iyy><izz>0.1667</izz></inertia></inertial>
          <collision name="c"><geometry><box><size>1 1 1</size></box></geometry></collision>
        </link>
      </model>
    </model>
  </world>
</sdf>)";

}  // namespace

// Gazebo 11's Model::LoadLinks makes board's link shelf's canonical link too: shelf's frame keeps its load-time
// offset (0.5 m below the link) and its twist is the link's. Ten steps of 1 ms of free fall (semi-implicit Euler):
// v = -9.8 * 0.010 = -0.098 m/s, z = 0.5 - 9.8e-6 * (1 + ... + 10) = 0.5 - 0.000539 m.
TEST(NestedModels, AModelWithOnlyNestedModelsFollowsItsCanonicalLink) {
  World w(load_world_string(kShelf, "nested.world"));
  EXPECT_EQ(w.model_names(), (std::vector<std::string>{"shelf", "shelf::board"}));
  w.step(10);
  const ModelState s = w.model_state("shelf");
  EXPECT_DOUBLE_EQ(s.pose.translation().x(), 1.0);
  EXPECT_DOUBLE_EQ(s.pose.translation().y(), 0.0);
  EXPECT_NEAR(s.pose.translation().z(), -0.000539, 1e-12);
  EXPECT_NEAR(s.linear.z(), -0.098, 1e-12);
  EXPECT_NEAR(s.angular.norm(), 0.0, 1e-12);
}

// Entity::SetWorldPoseModel: the nested models move with their parent, keeping their poses relative to it.
TEST(NestedModels, SettingAParentsPoseMovesItsNestedModels) {
  World w(load_world_string(kShelf, "nested.world"));
  ModelState target;
  target.pose = Eigen::Translation3d(2.0, 1.0, 3.0) * Eigen::Isometry3d::Identity();
  w.set_model_state("shelf", target);
  const Eigen::Vector3d board = w.model_state("shelf::board").pose.translation();
  EXPECT_NEAR(board.x(), 2.0, 1e-12);
  EXPECT_NEAR(board.y(), 1.0, 1e-12);
  EXPECT_NEAR(board.z(), 3.5, 1e-12);
}

// World::RemoveModel in Gazebo 11 removes the model entity with its children, nested models among them.
TEST(NestedModels, DeletingAParentDeletesItsNestedModels) {
  World w(load_world_string(kShelf, "nested.world"));
  w.remove("shelf");
  EXPECT_EQ(w.model_names(), std::vector<std::string>{});
}

// libsdformat 12 converts an SDF 1.7 link named "body::x" into link x of a nested model body (its 1.7 -> 1.8
// unflattening), where Gazebo 11 keeps one link named "body::x" of crate: car flattens that model back
// (docs/COMPAT-sdf.md 16a), so crate is one model with its link "body::x". Found by fuzz_sdf_world
// (test/fuzz/regressions/sdf_world/): when car kept the nested model, crate's state read its first body, which it did
// not have.
TEST(NestedModels, ALinkNameWithAScopeStaysOneLinkOfItsModel) {
  const std::string xml = R"(<?xml version="1.0"?>
<sdf version="1.7">
  <world name="w">
    <model name="crate">
      <pose>0 0 0.5 0 0 0</pose>
      <link name="body::x">
        <collision name="c"><geometry><box><size>1 1 1</size></box></geometry></collision>
      </link>
    </model>
  </world>
</sdf>)";
  World w(load_world_string(xml, "scoped.world"));
  EXPECT_EQ(w.model_names(), std::vector<std::string>{"crate"});
  EXPECT_EQ(w.find_link("crate::body::x").link, "body::x");
  w.step(10);
  EXPECT_NEAR(w.model_state("crate").pose.translation().z(), 0.5 - 0.000539, 1e-12);
}
