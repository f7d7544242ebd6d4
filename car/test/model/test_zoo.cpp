// The zoo robots (test/data/zoo/) in the core, without ROS: nothing refused, what is lumped or dropped, the
// world anchor holding, the mesh-only robot resting at the height its mesh gives. Values worked out by hand.
#include <gtest/gtest.h>

#include "car_sim/description.hpp"
#include "car_sim/world.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

bool has(const RobotModel& m, const std::string& code, const std::string& element) {
  for (const auto& d : m.diagnostics)
    if (d.code == code && d.element == element) return true;
  return false;
}

// A zoo URDF with package://car/test/data/zoo/ URIs made relative to the file (no ROS package path in gtest).
RobotModel zoo(const std::string& file) {
  std::string xml = read_text("test/data/zoo/" + file);
  const std::string pkg = "package://car/test/data/zoo/";
  for (auto at = xml.find(pkg); at != std::string::npos; at = xml.find(pkg)) xml.replace(at, pkg.size(), "");
  return load_urdf_string(xml, data_path("zoo/" + file));
}

}  // namespace

TEST(Zoo, SensorBotMasslessSensorLinksAreLumpedNotRefused) {
  const RobotModel m = zoo("sensor_bot.urdf");
  ASSERT_EQ(m.links.size(), 1u);
  EXPECT_TRUE(has(m, "link-lumped", "link[camera_link]"));
  EXPECT_TRUE(has(m, "link-lumped", "link[imu_link]"));
  // the camera sensor now on base_link at camera_joint's origin (0.1, 0, 0.06)
  ASSERT_EQ(m.sensors.size(), 1u);
  EXPECT_EQ(m.sensors[0].link, "base_link");
  EXPECT_NEAR(m.sensors[0].pose.translation().z(), 0.06, 1e-12);
  // mass stays base_link's 1 kg: the lumped links have none
  EXPECT_DOUBLE_EQ(m.links[0].inertial->mass, 1.0);
}

TEST(Zoo, CasterBotCasterLumpedWithItsOwnFriction) {
  const RobotModel m = zoo("caster_bot.urdf");
  EXPECT_TRUE(has(m, "link-lumped", "link[caster_link]"));
  const Link* b = m.find_link("base_link");
  ASSERT_EQ(b->collisions.size(), 2u);
  // <mu1 value="0.1"/> (attribute form) and <mu2>0.1</mu2> apply to the caster's box only
  EXPECT_EQ(m.surface(*b, b->collisions[1]).mu1, std::optional<double>(0.1));
  EXPECT_EQ(m.surface(*b, b->collisions[1]).mu2, std::optional<double>(0.1));
  EXPECT_FALSE(m.surface(*b, b->collisions[0]).mu1.has_value());
  // mass 2 + 0.05 kg
  EXPECT_DOUBLE_EQ(b->inertial->mass, 2.05);
}

TEST(Zoo, MeshBotRestsAtTheHeightItsMeshGives) {
  World w(empty_world());
  w.spawn(zoo("mesh_bot.urdf"), "mesh_bot", at(0, 0, 0) * Eigen::Translation3d(0, 0, 0.2));
  w.step(2000);  // 2 s: dropped 0.15 m, settled
  // the STL box is 0.1 m high, centred on base_link: its bottom at -0.05 m, so base_link rests at z = 0.05 m,
  // plus Bullet's 0.0005 m hull margin (physics_impl.hpp kMargin): 0.0505 m, within 2 mm
  EXPECT_NEAR(w.link_pose("mesh_bot", "base_link").translation().z(), 0.0505, 0.002);
}

TEST(Zoo, ArmFixedToTheWorldHoldsItsBase) {
  const RobotModel m = zoo("arm.urdf");
  EXPECT_TRUE(m.anchored());
  EXPECT_TRUE(has(m, "world-anchor", "joint[world_fix]"));
  World w(empty_world());
  w.spawn(m, "arm", at(1.0, 2.0, 0.0));
  w.step(1000);
  // base = spawn pose * world_fix origin = (1, 2, 0.5), held there against gravity
  const Eigen::Vector3d p = w.link_pose("arm", "base").translation();
  EXPECT_NEAR(p.x(), 1.0, 1e-9);
  EXPECT_NEAR(p.y(), 2.0, 1e-9);
  EXPECT_NEAR(p.z(), 0.5, 1e-9);
}

TEST(Zoo, RevoluteJointFromWorldKeepsItsPivot) {
  // a 1 kg point-like bob 0.3 m from a pivot 1 m above the spawn point, on a revolute joint (axis y) from `world`:
  // the model is anchored, the bob swings under gravity, and the pivot (the bob link's origin, on the joint
  // axis) stays at (0, 0, 1) while the bob's com leaves its start (0.3, 0, 1)
  const RobotModel m = load_urdf_string(
      "<robot name='pendulum'><link name='world'/>"
      "<link name='bob'><inertial><origin xyz='0.3 0 0'/><mass value='1'/>"
      "<inertia ixx='0.0001' ixy='0' ixz='0' iyy='0.0001' iyz='0' izz='0.0001'/></inertial></link>"
      "<joint name='pivot' type='revolute'><parent link='world'/><child link='bob'/><origin xyz='0 0 1'/>"
      "<axis xyz='0 1 0'/><limit lower='-3' upper='3' effort='0' velocity='10'/></joint></robot>");
  EXPECT_TRUE(m.anchored());
  World w(empty_world());
  w.spawn(m, "pendulum", at(0, 0, 0));
  w.step(200);  // 0.2 s
  const Eigen::Isometry3d bob = w.link_pose("pendulum", "bob");
  EXPECT_NEAR(bob.translation().x(), 0.0, 1e-6);
  EXPECT_NEAR(bob.translation().y(), 0.0, 1e-6);
  EXPECT_NEAR(bob.translation().z(), 1.0, 1e-6);
  // it swung: after 0.2 s the arm has turned down (com below the pivot height)
  EXPECT_LT((bob * Eigen::Vector3d(0.3, 0, 0)).z(), 1.0 - 0.05);
}
