// The core world: values worked out by hand for the seed car in box_house (worlds/box_house.world).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include <omp.h>

#include "car_sim/world.hpp"
#include "laser/laser.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

const RobotModel& car() {
  static const RobotModel m = load_urdf_string(read_text("test/data/car_camera_lidar04.urdf"), "car04");
  return m;
}

std::unique_ptr<World> box_house_with_car(double x = 0.0, double y = 0.0, double yaw = 0.0) {
  auto w = std::make_unique<World>(load_world_file(std::string(CAR_SOURCE_DIR) + "/worlds/box_house.world"));
  w->spawn(car(), "mycar", at(x, y, yaw));
  return w;
}

std::string load_error(const std::string& rel) {
  try {
    load_world_file(data_path(rel));
  } catch (const LoadError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(WorldLoad, BoxHouseModelsStepAndGravity) {
  const WorldDescription d = load_world_file(std::string(CAR_SOURCE_DIR) + "/worlds/box_house.world");
  EXPECT_DOUBLE_EQ(d.step_size, 0.001);
  EXPECT_DOUBLE_EQ(d.gravity.z(), -9.8);
  ASSERT_EQ(d.models.size(), 8u);
  EXPECT_TRUE(d.find_model("box_house")->is_static);
  EXPECT_FALSE(d.find_model("unit_box")->is_static);
  EXPECT_EQ(d.find_model("box_house")->links.size(), 4u);
}

TEST(WorldLoad, StatePosesWinOverModelPoses) {
  // unit_box_0 is declared after <state>, at y = -2.00354; the state says y = -2.00353, z = 0.499995
  const WorldDescription d = load_world_file(std::string(CAR_SOURCE_DIR) + "/worlds/box_house.world");
  const auto& p = d.find_model("unit_box_0")->pose.translation();
  EXPECT_DOUBLE_EQ(p.y(), -2.00353);
  EXPECT_DOUBLE_EQ(p.z(), 0.499995);
}

TEST(WorldLoad, GroundFrictionFromSurface) {
  const WorldDescription d = load_world_file(std::string(CAR_SOURCE_DIR) + "/worlds/box_house.world");
  const auto& c = d.find_model("ground_plane")->links[0].collisions[0];
  EXPECT_EQ(c.shape.type, ShapeType::Plane);
  EXPECT_DOUBLE_EQ(c.friction.mu, 100.0);
  EXPECT_DOUBLE_EQ(c.friction.mu2, 50.0);
}

TEST(WorldLoad, WallPoseFromModelAndLink) {
  // Wall_2: model at (-1.97643, 0.059964), link at (6.425, 0) turned by -pi/2 -> x = 4.44857
  const WorldDescription d = load_world_file(std::string(CAR_SOURCE_DIR) + "/worlds/box_house.world");
  const auto* m = d.find_model("box_house");
  const Eigen::Isometry3d T = m->pose * m->links[1].pose;
  EXPECT_NEAR(T.translation().x(), 4.44857, 1e-5);
  EXPECT_NEAR(T.translation().y(), 0.059964, 1e-5);
}

TEST(WorldPhysics, FreeFallFollowsSymplecticEuler) {
  World w(load_world_file(data_path("freefall.world")));
  w.step(250);  // 0.5 s at dt 0.002
  // v_n = -g n dt, z_n = z0 - g dt^2 n (n + 1) / 2
  const double n = 250, dt = 0.002, g = 5.0;
  EXPECT_NEAR(w.model_state("ball").pose.translation().z(), 1.0 - g * dt * dt * n * (n + 1) / 2, 1e-9);
  EXPECT_NEAR(w.model_state("ball").linear.z(), -g * n * dt, 1e-9);
  EXPECT_DOUBLE_EQ(w.time(), 0.5);
}

TEST(WorldPhysics, CarRestsOnWheelsAndCasters) {
  auto w = box_house_with_car();
  w->step(2000);
  // base_link: wheel radius 0.0325 + (base_length / 2 + lidi) - wheel_radius... = 0.055 above the ground
  EXPECT_NEAR(w->link_pose("mycar", "base_link").translation().z(), 0.055, 0.002);
}

TEST(WorldPhysics, ZeroCommandDriftsLessThanAMillimetreIn10s) {
  auto w = box_house_with_car();
  w->step(1000);
  const Eigen::Vector3d p0 = w->model_state("mycar").pose.translation();
  w->step(10000);
  EXPECT_LT((w->model_state("mycar").pose.translation() - p0).norm(), 1e-3);
}

// The seed's drive ramps by wheelAcceleration times upstream's seconds_since_last_update, 0.011 s at 100 Hz and
// 1 ms (docs/COMPAT-plugins.md): 0.0198 m/s of wheel surface speed per update, where the period alone would give
// 0.018. Settled, then commanded 0.5 m/s: once the wheels follow their motors (from the fifth update on), their
// speed grows by that much per update; over updates 5 to 12 (0.107 to 0.247 m/s, well below the target) the slope is
// 0.0198 within 0.0005.
TEST(WorldPhysics, TheDriveRampsByAccelTimesElevenMillisecondsPerUpdate) {
  auto w = box_house_with_car();
  w->step(500);
  w->set_cmd_vel("mycar", 0.5, 0.0);
  // [m/s] the left wheel's surface speed after each of 12 updates (10 steps each)
  std::vector<double> speed;
  for (int k = 1; k <= 12; ++k) {
    w->step(10);
    for (const JointState& j : w->joint_states("mycar"))
      if (j.name == "left2link") speed.push_back(j.velocity * 0.0325);
  }
  ASSERT_EQ(speed.size(), 12u);
  EXPECT_NEAR((speed[11] - speed[4]) / 7.0, 1.8 * 0.011, 5e-4);
}

// While its target turns, a wheel's motor is a velocity motor alone, as ODE's (Joint::SetParam "vel" with "fmax"):
// the seed car lifted 1 m with gravity off, its wheels free, commanded 0.5 m/s. Each update adds 1.8 m/s^2 x 0.011 s
// = 0.0198 m/s to the wheel's target (the wheel follows its motor within the step: 30 N m on a 0.05 kg wheel), and
// the wheel holds that speed until the next update, so every step's surface speed is a whole multiple of 0.0198.
// (A pull toward the integrated angle, as car's motors had, added up to 5 % of the speed in the steps after each
// update, and the seed car drove 2 cm off upstream's diff drive over a 10 s circle: tools/upstream_plugins.sh.)
TEST(WorldPhysics, WhileItsTargetMovesAWheelMotorHoldsTheRampsSpeed) {
  auto w = box_house_with_car();
  w->step(500);
  w->set_gravity(Eigen::Vector3d::Zero());
  ModelState s = w->model_state("mycar");
  s.pose.translation().z() += 1.0;
  s.linear.setZero();
  s.angular.setZero();
  w->set_model_state("mycar", s);
  w->set_cmd_vel("mycar", 0.5, 0.0);
  int moving = 0;
  for (int k = 0; k < 120; ++k) {
    w->step(1);
    for (const JointState& j : w->joint_states("mycar")) {
      if (j.name != "left2link") continue;
      const double v = j.velocity * 0.0325;  // [m/s] surface speed
      const double updates = v / 0.0198;
      EXPECT_NEAR(v, 0.0198 * std::round(updates), 1e-6) << "step " << k;
      moving += updates > 0.5 ? 1 : 0;
    }
  }
  // 120 steps from the command: the ramp reaches 0.5 m/s after 26 updates, so the speed grew all along
  EXPECT_GT(moving, 100);
}

TEST(WorldPhysics, StraightRampCoversExpectedDistance) {
  auto w = box_house_with_car();
  w->step(500);
  const Eigen::Vector3d p0 = w->model_state("mycar").pose.translation();
  w->set_cmd_vel("mycar", 0.5, 0.0);
  w->step(4000);
  // 0.5 m/s for 4 s minus the ramp at wheelAcceleration 1.8 m/s^2, which upstream's update applies over 0.011 s
  // per 0.01 s (1.98 m/s^2): 0.5 * 4 - 0.5^2 / (2 * 1.98)
  EXPECT_NEAR((w->model_state("mycar").pose.translation() - p0).norm(), 0.5 * 4 - 0.25 / 3.96, 0.03);
}

TEST(WorldPhysics, WallStopsTheCar) {
  // Wall_2's inner face is at x = 4.44857 - 0.075; the car's front (base radius 0.1) stops there.
  auto w = box_house_with_car(2.0, 0.0, 0.0);
  w->set_cmd_vel("mycar", 1.0, 0.0);
  double max_x = 0.0;
  for (int i = 0; i < 6000; ++i) {
    w->step();
    max_x = std::max(max_x, w->model_state("mycar").pose.translation().x());
  }
  EXPECT_LT(max_x, 4.44857 - 0.075 - 0.1 + 0.002);
  EXPECT_GT(max_x, 4.44857 - 0.075 - 0.1 - 0.01);  // it did reach the wall
}

TEST(WorldPhysics, CarPushesUnitBox) {
  // unit_box_0 (1 kg, 1 m cube) at x = -4.96407; the car comes from x = -3.5 heading -x and meets it after about
  // 2.5 s. The box's friction (9.8 N) is near what the car's 2.4 kg on its drive wheels can push: whether and
  // where the push jams (the box turns) changes with the last bits of the contact arithmetic, but the box is
  // pushed 0.4 m or more first.
  auto w = box_house_with_car(-3.5, -2.00353, M_PI);
  const double x0 = w->model_state("unit_box_0").pose.translation().x();
  w->set_cmd_vel("mycar", 0.5, 0.0);
  w->step(4000);
  EXPECT_LT(w->model_state("unit_box_0").pose.translation().x(), x0 - 0.4);
}

TEST(WorldPhysics, EncoderOdometryFollowsGroundTruthOverALap) {
  RobotModel m = car();
  for (auto& p : m.plugins)
    if (p.filename == "libgazebo_ros_diff_drive.so") p.params.emplace_back("odometrySource", "encoder");
  World w(load_world_file(std::string(CAR_SOURCE_DIR) + "/worlds/box_house.world"));
  w.spawn(m, "mycar", Eigen::Isometry3d::Identity());
  w.set_cmd_vel("mycar", 1.0, 1.0);
  double worst = 0.0;
  for (int i = 0; i < 6284; i += 10) {
    w.step(10);
    const Eigen::Vector3d truth = w.model_state("mycar").pose.translation();
    for (const auto& o : w.take_odometry())
      worst = std::max(worst, (o.pose.translation() - Eigen::Vector3d(truth.x(), truth.y(), 0)).norm());
  }
  EXPECT_LT(worst, 0.05);
}

TEST(WorldPhysics, SameCommandsSameOdometryBitForBit) {
  std::vector<double> runs[2];
  for (auto& run : runs) {
    auto w = box_house_with_car();
    w->set_cmd_vel("mycar", 1.0, 0.7);
    w->step(1500);
    w->set_cmd_vel("mycar", -0.3, -1.0);
    w->step(1500);
    for (const auto& o : w->take_odometry()) {
      run.push_back(o.pose.translation().x());
      run.push_back(o.pose.translation().y());
      run.push_back(o.linear.x());
    }
  }
  ASSERT_EQ(runs[0].size(), runs[1].size());
  EXPECT_EQ(0, std::memcmp(runs[0].data(), runs[1].data(), runs[0].size() * sizeof(double)));
}

TEST(WorldPhysics, ResetReplaysBitForBit) {
  auto w = box_house_with_car();
  w->set_cmd_vel("mycar", 1.0, 1.0);
  w->step(1000);
  const Eigen::Vector3d first = w->model_state("mycar").pose.translation();
  w->reset();
  EXPECT_EQ(w->tick(), 0u);
  EXPECT_NEAR(w->model_state("mycar").pose.translation().norm(), 0.0, 1e-12);
  w->set_cmd_vel("mycar", 1.0, 1.0);
  w->step(1000);
  EXPECT_EQ(w->model_state("mycar").pose.translation(), first);
}

// Islands are solved one by one on every OpenMP thread (src/physics/island_world.hpp): an island's result does not
// depend on which thread solved it or how many there are. Six cars, two of them nose to nose (one island), the
// others apart, among box_house's boxes while those are still awake: one thread and two give the same poses.
TEST(WorldPhysics, IslandsOnTwoThreadsMatchOneBitForBit) {
  std::vector<double> runs[2];
  const int threads[2] = {1, 2};
  const int before = omp_get_max_threads();
  for (int r = 0; r < 2; ++r) {
    omp_set_num_threads(threads[r]);
    auto w = std::make_unique<World>(load_world_file(std::string(CAR_SOURCE_DIR) + "/worlds/box_house.world"));
    omp_set_num_threads(before);
    // [m], world frame; car0 and car1 0.3 m apart facing each other
    const double spots[6][3] = {{0, 0, 0}, {0.3, 0, M_PI}, {-2, -1, 0}, {2, -1, 1}, {1, 1.5, 2}, {-2, 1.5, -1}};
    for (int i = 0; i < 6; ++i) {
      const std::string name = "car" + std::to_string(i);
      w->spawn(car(), name, at(spots[i][0], spots[i][1], spots[i][2]));
      w->set_cmd_vel(name, i < 2 ? 0.3 : 0.5, i < 2 ? 0.0 : 1.0);
    }
    w->step(1500);
    for (int i = 0; i < 6; ++i) {
      const auto s = w->model_state("car" + std::to_string(i));
      for (int k = 0; k < 3; ++k) runs[r].push_back(s.pose.translation()[k]);
      for (int k = 0; k < 3; ++k) runs[r].push_back(s.linear[k]);
    }
  }
  ASSERT_EQ(runs[0].size(), runs[1].size());
  EXPECT_EQ(0, std::memcmp(runs[0].data(), runs[1].data(), runs[0].size() * sizeof(double)));
  // the pair pushed against each other and stayed apart (not through each other): car0 still left of car1
  EXPECT_LT(runs[0][0], runs[0][6]);
}

// The body-by-body passes (free accelerations, joint feedback, integrated positions) and the narrow phase run on
// the OpenMP threads too (src/physics/island_world.hpp): sixteen cars in the empty world,
// fourteen driving circles of different sizes, one standing still, one dropped from 0.3 m, give every base pose,
// velocity and joint state equal bit for bit on one, two and three threads after 1.5 s.
TEST(WorldPhysics, ManyCarsOnAnyThreadCountMatchBitForBit) {
  std::vector<double> runs[3];
  const int threads[3] = {1, 2, 3};
  const int before = omp_get_max_threads();
  for (int r = 0; r < 3; ++r) {
    omp_set_num_threads(threads[r]);
    auto w = std::make_unique<World>(empty_world());
    omp_set_num_threads(before);
    for (int i = 0; i < 16; ++i) {
      const std::string name = "car" + std::to_string(i);
      // [m], world frame: a 4 x 4 grid 1.5 m apart; car15 starts 0.3 m up
      Eigen::Isometry3d pose = at(1.5 * (i % 4), 1.5 * (i / 4), 0.2 * i);
      if (i == 15) pose.translation().z() = 0.3;
      w->spawn(car(), name, pose);
      if (i < 14) w->set_cmd_vel(name, 0.1 + 0.05 * i, 1.0 - 0.15 * i);
    }
    w->step(1500);
    for (int i = 0; i < 16; ++i) {
      const std::string name = "car" + std::to_string(i);
      const auto s = w->model_state(name);
      for (int k = 0; k < 3; ++k) runs[r].push_back(s.pose.translation()[k]);
      const Eigen::Quaterniond q(s.pose.rotation());
      for (int k = 0; k < 4; ++k) runs[r].push_back(q.coeffs()[k]);
      for (int k = 0; k < 3; ++k) runs[r].push_back(s.linear[k]);
      for (int k = 0; k < 3; ++k) runs[r].push_back(s.angular[k]);
      for (const auto& j : w->joint_states(name)) {
        runs[r].push_back(j.position);
        runs[r].push_back(j.velocity);
      }
    }
  }
  for (int r = 1; r < 3; ++r) {
    ASSERT_EQ(runs[0].size(), runs[r].size());
    EXPECT_EQ(0, std::memcmp(runs[0].data(), runs[r].data(), runs[0].size() * sizeof(double))) << threads[r];
  }
  // the cars moved: car9 (0.55 m/s, -0.35 rad/s on a 1.57 m circle) left its start by more than 0.5 m in 1.5 s
  const double dx = runs[0][9 * (runs[0].size() / 16)] - 1.5, dy = runs[0][9 * (runs[0].size() / 16) + 1] - 3.0;
  EXPECT_GT(std::hypot(dx, dy), 0.5);
}

// A fleet's lidars, all due at the same tick, sweep on the threads (Plugin::concurrent): six cars among box_house's
// walls and boxes give the same scans, bit for bit and in the same order with the same robot, plug-in and tick, on
// one thread and on two.
TEST(WorldPhysics, FleetLidarsOnTwoThreadsMatchOneBitForBit) {
  std::vector<LaserScanOut> runs[2];
  const int threads[2] = {1, 2};
  const int before = omp_get_max_threads();
  for (int r = 0; r < 2; ++r) {
    omp_set_num_threads(threads[r]);
    auto w = std::make_unique<World>(load_world_file(std::string(CAR_SOURCE_DIR) + "/worlds/box_house.world"));
    for (int i = 0; i < 6; ++i) {
      const std::string name = "car" + std::to_string(i);
      // [m], [rad], world frame: a row 1.2 m apart, each turning its own way
      w->spawn(car(), name, at(-3.0 + 1.2 * i, 0.5, 0.5 * i));
      w->set_cmd_vel(name, 0.3, i % 2 ? 0.8 : -0.8);
      w->set_sensor_active(name, "gazebo_rplidar", true);
    }
    w->step(2000);
    runs[r] = w->take_outputs<LaserScanOut>();
    omp_set_num_threads(before);
  }
  // 5.5 Hz for 2 s: 11 scans per car
  ASSERT_EQ(runs[0].size(), 66u);
  ASSERT_EQ(runs[1].size(), runs[0].size());
  for (size_t k = 0; k < runs[0].size(); ++k) {
    const LaserScanOut &a = runs[0][k], &b = runs[1][k];
    EXPECT_EQ(a.robot, b.robot) << k;
    EXPECT_EQ(a.plugin, b.plugin) << k;
    EXPECT_EQ(a.tick, b.tick) << k;
    ASSERT_EQ(a.ranges.size(), b.ranges.size());
    EXPECT_EQ(0, std::memcmp(a.ranges.data(), b.ranges.data(), a.ranges.size() * sizeof(float))) << k;
    EXPECT_EQ(0, std::memcmp(a.intensities.data(), b.intensities.data(), a.intensities.size() * sizeof(float))) << k;
  }
  // cars in spawn order, each car's scans in tick order
  EXPECT_EQ(runs[0][10].robot, "car0");
  EXPECT_EQ(runs[0][11].robot, "car1");
  // the 5.5 Hz schedule from tick 0: ceil(2000 k / 11)
  EXPECT_EQ(runs[0][0].tick, 182u);
  EXPECT_EQ(runs[0][1].tick, 364u);
}

TEST(WorldPhysics, OdometryAtUpdateRate) {
  auto w = box_house_with_car();
  w->step(1000);
  // updateRate 100 Hz at dt 1 ms: every 10th tick
  const auto odom = w->take_odometry();
  ASSERT_EQ(odom.size(), 100u);
  EXPECT_EQ(odom[0].tick, 10u);
  EXPECT_EQ(odom[1].tick, 20u);
}

// reset_world keeps time, and Gazebo fires no time-reset event: its sensors keep lastUpdateTime and so their phase.
// The 5.5 Hz lidar scans at ticks ceil(k * 2000 / 11) from its start (182, 364, ..., 910); after a reset at tick
// 1000 the next is k = 6, tick 1091, not 1000 + 182.
TEST(WorldReset, ALidarKeepsItsPhaseOverAResetThatKeepsTime) {
  auto w = box_house_with_car();
  w->set_sensor_active("mycar", "gazebo_rplidar", true);
  w->step(1000);
  ASSERT_EQ(w->take_outputs<LaserScanOut>().size(), 5u);
  w->reset_poses();
  w->step(200);
  const auto scans = w->take_outputs<LaserScanOut>();
  ASSERT_EQ(scans.size(), 1u);
  EXPECT_EQ(scans[0].tick, 1091u);
}

// gazebo_ros_diff_drive's Reset sets last_update_time_ to the reset's time: its 100 Hz updates start again from
// the reset at tick 1005, every 10th tick after it as from a spawn (WorldPhysics.OdometryAtUpdateRate: 10, 20).
TEST(WorldReset, TheDiffDriveRestartsItsClockOverAResetThatKeepsTime) {
  auto w = box_house_with_car();
  w->step(1005);
  w->take_odometry();
  w->reset_poses();
  w->step(20);
  const auto odom = w->take_odometry();
  ASSERT_EQ(odom.size(), 2u);
  EXPECT_EQ(odom[0].tick, 1015u);
  EXPECT_EQ(odom[1].tick, 1025u);
}

TEST(WorldModels, SpawnTwiceFails) {
  auto w = box_house_with_car();
  EXPECT_THROW(w->spawn(car(), "mycar", at(1, 1, 0)), std::invalid_argument);
  EXPECT_THROW(w->spawn(car(), "unit_box", at(1, 1, 0)), std::invalid_argument);
}

TEST(WorldModels, RemoveThenGone) {
  auto w = box_house_with_car();
  w->remove("unit_box");
  w->remove("mycar");
  EXPECT_FALSE(w->has_model("unit_box"));
  EXPECT_FALSE(w->has_model("mycar"));
  w->reset();
  EXPECT_FALSE(w->has_model("unit_box"));  // as in Gazebo, a reset does not bring a deleted model back
  EXPECT_THROW(w->remove("nothing"), std::invalid_argument);
}

TEST(WorldModels, SetModelStateMovesTheCar) {
  auto w = box_house_with_car();
  ModelState s;
  s.pose = at(1.0, -1.0, 0.5);
  w->set_model_state("mycar", s);
  EXPECT_NEAR((w->model_state("mycar").pose.translation() - Eigen::Vector3d(1, -1, 0)).norm(), 0.0, 1e-12);
}

TEST(WorldModels, NonFiniteCommandRejected) {
  auto w = box_house_with_car();
  EXPECT_THROW(w->set_cmd_vel("mycar", std::nan(""), 0.0), std::invalid_argument);
  EXPECT_THROW(w->set_cmd_vel("mycar", 0.0, INFINITY), std::invalid_argument);
}

TEST(WorldErrors, MissingFile) {
  EXPECT_EQ(load_error("nope.world"), data_path("nope.world") + ": cannot open file");
}

TEST(WorldErrors, DynamicLinkWithoutMass) {
  EXPECT_EQ(load_error("bad/massless.world"),
            data_path("bad/massless.world") + ": model[crate]/link[body]/inertial: a dynamic link needs a mass > 0");
}

TEST(WorldErrors, MalformedSdfNamesTheFile) {
  const std::string msg = load_error("bad/malformed.world");
  EXPECT_EQ(msg.rfind(data_path("bad/malformed.world"), 0), 0u) << msg;
}

namespace {

// Five seed cars in five box_house worlds (noise seeds 0..4), lidar on, driving different arcs; car 3 heads into
// Wall_2 (inner face x = 4.374) at 1.5 m/s: ramping at 1.98 m/s^2 (1.8 over 0.011 s per 0.01 s update) it loses
// 0.568 m, so the base (radius 0.1 m) touches at x = 4.274 after 2.774 m, t = 2.23 s. Everything a step writes: base pose and twist, joint states, every scan.
std::vector<std::unique_ptr<World>> five_worlds() {
  std::vector<std::unique_ptr<World>> ws;
  for (int i = 0; i < 5; ++i) {
    WorldOptions o;
    o.seed = static_cast<uint64_t>(i);
    ws.push_back(std::make_unique<World>(load_world_file(std::string(CAR_SOURCE_DIR) + "/worlds/box_house.world"), o));
    ws.back()->spawn(car(), "mycar", at(0.5 * i, 0.0, 0.0));
    ws.back()->set_sensor_active("mycar", "gazebo_rplidar", true);
    ws.back()->set_cmd_vel("mycar", i == 3 ? 1.5 : 0.2 + 0.1 * i, i == 3 ? 0.0 : 1.0 - 0.4 * i);
  }
  return ws;
}

std::vector<double> trace(World& w) {
  std::vector<double> out;
  const ModelState s = w.model_state("mycar");
  for (int k = 0; k < 3; ++k) out.push_back(s.pose.translation()[k]);
  const Eigen::Quaterniond q(s.pose.rotation());
  for (double c : {q.x(), q.y(), q.z(), q.w()}) out.push_back(c);
  for (int k = 0; k < 3; ++k) out.push_back(s.linear[k]);
  for (int k = 0; k < 3; ++k) out.push_back(s.angular[k]);
  for (const JointState& j : w.joint_states("mycar")) {
    out.push_back(j.position);
    out.push_back(j.velocity);
  }
  for (const LaserScanOut& scan : w.take_outputs<LaserScanOut>())
    for (float r : scan.ranges) out.push_back(r);
  return out;
}

}  // namespace

// step_worlds runs the worlds on the pool, one world per item, their own loops nested (serial) on its thread: the
// same bits as each world stepped alone by World::step, on one, two and three threads, in 2500 steps of 10 calls.
TEST(WorldBatch, StepWorldsOnAnyThreadCountMatchesWorldsSteppedAlone) {
  std::vector<std::vector<double>> alone;
  for (auto& w : five_worlds()) {
    for (int c = 0; c < 10; ++c) w->step(250);
    alone.push_back(trace(*w));
  }
  // the wall stopped car 3 (unhindered it would be at x = 1.5 + 3.125 = 4.625 m by t = 2.5 s)
  EXPECT_NEAR(alone[3][0], 4.274, 0.01);
  const int before = omp_get_max_threads();
  for (int threads : {1, 2, 3}) {
    auto ws = five_worlds();
    std::vector<World*> ptrs;
    for (auto& w : ws) ptrs.push_back(w.get());
    omp_set_num_threads(threads);
    for (int c = 0; c < 10; ++c) step_worlds(ptrs, 250);
    omp_set_num_threads(before);
    for (size_t i = 0; i < ws.size(); ++i) {
      const std::vector<double> got = trace(*ws[i]);
      ASSERT_EQ(got.size(), alone[i].size()) << "world " << i << ", " << threads << " threads";
      EXPECT_EQ(0, std::memcmp(got.data(), alone[i].data(), got.size() * sizeof(double)))
          << "world " << i << ", " << threads << " threads";
    }
  }
}

// A world twice in the list would be stepped on two threads at once: refused before any world moves.
TEST(WorldBatch, AWorldTwiceIsRefused) {
  auto a = box_house_with_car();
  auto b = box_house_with_car();
  try {
    step_worlds({a.get(), b.get(), a.get()}, 10);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "step_worlds: worlds[2] is worlds[0]; a world may appear once");
  }
  EXPECT_EQ(a->tick(), 0u);
  EXPECT_EQ(b->tick(), 0u);
}
