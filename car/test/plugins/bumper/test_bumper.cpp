// libgazebo_ros_bumper.so: a frictionless 10 kg box with a contact sensor, resting on the ground and pushed
// against a static wall; values worked out by hand.
#include <gtest/gtest.h>

#include "bumper/bumper.hpp"
#include "car_sim/world.hpp"
#include "force/force.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

std::string bumper_robot(const std::string& collision) {
  return R"(<robot name="bot">
  <link name="body">
    <inertial><mass value="10"/><origin xyz="0 0 0.1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0 0 0.1"/><geometry><box size="0.4 0.4 0.2"/></geometry></collision>
  </link>
  <gazebo reference="body"><mu1>0</mu1><mu2>0</mu2>
    <sensor name="bump" type="contact">
      <update_rate>50</update_rate>
      <contact><collision>)" + collision + R"(</collision></contact>
      <plugin name="bumper" filename="libgazebo_ros_bumper.so"><bumperTopicName>bumps</bumperTopicName></plugin>
    </sensor>
  </gazebo>
  <gazebo><plugin name="push" filename="libgazebo_ros_force.so"><bodyName>body</bodyName><topicName>push</topicName></plugin></gazebo>
</robot>)";
}

// The ground and a static wall 0.2 m thick whose face is at x = 1.0 m.
WorldDescription wall_world() {
  return load_world_string(R"(<?xml version="1.0"?>
<sdf version="1.7"><world name="w">
  <model name="ground_plane"><static>true</static><link name="link"><collision name="collision">
    <geometry><plane><normal>0 0 1</normal><size>100 100</size></plane></geometry></collision></link></model>
  <model name="wall"><static>true</static><pose>1.1 0 0.5 0 0 0</pose><link name="link"><collision name="collision">
    <geometry><box><size>0.2 4 1</size></box></geometry></collision></link></model>
</world></sdf>)");
}

const ContactPair* pair_with(const ContactsOut& o, const std::string& other) {
  for (const auto& s : o.states)
    if (s.collision2 == other) return &s;
  return nullptr;
}

}  // namespace

TEST(Bumper, CollisionNamesMapToLinks) {
  const RobotModel m = load_urdf_string(bumper_robot("body_collision"), "bot.urdf");
  EXPECT_EQ(link_of_collision(m, "body_collision"), "body");
  EXPECT_EQ(link_of_collision(m, "base_fixed_joint_lump__body_collision_1"), "body");
  EXPECT_EQ(link_of_collision(m, "wheel_collision"), "");
}

TEST(Bumper, RestingOnTheGroundCarriesItsWeight) {
  // at rest the ground pushes up with m g = 10 kg * 9.8 m/s^2 = 98 N in total, along +z into the box; 50 Hz over
  // 1 s: 50 messages
  World w(wall_world());
  w.spawn(load_urdf_string(bumper_robot("body_collision"), "bot.urdf"), "bot", at(0, 0, 0));
  w.set_plugin_active("bot", "bumper", true);
  w.step(1000);
  const OutputQueue q = w.take_outputs();
  ASSERT_EQ(q.size(), 50u);
  const auto& o = dynamic_cast<const ContactsOut&>(*q.back());
  const ContactPair* g = pair_with(o, "ground_plane::link");
  ASSERT_NE(g, nullptr);
  EXPECT_EQ(g->collision1, "bot::body::body_collision");
  EXPECT_NEAR(g->total.force.z(), 98.0, 1.0);
  for (const auto& n : g->normals) EXPECT_NEAR(n.z(), 1.0, 1e-6);
  for (double d : g->depths) EXPECT_GE(d, 0.0);
  for (const auto& p : g->positions) EXPECT_NEAR(p.z(), 0.0, 2e-3);  // on the ground
}

TEST(Bumper, PushedAgainstTheWallReportsItsNormalAndName) {
  // 20 N along +x from x = 0: the box's front face (x = 0.2 m) reaches the wall face at x = 1.0 m after
  // 0.8 m = a t^2 / 2 with a = 2 m/s^2, t = 0.89 s. At rest against it (2 s later) the wall pushes back with the
  // 20 N along -x, the normal points out of the wall into the box: (-1, 0, 0), contact points on x = 1.0 m.
  World w(wall_world());
  w.spawn(load_urdf_string(bumper_robot("body_collision"), "bot.urdf"), "bot", at(0, 0, 0));
  Wrench f;
  f.force = Eigen::Vector3d(20, 0, 0);
  dynamic_cast<WrenchCommand*>(w.plugin("bot", "push"))->set_wrench(f);
  w.step(3000);
  w.set_plugin_active("bot", "bumper", true);
  w.step(20);
  const OutputQueue q = w.take_outputs();
  ASSERT_EQ(q.size(), 1u);
  const auto& o = dynamic_cast<const ContactsOut&>(*q.back());
  const ContactPair* c = pair_with(o, "wall::link");
  ASSERT_NE(c, nullptr);
  EXPECT_NEAR(c->total.force.x(), -20.0, 0.5);
  for (const auto& n : c->normals) EXPECT_NEAR(n.x(), -1.0, 1e-6);
  for (const auto& p : c->positions) EXPECT_NEAR(p.x(), 1.0, 2e-3);
  EXPECT_NE(pair_with(o, "ground_plane::link"), nullptr);
}

TEST(Bumper, UnknownCollisionIsAnError) {
  try {
    load_urdf_string(bumper_robot("wheel_collision"), "bot.urdf");
    World w(wall_world());
    w.spawn(load_urdf_string(bumper_robot("wheel_collision"), "bot.urdf"), "bot", at(0, 0, 0));
    FAIL() << "no error";
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("sensor[bump]/contact/collision: 'wheel_collision' is not a collision of the model"),
              std::string::npos)
        << e.what();
  }
}

// On a sensor that is not a contact sensor, upstream's Load logs "Contact sensor parent is not of type
// ContactSensor" and returns: the model loads without the plug-in, with a warning.
TEST(Bumper, OnAnotherSensorTypeThePluginDoesNotLoad) {
  const RobotModel m = load_urdf_string(
      "<robot name='bot'><link name='body'><inertial><mass value='1'/><inertia ixx='0.1' iyy='0.1' izz='0.1' "
      "ixy='0' ixz='0' iyz='0'/></inertial></link><gazebo reference='body'><sensor name='imu' type='imu'>"
      "<plugin name='bumper' filename='libgazebo_ros_bumper.so'/></sensor></gazebo></robot>",
      "bot.urdf");
  const ModelConfig c = resolve_plugins(m);
  EXPECT_TRUE(c.plugins.empty());
  ASSERT_FALSE(c.diagnostics.empty());
  EXPECT_EQ(c.diagnostics.back().code, "plugin-not-loaded");
  EXPECT_EQ(c.diagnostics.back().message,
            "libgazebo_ros_bumper.so needs a sensor of type contact, not 'imu'; the plug-in is not loaded");
}
