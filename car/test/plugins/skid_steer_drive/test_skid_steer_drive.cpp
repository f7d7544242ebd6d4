// libgazebo_ros_skid_steer_drive.so: a four-wheel base in the empty world, values worked out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "car_sim/world.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

// Base box 10 kg; four 0.5 kg wheels of radius 0.05 m (cylinders turned onto y, continuous joints about y) at
// x = +-L/2 = +-0.05 m (wheelbase L = 0.1 m) and y = +-s/2 = +-0.25 m (track s = 0.5 m).
std::string skid_robot(const std::string& keys) {
  std::string wheels;
  const char* names[4] = {"left_front", "right_front", "left_rear", "right_rear"};
  const char* xy[4] = {"0.05 0.25", "0.05 -0.25", "-0.05 0.25", "-0.05 -0.25"};
  for (int i = 0; i < 4; ++i) {
    const std::string n = names[i];
    wheels += "<link name=\"" + n + R"(_wheel"><inertial><mass value="0.5"/><inertia ixx="0.0004" iyy="0.000625" izz="0.0004" ixy="0" ixz="0" iyz="0"/></inertial>
      <collision><origin rpy="1.5708 0 0"/><geometry><cylinder radius="0.05" length="0.04"/></geometry></collision></link>
    <joint name=")" + n + R"(_joint" type="continuous"><parent link="base_footprint"/><child link=")" + n +
              "_wheel\"/><origin xyz=\"" + xy[i] + R"( 0.05"/><axis xyz="0 1 0"/></joint>
)";
  }
  return R"(<robot name="skid">
  <link name="base_footprint">
    <inertial><mass value="10"/><origin xyz="0 0 0.1"/><inertia ixx="0.2" iyy="0.05" izz="0.2" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0 0 0.1"/><geometry><box size="0.2 0.4 0.05"/></geometry></collision>
  </link>
)" + wheels + R"(  <gazebo><plugin name="skid" filename="libgazebo_ros_skid_steer_drive.so">
    <leftFrontJoint>left_front_joint</leftFrontJoint><rightFrontJoint>right_front_joint</rightFrontJoint>
    <leftRearJoint>left_rear_joint</leftRearJoint><rightRearJoint>right_rear_joint</rightRearJoint>
    <wheelSeparation>0.5</wheelSeparation><wheelDiameter>0.1</wheelDiameter>)" +
         keys + R"(</plugin></gazebo>
</robot>)";
}

double yaw_of(const Eigen::Isometry3d& p) { return std::atan2(p.linear()(1, 0), p.linear()(0, 0)); }

}  // namespace

TEST(SkidSteer, TurnsOnTheSpotAtTheSlipLimitedRate) {
  // Command v = 0, w = 1 rad/s: right wheels at vr = +w s/2 = 0.25 m/s, left at vl = -0.25 m/s, so the
  // kinematic rate is (vr - vl) / s = 1 rad/s. The wheels also slide sideways while the base turns; with equal
  // normal loads and isotropic Coulomb friction the torques about the centre balance when each wheel's slip
  // ((w - W) s/2 along the wheel, W L/2 across) satisfies s (w - W) s/2 = L W L/2, i.e.
  //   W = w s^2 / (s^2 + L^2) = 0.25 / 0.26 = 0.9615 rad/s   (slip 3.85 % below (vr - vl)/s).
  // Stated tolerance: within 5 % of (vr - vl)/s, and within 0.02 rad/s of the slip-limited 0.9615 rad/s; the
  // centre stays within 1 cm of where it started.
  World w(empty_world());
  w.spawn(load_urdf_string(skid_robot("<torque>20</torque>"), "skid.urdf"), "skid", at(0, 0, 0));
  w.set_cmd_vel("skid", 0.0, 1.0);
  w.step(1000);  // spin up
  const double yaw0 = yaw_of(w.model_state("skid").pose);
  w.step(1000);
  double dyaw = yaw_of(w.model_state("skid").pose) - yaw0;
  if (dyaw < 0) dyaw += 2 * M_PI;
  const double rate = dyaw / 1.0;
  std::printf("skid steer on the spot: %.4f rad/s for a kinematic 1 rad/s\n", rate);
  EXPECT_NEAR(rate, 1.0, 0.05);
  EXPECT_NEAR(rate, 0.25 / 0.26, 0.02);
  EXPECT_LT(w.model_state("skid").pose.translation().head<2>().norm(), 0.01);
}

TEST(SkidSteer, OdometryAtUpdateRateFromTheWorld) {
  // updateRate 50 Hz over 1 s: 50 messages; driving straight at 0.2 m/s the last one reads about 0.2 m/s
  World w(empty_world());
  w.spawn(load_urdf_string(skid_robot("<updateRate>50</updateRate>"), "skid.urdf"), "skid", at(0, 0, 0));
  w.set_cmd_vel("skid", 0.2, 0.0);
  w.step(1000);
  const OutputQueue out = w.take_outputs();
  ASSERT_EQ(out.size(), 50u);
  const auto& o = dynamic_cast<const OdometryOut&>(*out.back());
  EXPECT_NEAR(o.linear.x(), 0.2, 0.01);
  EXPECT_EQ(o.joints.size(), 4u);
  EXPECT_EQ(o.joints[0].name, "left_front_joint");
}

TEST(SkidSteer, MissingJointIsAnError) {
  try {
    World w(empty_world());
    std::string xml = skid_robot("");
    const std::string key = "<leftRearJoint>left_rear_joint</leftRearJoint>";
    xml.replace(xml.find(key), key.size(), "<leftRearJoint>nope</leftRearJoint>");
    w.spawn(load_urdf_string(xml, "skid.urdf"), "skid", at(0, 0, 0));
    FAIL() << "no error";
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("gazebo/plugin[skid]/leftRearJoint: joint 'nope' not found"), std::string::npos)
        << e.what();
  }
}

// At 30 Hz the odometry follows UpdateChild's rule (test_update_clock.cpp): ticks 33, 66, 99, 133, 166, 199.
TEST(SkidSteer, ThirtyHertzUpdatesByUpdateChildsClock) {
  World w(empty_world());
  w.spawn(load_urdf_string(skid_robot("<updateRate>30</updateRate>"), "skid.urdf"), "skid", at(0, 0, 0));
  w.step(200);
  std::vector<uint64_t> ticks;
  for (const auto& o : w.take_outputs()) ticks.push_back(o->tick);
  EXPECT_EQ(ticks, (std::vector<uint64_t>{33, 66, 99, 133, 166, 199}));
}

// publishOdometry fills position x and y only (z stays 0 in the message); the TF carries the pose's z.
TEST(SkidSteer, OdometryMessageIsPlanar) {
  World w(empty_world());
  w.spawn(load_urdf_string(skid_robot(""), "skid.urdf"), "skid", at(0, 0, 0));
  const PluginInfo p = w.plugins()[0];
  ASSERT_EQ(p.outputs.size(), 1u);
  EXPECT_TRUE(p.outputs[0].planar_position);
}
