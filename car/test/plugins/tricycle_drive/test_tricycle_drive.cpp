// libgazebo_ros_tricycle_drive.so: a steered front wheel and two free rear wheels; values worked out by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "car_sim/world.hpp"
#include "test_util.hpp"
#include "tricycle_drive/tricycle_drive.hpp"

using namespace car_sim;

namespace {

std::string wheel(const std::string& name, const std::string& parent, const std::string& xyz) {
  return "<link name=\"" + name + R"("><inertial><mass value="0.5"/><inertia ixx="0.0004" iyy="0.000625" izz="0.0004" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin rpy="1.5708 0 0"/><geometry><cylinder radius="0.05" length="0.03"/></geometry></collision></link>
  <joint name=")" + name + R"(_joint" type="continuous"><parent link=")" + parent + "\"/><child link=\"" + name +
         "\"/><origin xyz=\"" + xyz + R"("/><axis xyz="0 1 0"/></joint>
)";
}

// Wheelbase L = 0.5 m: front wheel (radius 0.05 m) steered at x = 0.3 m, rear wheels at x = -0.2 m, y = +-0.2 m.
std::string tricycle(const std::string& keys) {
  return R"(<robot name="tri">
  <link name="base_link">
    <inertial><mass value="10"/><origin xyz="0 0 0.1"/><inertia ixx="0.1" iyy="0.3" izz="0.3" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0 0 0.1"/><geometry><box size="0.6 0.3 0.05"/></geometry></collision>
  </link>
  <link name="steer"><inertial><mass value="0.2"/><inertia ixx="0.0001" iyy="0.0001" izz="0.0001" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="front_steering_joint" type="revolute"><parent link="base_link"/><child link="steer"/><origin xyz="0.3 0 0.05"/>
    <axis xyz="0 0 1"/><limit lower="-1.6" upper="1.6" effort="10" velocity="5"/></joint>
)" + wheel("front_wheel", "steer", "0 0 0") +
         wheel("left_wheel", "base_link", "-0.2 0.2 0.05") + wheel("right_wheel", "base_link", "-0.2 -0.2 0.05") +
         R"(  <gazebo><plugin name="tri" filename="libgazebo_ros_tricycle_drive.so">
    <actuatedWheelDiameter>0.1</actuatedWheelDiameter><encoderWheelDiameter>0.1</encoderWheelDiameter>
    <encoderWheelSeparation>0.4</encoderWheelSeparation><wheelTorque>20</wheelTorque>)" +
         keys + R"(</plugin></gazebo>
</robot>)";
}

double yaw_of(const Eigen::Isometry3d& p) { return std::atan2(p.linear()(1, 0), p.linear()(0, 0)); }

}  // namespace

TEST(Tricycle, WheelSpeedRampAsUpstream) {
  EXPECT_DOUBLE_EQ(tricycle_wheel_speed(0.0, 10.0, 0.0, 0.0, 0.01, 0.01), 10.0);   // no ramp
  EXPECT_DOUBLE_EQ(tricycle_wheel_speed(0.0, 10.0, 100.0, 50.0, 0.01, 0.01), 0.5);  // speeding up: decel * dt
  EXPECT_DOUBLE_EQ(tricycle_wheel_speed(10.0, 0.0, 100.0, 50.0, 0.01, 0.01), 9.0);  // slowing: accel * dt
  EXPECT_DOUBLE_EQ(tricycle_wheel_speed(9.995, 10.0, 100.0, 50.0, 0.01, 0.01), 9.995);  // within tolerance
}

TEST(Tricycle, TurnsAtTheBicycleRate) {
  // front wheel surface speed v = 0.5 m/s steered delta = 0.3 rad, rear wheels rolling without side slip: the
  // bicycle model's yaw rate is v sin(delta) / L = 0.5 * 0.29552 / 0.5 = 0.29552 rad/s (tolerance 3 %), and the
  // steering joint sits at 0.3 rad
  World w(empty_world());
  w.spawn(load_urdf_string(tricycle(""), "tri.urdf"), "tri", at(0, 0, 0));
  Twist t;
  t.linear.x() = 0.5;
  t.angular.z() = 0.3;
  w.set_cmd_vel("tri", t);
  w.step(1000);
  const double yaw0 = yaw_of(w.model_state("tri").pose);
  w.step(2000);
  const double rate = (yaw_of(w.model_state("tri").pose) - yaw0) / 2.0;
  EXPECT_NEAR(rate, std::sin(0.3), 0.03 * std::sin(0.3));
  // the steering joint must be among the joint states: a renamed or missing joint fails here, not silently
  bool steering_found = false;
  for (const auto& j : w.joint_states("tri")) {
    if (j.name != "front_steering_joint") continue;
    steering_found = true;
    EXPECT_NEAR(j.position, 0.3, 0.01);
  }
  EXPECT_TRUE(steering_found) << "no joint state named front_steering_joint";
}

TEST(Tricycle, EncoderOdometryTurnsTheRightWay) {
  // turning left (steering +0.3 rad) the encoder heading grows (upstream's sign error fixed): after 3 s the
  // odometry yaw agrees with the world's within 5 %
  World w(empty_world());
  w.spawn(load_urdf_string(tricycle("<odometrySource>encoder</odometrySource>"), "tri.urdf"), "tri", at(0, 0, 0));
  Twist t;
  t.linear.x() = 0.5;
  t.angular.z() = 0.3;
  w.set_cmd_vel("tri", t);
  w.step(3000);
  const OutputQueue q = w.take_outputs();
  ASSERT_EQ(q.size(), 300u);  // 100 Hz
  const auto& o = dynamic_cast<const OdometryOut&>(*q.back());
  const double truth = yaw_of(w.model_state("tri").pose);
  EXPECT_GT(truth, 0.5);
  EXPECT_NEAR(yaw_of(o.pose), truth, 0.05 * truth);
}

// Spawned 2 s into the run, 2 m above the ground (it falls for the 0.08 s of the test, so the wheel spins freely
// and its motor reaches each target), wheelAcceleration 20 rad/s^2 (speeding up uses wheelDeceleration, by default
// the same): upstream's first update comes 0.011 s after the load and each update adds 20 * 0.011 = 0.22 rad/s to
// the wheel's current speed (docs/COMPAT-plugins.md), toward 0.5 m/s / 0.05 m = 10 rad/s. So after update k the
// wheel turns at 0.22 k rad/s: 1.76 after 8 (the period alone would give 0.20 k; timing from tick 0 would make the
// first step 20 * 2.01 s, the whole 10 rad/s at once).
TEST(Tricycle, RampsByAccelTimesUpstreamsSecondsSinceTheLoad) {
  World w(empty_world());
  w.step(2000);
  Eigen::Isometry3d high = at(0, 0, 0);
  high.translation().z() = 2.0;
  w.spawn(load_urdf_string(tricycle("<wheelAcceleration>20</wheelAcceleration>"), "tri.urdf"), "tri", high);
  Twist t;
  t.linear.x() = 0.5;
  w.set_cmd_vel("tri", t);
  // [rad/s] the front wheel's speed after each of 9 periods of 10 steps (update k acts from period k + 1 on)
  std::vector<double> speed;
  for (int k = 1; k <= 9; ++k) {
    w.step(10);
    for (const auto& j : w.joint_states("tri"))
      if (j.name == "front_wheel_joint") speed.push_back(j.velocity);
  }
  ASSERT_EQ(speed.size(), 9u);
  for (int k = 1; k <= 8; ++k) EXPECT_NEAR(speed[k], 0.22 * k, 1e-3) << "after update " << k;
}

// At 30 Hz the odometry follows UpdateChild's rule (test_update_clock.cpp): ticks 33, 66, 99, 133, 166, 199.
TEST(Tricycle, ThirtyHertzUpdatesByUpdateChildsClock) {
  World w(empty_world());
  w.spawn(load_urdf_string(tricycle("<updateRate>30</updateRate>"), "tri.urdf"), "tri", at(0, 0, 0));
  w.step(200);
  std::vector<uint64_t> ticks;
  for (const auto& o : w.take_outputs()) ticks.push_back(o->tick);
  EXPECT_EQ(ticks, (std::vector<uint64_t>{33, 66, 99, 133, 166, 199}));
}

// car restarts the tricycle's clock at reset_world too, with its ramp's own clock (docs/COMPAT-plugins.md "After a
// reset"; upstream keeps it): 30 Hz updates from a reset at tick 150 come at 150 + 33, 66, as from a spawn there.
TEST(Tricycle, RestartsItsClockAtAResetThatKeepsTime) {
  World w(empty_world());
  w.spawn(load_urdf_string(tricycle("<updateRate>30</updateRate>"), "tri.urdf"), "tri", at(0, 0, 0));
  w.step(150);
  w.take_outputs();
  w.reset_poses();
  w.step(70);
  std::vector<uint64_t> ticks;
  for (const auto& o : w.take_outputs()) ticks.push_back(o->tick);
  EXPECT_EQ(ticks, (std::vector<uint64_t>{183, 216}));
}

// A negative updateRate: upstream's update_period_ is 0 (every step); car the same, with a warning.
TEST(Tricycle, NegativeUpdateRateIsEveryStepAndWarned) {
  World w(empty_world());
  w.spawn(load_urdf_string(tricycle("<updateRate>-5</updateRate>"), "tri.urdf"), "tri", at(0, 0, 0));
  w.step(10);
  EXPECT_EQ(w.take_outputs().size(), 10u);
  std::vector<std::string> messages;
  for (const Diagnostic& d : w.robot("tri").config.diagnostics)
    if (d.element == "gazebo/plugin[tri]/updateRate") messages.push_back(d.message);
  EXPECT_EQ(messages, std::vector<std::string>{"<updateRate> -5 is not > 0: the plug-in updates every step, as upstream"});
}

// publishWheelJointState: the four joints with an effort each, GetForce(0) upstream: what SetForce applied in the
// step, which nothing does to these joints (the driven two are velocity motors): zeros, with the port asking for
// them.
TEST(Tricycle, WheelJointStatesCarryZeroEfforts) {
  World w(empty_world());
  w.spawn(load_urdf_string(tricycle("<publishWheelJointState>true</publishWheelJointState>"), "tri.urdf"), "tri",
          at(0, 0, 0));
  Twist t;
  t.linear.x() = 0.5;
  w.set_cmd_vel("tri", t);
  w.step(100);
  bool port = false;
  for (const auto& p : w.plugins())
    for (const auto& o : p.outputs)
      if (o.type == sample_type<JointStatesSample>()) port = o.with_effort;
  EXPECT_TRUE(port);
  const auto outs = w.take_outputs();
  ASSERT_FALSE(outs.empty());
  const std::optional<JointStatesSample> s = outs.back()->sample_of<JointStatesSample>();
  ASSERT_TRUE(s);
  ASSERT_NE(s->efforts, nullptr);
  EXPECT_EQ(*s->efforts, std::vector<double>(4, 0.0));
  ASSERT_EQ(s->joints->size(), 4u);
}
