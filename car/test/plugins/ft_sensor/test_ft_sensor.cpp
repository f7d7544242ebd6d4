// libgazebo_ros_ft_sensor.so: the wrench a joint exerts on its child, at rest, worked out by hand.
#include <gtest/gtest.h>

#include "car_sim/world.hpp"
#include "ft_sensor/ft_sensor.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

// A 10 kg base box on the ground; on its top (z = 0.2 m) a revolute joint about z carries a 1 kg arm whose centre
// of mass is at (0, 0.2, 0.05) m in the arm's frame (no collision); spawned after steps_before_spawn steps.
std::unique_ptr<World> arm_world(const std::string& keys, uint64_t steps_before_spawn = 0) {
  const std::string xml = R"(<robot name="arm">
  <link name="base">
    <inertial><mass value="10"/><origin xyz="0 0 0.1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0 0 0.1"/><geometry><box size="0.4 0.4 0.2"/></geometry></collision>
  </link>
  <link name="arm">
    <inertial><mass value="1"/><origin xyz="0 0.2 0.05"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="arm_joint" type="revolute"><parent link="base"/><child link="arm"/><origin xyz="0 0 0.2"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="10" velocity="1"/></joint>
  <gazebo><plugin name="ft" filename="libgazebo_ros_ft_sensor.so"><jointName>arm_joint</jointName><topicName>ft</topicName>)" +
                          keys + R"(</plugin></gazebo>
</robot>)";
  auto w = std::make_unique<World>(empty_world());
  w->step(steps_before_spawn);
  w->spawn(load_urdf_string(xml, "arm.urdf"), "arm", at(0, 0, 0));
  return w;
}

}  // namespace

TEST(FtSensor, HoldsTheArmAgainstGravity) {
  // At rest the joint carries the arm's weight: force on the arm F = +m g z = (0, 0, 9.8) N. Its moment about the
  // arm's origin balances the weight's: tau = r x (m g z) with r = (0, 0.2, 0.05) m: (0.2 * 9.8, 0, 0) =
  // (1.96, 0, 0) N m. The arm frame is the world's (joint at 0, base level).
  auto w = arm_world("<updateRate>100</updateRate>");
  w->set_plugin_active("arm", "ft", true);
  w->step(1000);
  const OutputQueue q = w->take_outputs();
  ASSERT_EQ(q.size(), 100u);
  const auto& o = dynamic_cast<const WrenchOut&>(*q.back());
  EXPECT_NEAR(o.wrench.force.x(), 0.0, 0.01);
  EXPECT_NEAR(o.wrench.force.y(), 0.0, 0.01);
  EXPECT_NEAR(o.wrench.force.z(), 9.8, 0.05);
  EXPECT_NEAR(o.wrench.torque.x(), 1.96, 0.01);
  EXPECT_NEAR(o.wrench.torque.y(), 0.0, 0.01);
  EXPECT_NEAR(o.wrench.torque.z(), 0.0, 0.01);
}

TEST(FtSensor, UnknownJointIsAnError) {
  PluginSpec p;
  p.name = "bad";
  p.filename = "libgazebo_ros_ft_sensor.so";
  p.params = {{"jointName", "nope"}, {"topicName", "x"}};
  auto w = arm_world("");
  try {
    w->attach_plugin("arm", p);
    FAIL() << "no error";
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("gazebo/plugin[bad]/jointName: gazebo_ros_ft_sensor plugin error: jointName: nope does not exist"),
              std::string::npos)
        << e.what();
  }
}

// ft_sensor's last_time_ starts at 0, not at the load: at 10 Hz, spawned at tick 250, its first call (251 ms) is
// more than 0.1 s past 0 and publishes, then every 100 ms: 251, 351, 451.
TEST(FtSensor, ASpawnAfterTimeZeroPublishesAtItsFirstCall) {
  auto w = arm_world("<updateRate>10</updateRate>", 250);
  w->set_plugin_active("arm", "ft", true);
  w->step(250);
  std::vector<uint64_t> ticks;
  for (const auto& o : w->take_outputs()) ticks.push_back(o->tick);
  EXPECT_EQ(ticks, (std::vector<uint64_t>{251, 351, 451}));
}
