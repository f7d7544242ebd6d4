// A <gazebo> block without reference (sdformat copies its elements into the <model>): <self_collide> as the
// model's default for links that set none (franka_description writes <self_collide>true</self_collide> there);
// <static> and other model-level elements named in the model's diagnostics instead of silently dropped.
#include <gtest/gtest.h>

#include "car_sim/description.hpp"
#include "car_sim/world.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

// base: a 0.2 m cube of 5 kg. mid: 0.1 kg, no shape, on a revolute joint about z at base's centre. block: a 0.1 m
// cube of 0.5 kg on a prismatic z joint from mid, 0.4 m above base's centre, free over [-0.5, 0.1] m. block and
// base are not joined directly (mid lies between), so only self-collision keeps the block off the base.
std::string robot(const std::string& extra) {
  return R"(<robot name="stack">
  <link name="base"><inertial><mass value="5"/><inertia ixx="0.0333" iyy="0.0333" izz="0.0333" ixy="0" ixz="0" iyz="0"/>
    </inertial><collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <link name="mid"><inertial><mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/>
    </inertial></link>
  <joint name="spin" type="revolute"><parent link="base"/><child link="mid"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <link name="block"><inertial><mass value="0.5"/><inertia ixx="8.3e-4" iyy="8.3e-4" izz="8.3e-4" ixy="0" ixz="0" iyz="0"/>
    </inertial><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <joint name="slide" type="prismatic"><parent link="mid"/><child link="block"/><origin xyz="0 0 0.4"/>
    <axis xyz="0 0 1"/><limit lower="-0.5" upper="0.1" effort="100" velocity="100"/></joint>)" +
         extra + "</robot>";
}

// World height [m] of the block's centre after 2 s, the base spawned resting on the ground (centre at 0.1 m).
double block_height(const std::string& extra) {
  World w(empty_world());
  w.spawn(load_urdf_string(robot(extra), "stack"), "stack", at(0, 0, 0) * Eigen::Translation3d(0, 0, 0.1));
  w.step(2000);  // the block falls 0.25 m in 0.23 s; settled well before 2 s
  return w.link_pose("stack", "block").translation().z();
}

const Diagnostic* diag(const RobotModel& m, const std::string& element) {
  for (const auto& d : m.diagnostics)
    if (d.element == element) return &d;
  return nullptr;
}

}  // namespace

TEST(Zoo19RobotBlock, ModelSelfCollideGoesToEveryLinkThatSetsNone) {
  const RobotModel m = load_urdf_string(
      robot("<gazebo><self_collide>true</self_collide></gazebo>"
            "<gazebo reference='mid'><selfCollide>false</selfCollide></gazebo>"),
      "stack");
  EXPECT_EQ(m.find_link("base")->gazebo.self_collide, std::optional<bool>(true));
  EXPECT_EQ(m.find_link("block")->gazebo.self_collide, std::optional<bool>(true));
  // a link's own <selfCollide> wins
  EXPECT_EQ(m.find_link("mid")->gazebo.self_collide, std::optional<bool>(false));
}

TEST(Zoo19RobotBlock, WithoutSelfCollideTheBlockFallsThroughTheBaseToTheGround) {
  // the block passes through the base and lands on the ground plane: centre at its half height 0.05 m
  EXPECT_NEAR(block_height(""), 0.05, 0.002);
}

TEST(Zoo19RobotBlock, ModelSelfCollideLandsTheBlockOnTheBase) {
  // the base's top at 0.2 m, the block's half height 0.05 m: centre at 0.25 m
  EXPECT_NEAR(block_height("<gazebo><self_collide>true</self_collide></gazebo>"), 0.25, 0.002);
}

TEST(Zoo19RobotBlock, ModelStaticIsAWarningNamingIt) {
  const RobotModel m = load_urdf_string(robot("<gazebo><static>true</static></gazebo>"), "stack");
  const Diagnostic* d = diag(m, "gazebo/static");
  ASSERT_TRUE(d);
  EXPECT_EQ(d->severity, Severity::Warning);
  EXPECT_NE(d->message.find("not simulated"), std::string::npos) << d->message;
}

TEST(Zoo19RobotBlock, OtherModelElementIsANoteNamingIt) {
  const RobotModel m = load_urdf_string(robot("<gazebo><enable_wind>true</enable_wind></gazebo>"), "stack");
  const Diagnostic* d = diag(m, "gazebo/enable_wind");
  ASSERT_TRUE(d);
  EXPECT_EQ(d->severity, Severity::Info);
}

TEST(Zoo19RobotBlock, UnreadableModelSelfCollideIsALoadErrorNamingTheElement) {
  try {
    load_urdf_string(robot("<gazebo><self_collide>maybe</self_collide></gazebo>"), "stack");
    FAIL() << "no error";
  } catch (const LoadError& e) {
    // FILE:LINE: ELEMENT: REASON (the block is on line 11 of the robot text)
    EXPECT_EQ(std::string(e.what()), "stack:11: gazebo/self_collide: 'maybe' is not a boolean (true/false/yes/no/1/0)");
  }
}
