// World's gazebo_ros API (links, joints, wrenches, efforts, gravity): values worked out by hand for small robots
// floating in zero gravity, where only the applied wrench or effort acts (docs/COMPAT.md).
#include <gtest/gtest.h>

#include <cmath>

#include "car_sim/world.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

// test/data/floater.urdf: a cube of 6 kg, Izz = 1 kg m^2, com at its origin; a foot of 2 kg fixed under it (com
// 1.2 m below the cube's, Izz 0.01; merged into the cube's body); a spinner of 1 kg, Izz = 0.5 kg m^2, on a
// continuous joint 2 m above the cube, about z through every com (so the bodies turn about one axis, uncoupled).
const std::string& robot_xml() {
  static const std::string xml = read_text("test/data/floater.urdf");
  return xml;
}

// The floater at (0, 0, 5) in an empty world without gravity. dt = 0.001 s.
std::unique_ptr<World> floating() {
  auto w = std::make_unique<World>(empty_world());
  w->set_gravity(Eigen::Vector3d::Zero());
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(0, 0, 5);
  w->spawn(load_urdf_string(robot_xml(), "floater"), "f", pose);
  return w;
}

// Mass of the whole robot: cube 6 + foot 2 + spinner 1.
constexpr double kMass = 9.0;

// Linear momentum [kg m/s] of the floater: the cube's body (8 kg, com 0.3 m below the cube's origin) and the
// spinner (1 kg, com at its origin). A force off the common com also turns the robot, so momentum, not the root's
// speed, is what a force for a time gives: p = F n dt.
Eigen::Vector3d momentum(const World& w) {
  const ModelState cube = w.link_state(w.find_link("f::cube"));
  const ModelState spinner = w.link_state(w.find_link("f::spinner"));
  const Eigen::Vector3d r = cube.pose.linear() * Eigen::Vector3d(0, 0, -0.3);
  return 8.0 * (cube.linear + cube.angular.cross(r)) + 1.0 * spinner.linear;
}

}  // namespace

TEST(WorldApiLinks, ScopedAndPlainNames) {
  auto w = floating();
  EXPECT_EQ(w->find_link("f::spinner").model, "f");
  EXPECT_EQ(w->find_link("spinner").link, "spinner");
  EXPECT_EQ(w->find_link("ground_plane::link").model, "ground_plane");
  EXPECT_FALSE(w->find_link("ground_plane::link").robot);
}

TEST(WorldApiLinks, UnknownLinkNamesWhatIsMissing) {
  auto w = floating();
  try {
    w->find_link("f::wheel");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "model 'f' has no link 'wheel'");
  }
  try {
    w->find_link("g::cube");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "no model named 'g'");
  }
}

TEST(WorldApiLinks, ChildLinkStateFollowsTheJoint) {
  auto w = floating();
  w->set_joint_positions("f", {"spin"}, {0.5});
  // spinner = root (0 0 5) * joint origin (0 0 2) * Rz(0.5)
  const ModelState s = w->link_state(w->find_link("f::spinner"));
  EXPECT_NEAR(s.pose.translation().z(), 7.0, 1e-9);
  EXPECT_NEAR(Eigen::AngleAxisd(s.pose.linear()).angle(), 0.5, 1e-9);
  EXPECT_NEAR(w->model_state("f").pose.translation().z(), 5.0, 1e-9);
}

TEST(WorldApiLinks, SetLinkStateMovesTheModelRigidly) {
  auto w = floating();
  ModelState target;
  target.pose.translation() = Eigen::Vector3d(1, 2, 3);
  w->set_link_state(w->find_link("spinner"), target);
  // the spinner sits 2 m above the root: the root goes to (1, 2, 1)
  EXPECT_NEAR((w->model_state("f").pose.translation() - Eigen::Vector3d(1, 2, 1)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((w->link_state(w->find_link("spinner")).pose.translation() - Eigen::Vector3d(1, 2, 3)).norm(), 0.0,
              1e-9);
}

TEST(WorldApiLinks, NonFiniteLinkStateLeavesTheWorldUntouched) {
  auto w = floating();
  ModelState bad;
  bad.pose.translation().x() = std::nan("");
  EXPECT_THROW(w->set_link_state(w->find_link("spinner"), bad), std::invalid_argument);
  EXPECT_NEAR(w->model_state("f").pose.translation().z(), 5.0, 1e-12);
}

TEST(WorldApiProperties, TopLinkCarriesTheMergedMass) {
  auto w = floating();
  const LinkProperties p = w->link_properties(w->find_link("f::cube"));
  // cube 6 kg at 0 and foot 2 kg at z = -0.6 - 0.6 = -1.2 (inertial origin in the foot frame): com z = -2.4 / 8
  EXPECT_DOUBLE_EQ(p.mass, 8.0);
  EXPECT_NEAR(p.com.z(), -0.3, 1e-12);
  // Izz about the com: 1 + 0.01 (the offset is along z)
  EXPECT_NEAR(p.inertia(2, 2), 1.01, 1e-12);
  EXPECT_DOUBLE_EQ(w->link_properties(w->find_link("spinner")).mass, 1.0);
}

TEST(WorldApiProperties, ModelListsBodiesGeomsAndMovingJoints) {
  auto w = floating();
  const ModelProperties p = w->model_properties("f");
  EXPECT_EQ(p.bodies, (std::vector<std::string>{"cube", "spinner"}));
  EXPECT_EQ(p.joints, (std::vector<std::string>{"spin"}));
  EXPECT_EQ(p.geoms,
            (std::vector<std::string>{"cube_collision", "cube_fixed_joint_lump__foot_collision", "spinner_collision"}));
  EXPECT_FALSE(p.is_static);
  EXPECT_TRUE(w->model_properties("ground_plane").is_static);
}

TEST(WorldApiProperties, JointTypeDampingAndPosition) {
  auto w = floating();
  w->set_joint_positions("f", {"spin"}, {-1.25});
  const JointProperties j = w->joint_properties("f::spin");
  EXPECT_EQ(j.type, JointType::Continuous);
  EXPECT_DOUBLE_EQ(j.damping, 0.25);
  EXPECT_NEAR(j.position, -1.25, 1e-12);
  EXPECT_THROW(w->joint_properties("foot_joint"), std::invalid_argument);  // fixed: not a joint in Gazebo either
}

TEST(WorldApiJoints, BadConfigurationChangesNothing) {
  auto w = floating();
  EXPECT_THROW(w->set_joint_positions("f", {"spin", "nope"}, {1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(w->set_joint_positions("f", {"spin"}, {1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(w->set_joint_positions("f", {"spin"}, {std::nan("")}), std::invalid_argument);
  EXPECT_THROW(w->set_joint_positions("nobody", {"spin"}, {1.0}), std::invalid_argument);
  EXPECT_DOUBLE_EQ(w->joint_properties("spin").position, 0.0);
}

TEST(WorldApiWrench, ForceForADurationGivesMomentum) {
  auto w = floating();
  // 4.5 N along x from t = 0 for 0.5 s: steps starting at t = 0 ... 0.5 s, 501 of them; v = F n dt / m
  w->apply_wrench(w->find_link("f::cube"), Eigen::Vector3d(4.5, 0, 0), Eigen::Vector3d::Zero(), 0.0, 0.5);
  w->step(1000);
  // (1e-6: the robot also turns, and the integrator's rotation error shows in the momentum read back)
  EXPECT_NEAR(momentum(*w).x(), 4.5 * 501 * 0.001, 1e-6);
}

TEST(WorldApiWrench, ZeroDurationActsOneStep) {
  auto w = floating();
  w->apply_wrench(w->find_link("f::cube"), Eigen::Vector3d(0, 9.0, 0), Eigen::Vector3d::Zero(), 0.0, 0.0);
  w->step(10);
  EXPECT_NEAR(momentum(*w).y(), 9.0 * 0.001, 1e-12);
}

TEST(WorldApiWrench, LaterStartWaitsForItsTime) {
  auto w = floating();
  // starts at t = 0.2 s for 0.1 s: steps 200 ... 300, 101 of them
  w->apply_wrench(w->find_link("cube"), Eigen::Vector3d(0, 0, 9.0), Eigen::Vector3d::Zero(), 0.2, 0.1);
  w->step(200);
  EXPECT_NEAR(w->model_state("f").linear.z(), 0.0, 1e-12);
  w->step(200);
  EXPECT_NEAR(w->model_state("f").linear.z(), 9.0 * 101 * 0.001 / kMass, 1e-9);
}

TEST(WorldApiWrench, EndlessUntilCleared) {
  auto w = floating();
  w->apply_wrench(w->find_link("cube"), Eigen::Vector3d(9.0, 0, 0), Eigen::Vector3d::Zero(), 0.0, -1.0);
  w->step(100);
  EXPECT_EQ(w->clear_wrenches("f::cube"), 1);
  w->step(100);
  EXPECT_NEAR(momentum(*w).x(), 9.0 * 100 * 0.001, 1e-6);
  EXPECT_EQ(w->clear_wrenches("cube"), 0);
}

TEST(WorldApiWrench, TorqueTurnsTheCubeNotTheFreeSpinner) {
  auto w = floating();
  // 2 N m about z for one step on the cube's body (cube + foot, Izz = 1 + 0.01 about the common z axis); the
  // spinner's joint is free about that axis, so it keeps still and its joint rate is minus the cube's
  w->apply_wrench(w->find_link("cube"), Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 2.0), 0.0, 0.0);
  w->step(1);
  EXPECT_NEAR(w->model_state("f").angular.z(), 2.0 * 0.001 / 1.01, 1e-9);
  EXPECT_NEAR(w->joint_properties("spin").velocity, -2.0 * 0.001 / 1.01, 1e-9);
}

TEST(WorldApiWrench, BadWrenchIsRefusedAndNothingActs) {
  auto w = floating();
  EXPECT_THROW(w->apply_wrench(w->find_link("cube"), Eigen::Vector3d(std::nan(""), 0, 0), Eigen::Vector3d::Zero(),
                               0.0, 1.0),
               std::invalid_argument);
  w->step(10);
  EXPECT_EQ(w->model_state("f").linear.norm(), 0.0);
}

// gazebo_ros's ApplyBodyWrench finds a static model's link and succeeds; ODELink::AddForce has no body to push
TEST(WorldApiWrench, AWrenchOnAStaticLinkIsAcceptedAndMovesNothing) {
  auto w = floating();
  const ModelState before = w->model_state("ground_plane");
  EXPECT_NO_THROW(w->apply_wrench(w->find_link("ground_plane::link"), Eigen::Vector3d(1, 0, 0),
                                  Eigen::Vector3d::Zero(), 0.0, 1.0));
  w->step(10);
  EXPECT_TRUE(w->model_state("ground_plane").pose.isApprox(before.pose, 0.0));
  EXPECT_EQ(w->model_state("f").linear.norm(), 0.0);
}

TEST(WorldApiEffort, EffortSpinsBothSidesOfTheJoint) {
  auto w = floating();
  // 1 N m on the spin joint for the steps starting at t = 0 ... 0.099 s (100 steps). The spinner (Izz 0.5) and the
  // cube's body (Izz 1.01) turn opposite ways, so the joint rate q' obeys q'' = k (T - d q') with
  // k = 1/0.5 + 1/1.01 and the URDF's joint damping d = 0.25 N m s/rad, applied from the rate at the start of each
  // 1 ms step: q'(n+1) = q'(n) + dt k (T - d q'(n)).
  w->apply_joint_effort("f::spin", 1.0, 0.0, 0.099);
  w->step(100);
  const double k = 1.0 / 0.5 + 1.0 / 1.01, d = 0.25, dt = 0.001;
  double q = 0.0;
  for (int n = 0; n < 100; ++n) q += dt * k * (1.0 - d * q);
  EXPECT_NEAR(w->joint_properties("spin").velocity, q, 1e-12);  // 0.2882 rad/s (0.2990 undamped)
  // angular momentum about z stays zero: I_cube w_cube + I_spinner (w_cube + q') = 0
  const double w_cube = w->model_state("f").angular.z();
  EXPECT_NEAR(1.01 * w_cube + 0.5 * (w_cube + w->joint_properties("spin").velocity), 0.0, 1e-9);
  // no effort after its duration: only the damping acts, q' <- q' (1 - dt k d) per step
  const double before = w->joint_properties("spin").velocity;
  w->step(10);
  EXPECT_NEAR(w->joint_properties("spin").velocity, before * std::pow(1.0 - dt * k * d, 10), 1e-12);
}

TEST(WorldApiEffort, UnknownJointIsRefused) {
  auto w = floating();
  EXPECT_THROW(w->apply_joint_effort("f::nope", 1.0, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(w->apply_joint_effort("spin", std::nan(""), 0.0, 1.0), std::invalid_argument);
}

TEST(WorldApiPhysics, GravityChangesAndSurvivesAReset) {
  auto w = floating();
  w->set_gravity(Eigen::Vector3d(0, 0, -2.0));
  w->step(100);
  EXPECT_NEAR(w->model_state("f").linear.z(), -2.0 * 100 * 0.001, 1e-9);
  w->reset();
  EXPECT_EQ(w->gravity(), Eigen::Vector3d(0, 0, -2.0));
  w->step(50);
  EXPECT_NEAR(w->model_state("f").linear.z(), -2.0 * 50 * 0.001, 1e-9);
  EXPECT_THROW(w->set_gravity(Eigen::Vector3d(0, 0, INFINITY)), std::invalid_argument);
}

TEST(WorldApiPhysics, SolverIterations) {
  auto w = floating();
  EXPECT_EQ(w->solver_iterations(), 10);
  w->set_solver_iterations(50);
  EXPECT_EQ(w->solver_iterations(), 50);
  EXPECT_THROW(w->set_solver_iterations(0), std::invalid_argument);
}

// ---- the checks of the numbers the API takes (world.hpp, docs/COMPAT.md "Every service"): exact reasons, made
// before any name is looked up, the world untouched

namespace {

// The reason a call is refused with ("" when it is not).
template <class F>
std::string refusal(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(WorldApiChecks, NonFiniteModelStateIsRefusedAndTheModelStays) {
  auto w = floating();
  ModelState bad = w->model_state("f");
  bad.linear.y() = INFINITY;
  EXPECT_EQ(refusal([&] { w->set_model_state("f", bad); }), "pose and twist must be finite numbers");
  EXPECT_EQ(w->model_state("f").linear, Eigen::Vector3d::Zero());
}

TEST(WorldApiChecks, NonFiniteModelStateIsRefusedBeforeTheNameIsLookedUp) {
  auto w = floating();
  ModelState bad;
  bad.pose.translation().x() = std::nan("");
  EXPECT_EQ(refusal([&] { w->set_model_state("ghost", bad); }), "pose and twist must be finite numbers");
}

TEST(WorldApiChecks, NonFiniteLinkStateHasTheReason) {
  auto w = floating();
  ModelState bad;
  bad.angular.z() = -INFINITY;
  EXPECT_EQ(refusal([&] { w->set_link_state(w->find_link("spinner"), bad); }), "pose and twist must be finite numbers");
}

TEST(WorldApiChecks, NonFiniteEffortIsRefusedBeforeTheJointIsLookedUp) {
  auto w = floating();
  EXPECT_EQ(refusal([&] { w->apply_joint_effort("spin", INFINITY, 0.0, 1.0); }), "effort must be a finite number");
  EXPECT_EQ(refusal([&] { w->apply_joint_effort("nope", std::nan(""), 0.0, 1.0); }), "effort must be a finite number");
  w->step(10);
  EXPECT_EQ(w->joint_properties("spin").velocity, 0.0);
}

TEST(WorldApiChecks, NonFiniteEffortTimingHasItsOwnReason) {
  auto w = floating();
  EXPECT_EQ(refusal([&] { w->apply_joint_effort("spin", 1.0, std::nan(""), 1.0); }),
            "the start time and duration must be finite");
  EXPECT_EQ(refusal([&] { w->apply_joint_effort("spin", 1.0, 0.0, INFINITY); }),
            "the start time and duration must be finite");
}

// gazebo_msgs/SetPhysicsProperties' numbers, one bad at a time beside good ones (gravity -9.8 m/s^2, step 1 ms,
// 1000 Hz)
TEST(WorldApiChecks, NonFiniteOrNegativePhysicsPropertiesHaveTheReason) {
  const std::string why = "gravity, time_step and max_update_rate must be finite (max_update_rate >= 0)";
  const Eigen::Vector3d g(0, 0, -9.8);
  EXPECT_EQ(refusal([&] { check_physics_properties(Eigen::Vector3d(0, std::nan(""), -9.8), 0.001, 1000.0); }), why);
  EXPECT_EQ(refusal([&] { check_physics_properties(g, INFINITY, 1000.0); }), why);
  EXPECT_EQ(refusal([&] { check_physics_properties(g, 0.001, std::nan("")); }), why);
  EXPECT_EQ(refusal([&] { check_physics_properties(g, 0.001, INFINITY); }), why);
  EXPECT_EQ(refusal([&] { check_physics_properties(g, 0.001, -1.0); }), why);
}

// 0 Hz: as fast as possible (Gazebo's real_time_update_rate 0)
TEST(WorldApiChecks, ZeroUpdateRateIsAPhysicsProperty) {
  EXPECT_EQ(refusal([] { check_physics_properties(Eigen::Vector3d(0, 0, -9.8), 0.001, 0.0); }), "");
}

// (1.0025 - 1) / 0.001 = 2.5 steps: the third step ends after the time
TEST(WorldApiChecks, StepsUntilATimeBetweenSteps) {
  EXPECT_EQ(steps_until(1.0, 1.0025, 0.001), std::optional<uint64_t>(3));
}

// (0.503 - 0.5) / 0.001 is 3.0000000000000027 in doubles: a time on a step's end is that step, not the next
TEST(WorldApiChecks, StepsUntilATimeOnAStepsEnd) {
  EXPECT_EQ(steps_until(0.5, 0.503, 0.001), std::optional<uint64_t>(3));
}

TEST(WorldApiChecks, StepsUntilNothingUnlessAFiniteTimeAfterNow) {
  EXPECT_EQ(steps_until(2.0, 2.0, 0.001), std::nullopt);
  EXPECT_EQ(steps_until(2.0, 1.0, 0.001), std::nullopt);
  EXPECT_EQ(steps_until(2.0, std::nan(""), 0.001), std::nullopt);
  EXPECT_EQ(steps_until(2.0, INFINITY, 0.001), std::nullopt);
}
