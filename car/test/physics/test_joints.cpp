// Joint physics (docs/COMPAT-physics.md): viscous damping, Coulomb friction, hard stops on prismatic joints,
// motor effort and velocity caps from <limit>, and selfCollide. The robots hang from a 1e5 kg base that feels
// no gravity (<gravity>false</gravity>), so the base barely moves (reactions are 1e-5 of the joint's) and no
// ground is needed. g = 10 m/s^2, dt = 1 ms.
#include <gtest/gtest.h>
#include <omp.h>

#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>

#include "physics_fixtures.hpp"

using namespace car_sim;
using namespace car_sim::test_physics;

namespace {

// The heavy floating base: a 1 m cube of 1e5 kg without collision geometry, gravity off.
const std::string kBase = "<link name=\"base\">" + box_inertial(1e5, 1, 1, 1) +
                          "</link><gazebo reference=\"base\"><gravity>false</gravity></gazebo>";

// A pendulum: a 1 kg bob (I about its centre 0.001 kg m^2) 0.5 m below a hinge about y, its joint frame turned
// by theta0 about y so that it starts theta0 from hanging straight down (the rest position is q = -theta0).
RobotModel pendulum(double theta0, const std::string& dynamics) {
  return load_urdf_string("<robot name=\"pendulum\">" + kBase +
                              fmt("<joint name=\"hinge\" type=\"continuous\"><parent link=\"base\"/><child link=\"bob\"/>"
                                  "<origin xyz=\"0 0 0\" rpy=\"0 %.17g 0\"/><axis xyz=\"0 1 0\"/>",
                                  theta0) +
                              dynamics +
                              "</joint><link name=\"bob\"><inertial><origin xyz=\"0 0 -0.5\"/><mass value=\"1\"/>"
                              "<inertia ixx=\"0.001\" iyy=\"0.001\" izz=\"0.001\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/>"
                              "</inertial></link></robot>",
                          "pendulum.urdf");
}

}  // namespace

TEST(JointDynamics, PendulumDecaysAsDampedOscillator) {
  // I = m L^2 + I_c = 0.25 + 0.001 = 0.251 kg m^2, d = 0.1 N m s/rad. Small angles: I p'' + d p' + m g L p = 0
  // with p = theta0 + q: sigma = d / (2 I) = 0.199203 1/s, w0^2 = m g L / I = 19.920319, wd = sqrt(w0^2 -
  // sigma^2) = 4.458771 rad/s; from rest p(t) = theta0 e^(-sigma t) (cos wd t + sigma / wd sin wd t).
  // theta0 = 0.05 rad (the sin p ~ p error shifts the phase by < 1e-4 rad over 5 s). Tolerance 1 % of theta0.
  const double theta0 = 0.05, I = 0.251, d = 0.1;
  const double sigma = d / (2 * I), wd = std::sqrt(1.0 * kG * 0.5 / I - sigma * sigma);
  EXPECT_NEAR(sigma, 0.199203, 1e-6);
  EXPECT_NEAR(wd, 4.458771, 1e-6);
  physics::Physics p(world(""), options(), {});
  physics::Robot& r = p.add_robot(pendulum(theta0, "<dynamics damping=\"0.1\"/>"), "pendulum", pose(0, 0, 2), {});
  const int hinge = r.joint("hinge");
  for (int second = 1; second <= 5; ++second) {
    run(p, 1000);
    const double t = second;
    const double expected = theta0 * std::exp(-sigma * t) * (std::cos(wd * t) + sigma / wd * std::sin(wd * t));
    EXPECT_NEAR(theta0 + r.joint_position(hinge), expected, 0.01 * theta0) << "t = " << t << " s";
  }
}

TEST(JointDynamics, CoulombFrictionHoldsBelowItsTorque) {
  // Gravity's torque on the bob at theta0 = 0.05 rad: m g L sin theta0 = 5 sin 0.05 = 0.24990 N m.
  // friction 1.0 N m > 0.2499: the pendulum stays put. friction 0.1 N m < 0.2499: it swings, at first with
  // a = (0.2499 - 0.1) / 0.251 = 0.597 rad/s^2, so after 0.2 s q ~ -a t^2 / 2 = -0.0119 rad.
  {
    physics::Physics p(world(""), options(), {});
    physics::Robot& r = p.add_robot(pendulum(0.05, "<dynamics friction=\"1.0\"/>"), "pendulum", pose(0, 0, 2), {});
    run(p, 1000);
    EXPECT_NEAR(r.joint_position(r.joint("hinge")), 0.0, 1e-4);
  }
  {
    physics::Physics p(world(""), options(), {});
    physics::Robot& r = p.add_robot(pendulum(0.05, "<dynamics friction=\"0.1\"/>"), "pendulum", pose(0, 0, 2), {});
    run(p, 200);
    EXPECT_NEAR(r.joint_position(r.joint("hinge")), -0.5 * (0.2499 - 0.1) / 0.251 * 0.04, 0.001);
  }
}

TEST(JointLimits, PrismaticStopsAtItsLimit) {
  // A 1 kg slider on a vertical prismatic joint (lower -0.2 m) falls freely: after n = 100 steps
  // q = -g dt^2 n (n + 1) / 2 = -0.0505 m; it reaches -0.2 m at t = sqrt(2 * 0.2 / g) = 0.2 s and stays there.
  const RobotModel m = load_urdf_string(
      "<robot name=\"slider\">" + kBase +
          "<joint name=\"slide\" type=\"prismatic\"><parent link=\"base\"/><child link=\"slider\"/>"
          "<axis xyz=\"0 0 1\"/><limit lower=\"-0.2\" upper=\"0.2\" effort=\"100\" velocity=\"10\"/></joint>"
          "<link name=\"slider\">" + box_inertial(1, 0.1, 0.1, 0.1) + "</link></robot>",
      "slider.urdf");
  physics::Physics p(world(""), options(), {});
  physics::Robot& r = p.add_robot(m, "slider", pose(0, 0, 2), {});
  const int slide = r.joint("slide");
  run(p, 100);
  EXPECT_NEAR(r.joint_position(slide), -kG * kDt * kDt * 100 * 101 / 2, 1e-5);
  run(p, 900);
  EXPECT_NEAR(r.joint_position(slide), -0.2, 1e-3);
  EXPECT_NEAR(r.joint_velocity(slide), 0.0, 1e-3);
}

namespace {

// A disk (1 kg, I about its axis 0.01 kg m^2) on a vertical continuous joint with the given <limit>.
RobotModel turntable(const std::string& limit) {
  return load_urdf_string("<robot name=\"turntable\">" + kBase +
                              "<joint name=\"spin\" type=\"continuous\"><parent link=\"base\"/><child link=\"disk\"/>"
                              "<axis xyz=\"0 0 1\"/>" + limit +
                              "</joint><link name=\"disk\"><inertial><mass value=\"1\"/>"
                              "<inertia ixx=\"0.005\" iyy=\"0.005\" izz=\"0.01\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/>"
                              "</inertial></link></robot>",
                          "turntable.urdf");
}

}  // namespace

TEST(JointLimits, MotorVelocityCappedByLimit) {
  // A motor asked for 5 rad/s with 100 N m on a joint with <limit velocity="2">: it turns at 2 rad/s.
  physics::Physics p(world(""), options(), {});
  physics::Robot& r = p.add_robot(turntable("<limit effort=\"100\" velocity=\"2\"/>"), "t", pose(0, 0, 2), {});
  const int spin = r.joint("spin");
  const int motor = r.add_motor(spin, 100.0);
  MotorTarget target;
  target.velocity = 5.0;
  r.set_motor(motor, target);
  run(p, 500);
  EXPECT_NEAR(r.joint_velocity(spin), 2.0, 1e-6);
}

TEST(JointLimits, MotorEffortCappedByLimit) {
  // A motor with 100 N m asked for 1000 rad/s on a joint with <limit effort="0.5">: it pushes with 0.5 N m,
  // a = 0.5 / 0.01 = 50 rad/s^2, so after 0.1 s the disk turns at 5 rad/s. Tolerance 0.5 %.
  physics::Physics p(world(""), options(), {});
  physics::Robot& r = p.add_robot(turntable("<limit effort=\"0.5\" velocity=\"0\"/>"), "t", pose(0, 0, 2), {});
  const int spin = r.joint("spin");
  const int motor = r.add_motor(spin, 100.0);
  MotorTarget target;
  target.velocity = 1000.0;
  r.set_motor(motor, target);
  run(p, 100);
  EXPECT_NEAR(r.joint_velocity(spin), 5.0, 0.025);
}

namespace {

// Two 5 cm cube fingers on prismatic joints along y, 0.2 m apart (centres at y = -0.1 and +0.1), gravity off.
// The left one is driven at +0.2 m/s for 1 s, the right one held at 0. Returns the left finger's joint position.
// `cars` seed cars fall freely 10 m away beside it (no ground); their own link pairs lengthen the broad phase's
// pair array, and *pairs gets its length after the first step.
double close_fingers(bool self_collide, int cars = 0, int* pairs = nullptr) {
  const std::string flag = self_collide ? "<selfCollide>true</selfCollide>" : "";
  std::string xml = "<robot name=\"gripper\">" + kBase;
  for (const char* side : {"left", "right"}) {
    const double y = std::string(side) == "left" ? -0.1 : 0.1;
    xml += std::string("<joint name=\"") + side + "\" type=\"prismatic\"><parent link=\"base\"/>" +
           "<child link=\"" + side + "_finger\"/>" + fmt("<origin xyz=\"0 %g 0\"/>", y) +
           "<axis xyz=\"0 1 0\"/><limit lower=\"-1\" upper=\"1\" effort=\"1000\" velocity=\"10\"/></joint>"
           "<link name=\"" + side + "_finger\">" + box_inertial(0.1, 0.05, 0.05, 0.05) +
           "<collision><geometry><box size=\"0.05 0.05 0.05\"/></geometry></collision></link>"
           "<gazebo reference=\"" + side + "_finger\"><gravity>false</gravity>" + flag + "</gazebo>";
  }
  physics::Physics p(world(""), options(), {});
  physics::Robot& r = p.add_robot(load_urdf_string(xml + "</robot>", "gripper.urdf"), "gripper", pose(0, 0, 2), {});
  // [m], world frame: a row along x, 1.5 m apart
  for (int i = 0; i < cars; ++i) p.add_robot(seed_car(), "car" + std::to_string(i), pose(10.0 + 1.5 * i, 0, 2), {});
  const int left = r.add_motor(r.joint("left"), 10.0);
  const int right = r.add_motor(r.joint("right"), 1000.0);
  MotorTarget drive;
  drive.velocity = 0.2;
  r.set_motor(left, drive);
  r.set_motor(right, MotorTarget());
  run(p, 1);
  if (pairs) *pairs = p.bullet().getPairCache()->getNumOverlappingPairs();
  run(p, 999);
  return r.joint_position(r.joint("left"));
}

}  // namespace

TEST(SelfCollide, OffByDefaultOnWhenSet) {
  // Off (Gazebo's default): the left finger passes through the right one: q = 0.2 m/s * 1 s = 0.2 m.
  // On: it stops touching the right finger (held at y = 0.1): its centre at 0.1 - 0.05 = 0.05, q = 0.15 m.
  // Tolerance 2 mm.
  EXPECT_NEAR(close_fingers(false), 0.2, 0.002);
  EXPECT_NEAR(close_fingers(true), 0.15, 0.002);
}

// The dispatcher on two threads (IslandDispatcher: 32 pairs or more) skips the pairs self-collision refuses by a
// mark it keeps in each pair; the gripper's fingers still meet when it self-collides and pass through each other
// when it does not, as alone (the values of OffByDefaultOnWhenSet).
TEST(SelfCollide, TheThreadedDispatcherKeepsTheRule) {
  const int before = omp_get_max_threads();
  omp_set_num_threads(2);
  int pairs[2] = {0, 0};
  const double off = close_fingers(false, 10, &pairs[0]);
  const double on = close_fingers(true, 10, &pairs[1]);
  omp_set_num_threads(before);
  // ten cars' own link pairs (about four each) and the fingers' pair: past the threaded path's 32
  EXPECT_GE(pairs[0], 32);
  EXPECT_GE(pairs[1], 32);
  EXPECT_NEAR(off, 0.2, 0.002);
  EXPECT_NEAR(on, 0.15, 0.002);
}
