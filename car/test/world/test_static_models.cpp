// Moving a static world model with set_model_state, as Gazebo 11 does (docs/COMPAT.md set_model_state): its
// collisions take the new pose, its twist is ignored, a plane stays where it was loaded, nothing asleep is woken,
// nested models move along, and a reset puts it back.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include "car_sim/world.hpp"
#include "laser/laser.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

// A ground plane; a static platform (1 x 1 x 0.2 m) at (5, 5, 0.1), far from everything; a static wall
// (0.2 x 2 x 1 m) at (0, 10, 0.5); a 1 kg crate (0.2 m cube) at (0, 0, 1), falling from the first step.
const char* kWorld = R"(<?xml version="1.0"?>
<sdf version="1.7">
  <world name="w">
    <model name="ground_plane">
      <static>true</static>
      <link name="link">
        <collision name="c"><geometry><plane><normal>0 0 1</normal><size>100 100</size></plane></geometry></collision>
      </link>
    </model>
    <model name="platform">
      <static>true</static>
      <pose>5 5 0.1 0 0 0</pose>
      <link name="link">
        <collision name="c"><geometry><box><size>1 1 0.2</size></box></geometry></collision>
      </link>
    </model>
    <model name="wall">
      <static>true</static>
      <pose>0 10 0.5 0 0 0</pose>
      <link name="link">
        <pose>0 0 0.25 0 0 0</pose>
        <collision name="c"><geometry><box><size>0.2 2 1</size></box></geometry></collision>
      </link>
    </model>
    <model name="crate">
      <pose>0 0 1 0 0 0</pose>
      <link name="link">
        <inertial><mass>1</mass><inertia><ixx>0.00667</ixx><iyy>0.00667</iyy><izz>0.00667</izz></inertia></inertial>
        <collision name="c"><geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision>
      </link>
    </model>
  </world>
</sdf>)";

ModelState placed(double x, double y, double z, double yaw = 0.0) {
  ModelState s;
  s.pose = at(x, y, yaw);
  s.pose.translation().z() = z;
  return s;
}

std::string bits(const ModelState& s) {
  std::string out(sizeof(double) * 19, '\0');
  std::memcpy(&out[0], s.pose.matrix().data(), sizeof(double) * 16);
  std::memcpy(&out[sizeof(double) * 16], s.linear.data(), sizeof(double) * 3);
  return out;
}

}  // namespace

// gazebo_ros's SetModelState on a static model: Model::SetWorldPose moves it; SetLinearVel and SetAngularVel reach
// no body (a static link has none), so it stays at rest. Its links move with it.
TEST(StaticModels, AStaticModelTakesThePoseAndIgnoresTheTwist) {
  World w(load_world_string(kWorld, "static.world"));
  ModelState target = placed(1.0, 2.0, 0.5, 0.3);
  target.linear = Eigen::Vector3d(1, 0, 0);
  target.angular = Eigen::Vector3d(0, 0, 1);
  w.set_model_state("wall", target);
  w.step(10);
  const ModelState s = w.model_state("wall");
  EXPECT_TRUE(s.pose.isApprox(target.pose, 1e-15));
  EXPECT_EQ(s.linear, Eigen::Vector3d::Zero());
  EXPECT_EQ(s.angular, Eigen::Vector3d::Zero());
  // the link 0.25 m above the model frame
  const Eigen::Vector3d link = w.link_state(w.find_link("wall::link")).pose.translation();
  EXPECT_NEAR(link.x(), 1.0, 1e-12);
  EXPECT_NEAR(link.y(), 2.0, 1e-12);
  EXPECT_NEAR(link.z(), 0.75, 1e-12);
}

// The platform moved under the falling crate (top face at z = 0.4 m) holds it up: the crate rests with its centre
// 0.1 m above that face, not on the ground (0.1 m). Bullet's contacts rest within a millimetre of touching.
TEST(StaticModels, AMovedStaticModelHoldsUpWhatFallsOnIt) {
  World w(load_world_string(kWorld, "static.world"));
  w.set_model_state("platform", placed(0.0, 0.0, 0.3));
  w.step(1500);
  EXPECT_NEAR(w.model_state("crate").pose.translation().z(), 0.5, 1e-3);
}

// ODE's plane is not placeable (ODEPlaneShape::CreatePlane), so ODECollision::OnPoseChange leaves it: the ground
// plane reports its new pose, and the crate still lands where it was loaded (centre 0.1 m above z = 0).
TEST(StaticModels, APlaneStaysWhereItWasLoaded) {
  World w(load_world_string(kWorld, "static.world"));
  w.set_model_state("ground_plane", placed(0.0, 0.0, 0.5));
  w.step(1500);
  EXPECT_DOUBLE_EQ(w.model_state("ground_plane").pose.translation().z(), 0.5);
  EXPECT_NEAR(w.model_state("crate").pose.translation().z(), 0.1, 1e-3);
}

// Gazebo's ODEPhysics::Collide skips a static geom and a disabled body, so a static model moved into a sleeping
// object leaves it where it sleeps, bit for bit, until something awake touches it (car's islands: the same rule).
TEST(StaticModels, ASleepingObjectIsNotWokenByAStaticModelMovedOntoIt) {
  World w(load_world_string(kWorld, "static.world"));
  w.step(4000);  // landed by 0.5 s, asleep 2 s later
  const ModelState asleep = w.model_state("crate");
  ASSERT_NEAR(asleep.pose.translation().z(), 0.1, 1e-3);
  w.set_model_state("platform", placed(0.0, 0.0, 0.1));
  w.step(100);
  EXPECT_EQ(bits(w.model_state("crate")), bits(asleep));
}

namespace {

// The seed car at the origin, facing +x, its lidar (5.5 Hz, range noise 0.01 m) on; the crate out of its way.
void add_car_with_lidar(World& w) {
  w.remove("crate");
  w.spawn(load_urdf_string(read_text("test/data/car_camera_lidar04.urdf"), "car04"), "mycar", at(0, 0, 0));
  w.set_sensor_active("mycar", "gazebo_rplidar", true);
}

// Steps n steps; the last scan's ray 180 [m] (yaw 3/359 rad, cos = 1 - 3.5e-5: straight ahead), NaN when no scan
// came in those steps.
double range_ahead(World& w, uint64_t n) {
  w.step(n);
  const std::vector<LaserScanOut> scans = w.take_outputs<LaserScanOut>();
  return scans.empty() ? std::nan("") : scans.back().ranges[180];
}

// Where the wall moved to (2, 0, 0) faces the car: its near face at x = 2 - 0.1 = 1.9 m, from the laser link [m].
double to_wall(const World& w) { return 1.9 - w.link_pose("mycar", "laser").translation().x(); }

}  // namespace

// The lidar sees the wall where it was moved, in a scene it had already swept.
TEST(StaticModels, ALidarSeesAStaticModelWhereItWasMoved) {
  World w(load_world_string(kWorld, "static.world"));
  add_car_with_lidar(w);
  const double before = range_ahead(w, 200);
  ASSERT_FALSE(std::isnan(before)) << "no scan in 0.2 s of a 5.5 Hz lidar";
  EXPECT_TRUE(std::isinf(before));  // nothing ahead
  w.set_model_state("wall", placed(2.0, 0.0, 0.0));
  const double after = range_ahead(w, 400);
  ASSERT_FALSE(std::isnan(after)) << "no scan in 0.4 s of a 5.5 Hz lidar";
  EXPECT_NEAR(after, to_wall(w), 0.05);
}

// The ray scene is built afresh when a robot is spawned: a static model moved before that is built where it is now.
TEST(StaticModels, ALidarSpawnedAfterTheMoveSeesTheStaticModelWhereItIs) {
  World w(load_world_string(kWorld, "static.world"));
  w.set_model_state("wall", placed(2.0, 0.0, 0.0));
  add_car_with_lidar(w);
  const double r = range_ahead(w, 400);
  ASSERT_FALSE(std::isnan(r)) << "no scan in 0.4 s of a 5.5 Hz lidar";
  EXPECT_NEAR(r, to_wall(w), 0.05);
}

// delete_model takes a static model out of the ray scene as well as out of the physics: the wall's echo goes.
TEST(StaticModels, ALidarNoLongerSeesADeletedStaticModel) {
  World w(load_world_string(kWorld, "static.world"));
  add_car_with_lidar(w);
  w.set_model_state("wall", placed(2.0, 0.0, 0.0));
  const double before = range_ahead(w, 200);
  ASSERT_FALSE(std::isnan(before)) << "no scan in 0.2 s of a 5.5 Hz lidar";
  ASSERT_TRUE(std::isfinite(before));
  w.remove("wall");
  const double after = range_ahead(w, 400);
  ASSERT_FALSE(std::isnan(after)) << "no scan in 0.4 s of a 5.5 Hz lidar";
  EXPECT_TRUE(std::isinf(after));
}

// reset_world (Model::Reset) puts a moved static model back at its load pose, collisions with it: the crate falls
// past where the platform was moved to and lands on the ground.
TEST(StaticModels, AResetPutsAMovedStaticModelBack) {
  World w(load_world_string(kWorld, "static.world"));
  w.set_model_state("platform", placed(0.0, 0.0, 0.3));
  w.reset_poses();
  EXPECT_TRUE(w.model_state("platform").pose.isApprox(placed(5.0, 5.0, 0.1).pose, 1e-15));
  w.step(1500);
  EXPECT_NEAR(w.model_state("crate").pose.translation().z(), 0.1, 1e-3);
}

namespace {

// rack: a dynamic model with no link of its own, holding a static shelf 0.5 m above its frame; cart: a dynamic
// model holding a static sign 1 m above it.
const char* kNested = R"(<?xml version="1.0"?>
<sdf version="1.7">
  <world name="w">
    <model name="rack">
      <pose>1 0 0 0 0 0</pose>
      <model name="shelf">
        <static>true</static>
        <pose>0 0 0.5 0 0 0</pose>
        <link name="l">
          <collision name="c"><geometry><box><size>1 1 0.1</size></box></geometry></collision>
        </link>
      </model>
    </model>
    <model name="cart">
      <pose>0 3 0 0 0 0</pose>
      <link name="body">
        <gravity>false</gravity>
        <inertial><mass>1</mass><inertia><ixx>0.1</ixx><iyy>0.1</iyy><izz>0.1</izz></inertia></inertial>
        <collision name="c"><geometry><box><size>0.5 0.5 0.5</size></box></geometry></collision>
      </link>
      <model name="sign">
        <static>true</static>
        <pose>0 0 1 0 0 0</pose>
        <link name="l">
          <collision name="c"><geometry><box><size>0.1 0.5 0.5</size></box></geometry></collision>
        </link>
      </model>
    </model>
  </world>
</sdf>)";

}  // namespace

// Entity::SetWorldPoseModel moves every nested model with its parent, a static one too.
TEST(StaticModels, ADynamicModelMovesItsStaticNestedModel) {
  World w(load_world_string(kNested, "nested.world"));
  w.set_model_state("cart", placed(2.0, 3.0, 0.0));
  const Eigen::Vector3d sign = w.model_state("cart::sign").pose.translation();
  EXPECT_NEAR(sign.x(), 2.0, 1e-12);
  EXPECT_NEAR(sign.y(), 3.0, 1e-12);
  EXPECT_NEAR(sign.z(), 1.0, 1e-12);
}

// A model whose only links are a static nested model's follows that model's link (its canonical link,
// Model::LoadLinks): moved, it reports the pose it was given, and its shelf keeps the 0.5 m offset.
TEST(StaticModels, AModelOfOnlyStaticNestedModelsReportsItsNewPose) {
  World w(load_world_string(kNested, "nested.world"));
  w.set_model_state("rack", placed(-1.0, 2.0, 0.0));
  const Eigen::Vector3d rack = w.model_state("rack").pose.translation();
  const Eigen::Vector3d shelf = w.model_state("rack::shelf").pose.translation();
  EXPECT_NEAR(rack.x(), -1.0, 1e-12);
  EXPECT_NEAR(rack.y(), 2.0, 1e-12);
  EXPECT_NEAR(rack.z(), 0.0, 1e-12);
  EXPECT_NEAR(shelf.z(), 0.5, 1e-12);
}
