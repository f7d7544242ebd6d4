// One test per ros_control controller type that test_ros_control.cpp does not cover, each against a value worked
// out by hand (docs/COMPAT-control.md). Fixtures: test/data/control/turntable.urdf (two free joints about the
// vertical axis, inertia 0.5 and 0.25 kg m^2, effort + velocity + position interfaces) and arm.urdf (two 1 kg links,
// centres of mass 0.5 m from their joints, anchored to the world).
//
// Timing, common to all tests: the world steps 1 ms; the controllers run in each step's pre_physics on the state
// at the step's start, from the second step on (the first step after the plug-in starts only reads the state), so
// a command set at t = 0 acts from t = 1 ms: over t = N ms a constant command acts for N - 1 steps. Bullet
// integrates semi-implicit Euler: under a constant acceleration alpha for n steps, v = alpha n dt and
// q = alpha dt^2 n (n + 1) / 2.
#include <gtest/gtest.h>

#include <cmath>

#include "control_fixture.hpp"

using namespace car_sim;
using namespace car_sim::control_test;
using control::Params;

namespace {

constexpr double kDt = 0.001; // [s], the empty world's step

JointState joint(const World& w, const std::string& robot, const std::string& j) {
  for (const auto& s : w.joint_states(robot))
    if (s.name == j) return s;
  ADD_FAILURE() << "no joint " << j;
  return {};
}

control::CommandController& command_ctl(RosControl& rc, const std::string& name) {
  return *dynamic_cast<control::CommandController*>(rc.controller(name));
}

// A command through the manager's port, as the node gives it (held until a just-started controller's first update).
void command(RosControl& rc, const std::string& name, const std::vector<double>& v) {
  CommandResult r;
  if (command_ctl(rc, name).group())
    rc.command(name + "/command", Float64Array{v}, &r);
  else
    rc.command(name + "/command", Float64{v.at(0)}, &r);
  ASSERT_FALSE(r.refused) << r.reason;
  for (const auto& n : r.notes) ADD_FAILURE() << n.text;
}

control::TrajectoryController& trajectory_ctl(RosControl& rc, const std::string& name) {
  return *dynamic_cast<control::TrajectoryController*>(rc.controller(name));
}

// Semi-implicit Euler position after n steps of constant acceleration alpha [rad/s^2] from rest: [rad]
double euler_position(double alpha, int n) { return alpha * kDt * kDt * n * (n + 1) / 2.0; }

}  // namespace

// ---- forward command controllers, one joint -----------------------------------------------------------------

TEST(ControllerTypes, JointEffortControllerAcceleratesTheJointAtTauOverI) {
  // effort_controllers/JointEffortController on joint a (I = 0.5 kg m^2, no gravity torque, no damping):
  // tau = 1 N m -> alpha = tau / I = 2 rad/s^2; after t = 1 s: theta = alpha t^2 / 2 = 1.0 rad, omega = 2 rad/s.
  // Discrete (999 steps of 1 ms, semi-implicit Euler): theta = 2 * 1e-6 * 999 * 1000 / 2 = 0.999 rad,
  // omega = 2 * 0.999 = 1.998 rad/s.
  auto w = world_with("turntable.urdf", "tt");
  RosControl& rc = manager(*w, "tt");
  rc.load("a_ctl", "effort_controllers/JointEffortController", Params{{"joint", {"a"}}});
  start(rc, {"a_ctl"});
  command(rc, "a_ctl", {1.0});
  w->step(1000);
  EXPECT_NEAR(joint(*w, "tt", "a").position, euler_position(2.0, 999), 1e-6);
  EXPECT_NEAR(joint(*w, "tt", "a").position, 1.0, 2e-3);
  EXPECT_NEAR(joint(*w, "tt", "a").velocity, 1.998, 1e-6);
  // joint b has no controller: effort interface listed first, so it gets 0 and stays at rest
  EXPECT_EQ(joint(*w, "tt", "b").position, 0.0);
}

TEST(ControllerTypes, JointVelocityControllerTurnsTheJointAtItsCommand) {
  // velocity_controllers/JointVelocityController on joint b: the velocity interface is a joint motor capped by
  // <limit effort> 100 N m (Gazebo: SetParam("vel") with fmax = the effort limit), so on I = 0.25 kg m^2 the speed
  // rises at most 100 / 0.25 = 400 rad/s^2, 0.4 rad/s per step, to its command 3 rad/s: steps 2..8 run at
  // 0.4, 0.8, ..., 2.8 rad/s (sum 11.2), steps 9..1000 at 3 rad/s (992 steps):
  // theta(1 s) = 1 ms * (11.2 + 992 * 3) rad/s = 2.9872 rad (an uncapped motor: 3 * 0.999 = 2.997 rad).
  auto w = world_with("turntable.urdf", "tt");
  RosControl& rc = manager(*w, "tt");
  rc.load("b_ctl", "velocity_controllers/JointVelocityController", Params{{"joint", {"b"}}});
  start(rc, {"b_ctl"});
  command(rc, "b_ctl", {3.0});
  w->step(1000);
  EXPECT_NEAR(joint(*w, "tt", "b").velocity, 3.0, 1e-6);
  EXPECT_NEAR(joint(*w, "tt", "b").position, 2.9872, 1e-6);
}

// The position interface is a joint motor that asks for the whole position error in one step (velocity error / dt)
// with its impulse capped by <limit effort> * dt. It lands on the command in one step when the impulse suffices:
// I |e| / dt <= tau_max dt, i.e. |e| <= tau_max dt^2 / I = 100 N m * 1e-6 s^2 / 0.5 kg m^2 = 2e-4 rad on joint a,
// 4e-4 rad on joint b (larger steps: PositionInterfaceReachesALargeStepWithoutOvershoot below).
TEST(ControllerTypes, JointPositionControllerMovesTheJointToItsCommand) {
  // position_controllers/JointPositionController on joint a, command 1.5e-4 rad (< 2e-4 rad): the first update
  // (step 2) lands the joint on it at 1.5e-4 rad / 1 ms = 0.15 rad/s, step 3 stops it (0.5 * 0.15 = 0.075 N m s
  // <= 0.1 N m s): after 3 steps a = 1.5e-4 rad at rest, and it holds.
  auto w = world_with("turntable.urdf", "tt");
  RosControl& rc = manager(*w, "tt");
  rc.load("a_ctl", "position_controllers/JointPositionController", Params{{"joint", {"a"}}});
  start(rc, {"a_ctl"});
  command(rc, "a_ctl", {1.5e-4});
  w->step(2);
  EXPECT_NEAR(joint(*w, "tt", "a").position, 1.5e-4, 1e-9);
  EXPECT_NEAR(joint(*w, "tt", "a").velocity, 0.15, 1e-6);
  w->step(1);
  EXPECT_NEAR(joint(*w, "tt", "a").velocity, 0.0, 1e-6);
  w->step(997);
  EXPECT_NEAR(joint(*w, "tt", "a").position, 1.5e-4, 1e-9);
}

TEST(ControllerTypes, PositionInterfaceReachesALargeStepWithoutOvershoot) {
  // A step far beyond one step's reach: command 0.8 rad on joint a (I = 0.5 kg m^2 about its axis, cap 100 N m).
  // The motor moves no faster than sqrt(2 a |e|) with a = 0.5 * 100 / 0.5 = 100 rad/s^2 (half the cap's
  // 200 rad/s^2), so braking never needs more than the cap: the joint never passes 0.8 rad. Time: accelerating at
  // 200 rad/s^2 until v = sqrt(2 * 100 * (0.8 - q)) (q = v^2 / 400: v = 10.3 rad/s at q = 0.267 rad, t = 0.052 s),
  // then braking at 100 rad/s^2 for 0.103 s: on the command at about 0.155 s; at 1 s it is there, at rest.
  auto w = world_with("turntable.urdf", "tt");
  RosControl& rc = manager(*w, "tt");
  rc.load("a_ctl", "position_controllers/JointPositionController", Params{{"joint", {"a"}}});
  start(rc, {"a_ctl"});
  command(rc, "a_ctl", {0.8});
  double highest = 0.0;
  for (int k = 0; k < 1000; ++k) {
    w->step(1);
    highest = std::max(highest, joint(*w, "tt", "a").position);
    if (k == 199) {
      EXPECT_NEAR(joint(*w, "tt", "a").position, 0.8, 1e-6);  // t = 0.2 s
    }
  }
  EXPECT_LE(highest, 0.8 + 1e-9);
  EXPECT_NEAR(joint(*w, "tt", "a").position, 0.8, 1e-9);
  EXPECT_NEAR(joint(*w, "tt", "a").velocity, 0.0, 1e-6);
}

TEST(ControllerTypes, EffortPidVelocityControllerApproachesItsSetPointWithTimeConstantIOverP) {
  // effort_controllers/JointVelocityController on joint a, pid p = 5 N m s/rad only, set point 2 rad/s:
  // I dw/dt = p (2 - w) -> w(t) = 2 (1 - exp(-p t / I)), time constant I / p = 0.5 / 5 = 0.1 s.
  // Discrete: w_{k+1} = w_k + (p dt / I)(2 - w_k) = w_k + 0.01 (2 - w_k), from the second step:
  // after 100 ms (99 updates) w = 2 (1 - 0.99^99) = 1.26054 rad/s (continuous: 2 (1 - e^-1) = 1.26424 rad/s, the
  // explicit step's error is O(p dt / I) = 1 % of the change);
  // after 1 s, w = 2 (1 - 0.99^999) = 2.0000 rad/s to 1e-4.
  auto w = world_with("turntable.urdf", "tt");
  RosControl& rc = manager(*w, "tt");
  rc.load("a_ctl", "effort_controllers/JointVelocityController", Params{{"joint", {"a"}}, {"pid/p", {"5"}}});
  start(rc, {"a_ctl"});
  command(rc, "a_ctl", {2.0});
  w->step(100);
  EXPECT_NEAR(joint(*w, "tt", "a").velocity, 2.0 * (1.0 - std::pow(0.99, 99)), 1e-6);
  EXPECT_NEAR(joint(*w, "tt", "a").velocity, 2.0 * (1.0 - std::exp(-1.0)), 5e-3);
  w->step(900);
  EXPECT_NEAR(joint(*w, "tt", "a").velocity, 2.0, 1e-4);
}

// ---- forward command controllers, joint groups --------------------------------------------------------------

TEST(ControllerTypes, JointGroupEffortControllerGivesEachJointTauOverI) {
  // effort_controllers/JointGroupEffortController on [a, b], command (1.0, -0.25) N m; I = (0.5, 0.25) kg m^2:
  // alpha = (2, -1) rad/s^2; after 1 s: theta = alpha t^2 / 2 = (1.0, -0.5) rad, omega = (2, -1) rad/s
  // (discrete, 999 steps: theta = (0.999, -0.4995) rad, omega = (1.998, -0.999) rad/s).
  auto w = world_with("turntable.urdf", "tt");
  RosControl& rc = manager(*w, "tt");
  rc.load("g", "effort_controllers/JointGroupEffortController", Params{{"joints", {"a", "b"}}});
  start(rc, {"g"});
  command(rc, "g", {1.0, -0.25});
  w->step(1000);
  EXPECT_NEAR(joint(*w, "tt", "a").position, 1.0, 2e-3);
  EXPECT_NEAR(joint(*w, "tt", "b").position, -0.5, 2e-3);
  EXPECT_NEAR(joint(*w, "tt", "a").position, euler_position(2.0, 999), 1e-6);
  EXPECT_NEAR(joint(*w, "tt", "b").position, euler_position(-1.0, 999), 1e-6);
  EXPECT_NEAR(joint(*w, "tt", "a").velocity, 1.998, 1e-6);
  EXPECT_NEAR(joint(*w, "tt", "b").velocity, -0.999, 1e-6);
}

TEST(ControllerTypes, JointGroupVelocityControllerTurnsEachJointAtItsCommand) {
  // velocity_controllers/JointGroupVelocityController on [b, a] (order of `joints`, not of the URDF), command
  // (-1.5, 2.5) rad/s. Each motor is capped by 100 N m: the speed changes at most 100 N m * 1 ms / I per step,
  // 0.4 rad/s on b (0.25 kg m^2), 0.2 rad/s on a (0.5 kg m^2). Over 1 s (steps 2..1000 driven):
  //   b: 0.4, 0.8, 1.2 rad/s (sum 2.4), then 996 steps at 1.5: theta_b = -1 ms * (2.4 + 1494) = -1.4964 rad
  //   a: 0.2 ... 2.4 rad/s (12 steps, sum 15.6), then 987 steps at 2.5: theta_a = 1 ms * (15.6 + 2467.5) = 2.4831 rad
  auto w = world_with("turntable.urdf", "tt");
  RosControl& rc = manager(*w, "tt");
  rc.load("g", "velocity_controllers/JointGroupVelocityController", Params{{"joints", {"b", "a"}}});
  start(rc, {"g"});
  command(rc, "g", {-1.5, 2.5});
  w->step(1000);
  EXPECT_NEAR(joint(*w, "tt", "b").velocity, -1.5, 1e-6);
  EXPECT_NEAR(joint(*w, "tt", "a").velocity, 2.5, 1e-6);
  EXPECT_NEAR(joint(*w, "tt", "b").position, -1.4964, 1e-6);
  EXPECT_NEAR(joint(*w, "tt", "a").position, 2.4831, 1e-6);
}

TEST(ControllerTypes, JointGroupPositionControllerMovesEachJointToItsCommand) {
  // position_controllers/JointGroupPositionController on [a, b], command (1.5e-4, -3.5e-4) rad: within each joint's
  // one-step reach (2e-4 rad on a, 4e-4 rad on b, above), so both are on their command after the first update
  // (step 2) and at rest after step 3; a second command (-1e-4, 0) rad: both there 2 steps later.
  auto w = world_with("turntable.urdf", "tt");
  RosControl& rc = manager(*w, "tt");
  rc.load("g", "position_controllers/JointGroupPositionController", Params{{"joints", {"a", "b"}}});
  start(rc, {"g"});
  command(rc, "g", {1.5e-4, -3.5e-4});
  w->step(2);
  EXPECT_NEAR(joint(*w, "tt", "a").position, 1.5e-4, 1e-9);
  EXPECT_NEAR(joint(*w, "tt", "b").position, -3.5e-4, 1e-9);
  w->step(98);
  EXPECT_NEAR(joint(*w, "tt", "a").position, 1.5e-4, 1e-9);
  EXPECT_NEAR(joint(*w, "tt", "b").position, -3.5e-4, 1e-9);
  EXPECT_NEAR(joint(*w, "tt", "b").velocity, 0.0, 1e-6);
  command(rc, "g", {-1e-4, 0.0});
  w->step(2);
  EXPECT_NEAR(joint(*w, "tt", "a").position, -1e-4, 1e-9);
  EXPECT_NEAR(joint(*w, "tt", "b").position, 0.0, 1e-9);
  // a command of the wrong size is refused and changes nothing
  std::string why;
  EXPECT_FALSE(command_ctl(rc, "g").set_command({1.0}, &why));
  EXPECT_EQ(why, "command has 1 values for 2 joints");
  w->step(10);
  EXPECT_NEAR(joint(*w, "tt", "a").position, -1e-4, 1e-9);
}

// ---- trajectory controllers with PID gains ------------------------------------------------------------------

TEST(ControllerTypes, VelocityTrajectoryLagsByVOverPAndMeetsItsGoalAtItsTime) {
  // velocity_controllers/JointTrajectoryController on the turntable: one point (a, b) = (0.5, -0.5) rad at 2 s,
  // positions only, so linear from (0, 0): desired velocity v_d = (0.25, -0.25) rad/s. The velocity interface
  // turns the joint at the command u = p e + clamp(i sum(e dt)) + d de/dt (velocity_ff 0, d 0), e = q_d - q.
  // Each step: e_{k+1} = e_k + dt (v_d - u_k).
  //   a: gains {p 10 1/s, i 0, d 0, i_clamp 0}: u = p e -> e settles at v_d / p = 0.25 / 10 = 0.025 rad
  //      (factor 1 - p dt = 0.99 per step: settled long before 2 s).
  //   b: gains {p 10 1/s, i 20 1/s^2, d 0, i_clamp 0.05 rad/s}: the integral reaches its clamp -0.05 rad/s within
  //      ~0.25 s (i e t ~ 20 * 0.02 * 0.25 = 0.1 > 0.05), then u = p e - 0.05 -> e settles at (v_d + 0.05) / p =
  //      (-0.25 + 0.05) / 10 = -0.02 rad (without the clamp the integral would drive e to 0).
  // At 1 s: q = (0.25 - 0.025, -0.25 + 0.02) = (0.225, -0.23) rad; at 2 s: (0.475, -0.48) rad.
  // Goal tolerance 0.03 rad > 0.025 and 0.02 (stopped_velocity_tolerance 0: unchecked), so the goal succeeds at
  // its time: the update at t = 2.0 s (the 2001st step's pre_physics) sees both joints inside.
  auto w = world_with("turntable.urdf", "tt");
  RosControl& rc = manager(*w, "tt");
  rc.load("traj", "velocity_controllers/JointTrajectoryController",
          Params{{"joints", {"a", "b"}},
                 {"gains/a/p", {"10"}}, {"gains/a/i", {"0"}}, {"gains/a/d", {"0"}}, {"gains/a/i_clamp", {"0"}},
                 {"gains/b/p", {"10"}}, {"gains/b/i", {"20"}}, {"gains/b/d", {"0"}}, {"gains/b/i_clamp", {"0.05"}},
                 {"constraints/goal_time", {"0.5"}}, {"constraints/stopped_velocity_tolerance", {"0"}},
                 {"constraints/a/trajectory", {"0.1"}}, {"constraints/a/goal", {"0.03"}},
                 {"constraints/b/trajectory", {"0.1"}}, {"constraints/b/goal", {"0.03"}}});
  start(rc, {"traj"});
  control::TrajGoal g;
  g.joint_names = {"a", "b"};
  g.points.push_back({{0.5, -0.5}, {}, {}, 2.0});
  std::string why;
  int code = 0;
  ASSERT_TRUE(trajectory_ctl(rc, "traj").set_trajectory(g, 7, w->time(), &why, &code)) << why;
  w->step(1000);  // t = 1 s
  EXPECT_NEAR(joint(*w, "tt", "a").position, 0.225, 2e-4);
  EXPECT_NEAR(joint(*w, "tt", "b").position, -0.23, 2e-4);
  EXPECT_NEAR(joint(*w, "tt", "a").velocity, 0.25, 1e-4);  // on the ramp the lag is constant: q' = v_d
  w->step(1000);  // t = 2 s
  EXPECT_NEAR(joint(*w, "tt", "a").position, 0.475, 2e-4);
  EXPECT_NEAR(joint(*w, "tt", "b").position, -0.48, 2e-4);
  EXPECT_TRUE(w->take_outputs<control::TrajectoryResultOutput>().empty());  // not before its time
  w->step(1);
  const auto results = w->take_outputs<control::TrajectoryResultOutput>();
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].goal, 7u);
  EXPECT_EQ(results[0].error_code, 0) << results[0].error_string;  // SUCCESSFUL
}

TEST(ControllerTypes, EffortTrajectoryHoldsTheArmAgainstGravityWithinItsConstraints) {
  // effort_controllers/JointTrajectoryController on the world-anchored arm (the acceptance case): one
  // point (shoulder, elbow) = (-0.5, 0.5) rad at 2 s: link1 raised 0.5 rad above horizontal (q > 0 points down),
  // link2 horizontal. Effort = p e + clamp(i sum(e dt)) + d de/dt, e = q_d - q.
  //   elbow, gains {p 500 N m/rad, i 0, d 20, i_clamp 0}: P only at rest, so it sags until p e balances gravity:
  //     tau_e = m2 g l2 cos(q1 + q2) = 1 kg * 9.8 * 0.5 m * cos(0.0098) = 4.900 N m -> e = 4.9 / 500 =
  //     0.0098 rad: elbow at 0.5 + 0.0098 = 0.5098 rad, effort -4.900 N m (pushing up).
  //   shoulder, gains {p 1000, i 2000, d 50, i_clamp 30 N m}: the integral takes the gravity torque (it is below
  //     the clamp), so the error goes to 0 (slowest pole about -i / p = -2 1/s: after 8 s at rest, e ~ 1e-9):
  //     tau_s = g (m1 l1/2 cos q1 + m2 (l1 cos q1 + l2/2 cos(q1 + q2))) = 9.8 * (0.5 cos 0.5 + cos 0.5 +
  //     0.5 cos 0.0098) = 9.8 * 1.81635 = 17.800 N m, effort -17.800 N m.
  // Constraints: path 0.2 rad, goal 0.02 rad (> 0.0098) per joint, stopped velocity 0.05 rad/s, goal_time 1 s:
  // the goal succeeds within 1 s after its time and the pose then holds inside the goal tolerance.
  auto w = world_with("arm.urdf", "arm");
  RosControl& rc = manager(*w, "arm");
  rc.load("js", "joint_state_controller/JointStateController", Params{{"publish_rate", {"10"}}});
  rc.load("traj", "effort_controllers/JointTrajectoryController",
          Params{{"joints", {"shoulder", "elbow"}},
                 {"gains/shoulder/p", {"1000"}}, {"gains/shoulder/i", {"2000"}}, {"gains/shoulder/d", {"50"}},
                 {"gains/shoulder/i_clamp", {"30"}},
                 {"gains/elbow/p", {"500"}}, {"gains/elbow/i", {"0"}}, {"gains/elbow/d", {"20"}},
                 {"gains/elbow/i_clamp", {"0"}},
                 {"constraints/goal_time", {"1.0"}}, {"constraints/stopped_velocity_tolerance", {"0.05"}},
                 {"constraints/shoulder/trajectory", {"0.2"}}, {"constraints/shoulder/goal", {"0.02"}},
                 {"constraints/elbow/trajectory", {"0.2"}}, {"constraints/elbow/goal", {"0.02"}}});
  start(rc, {"js", "traj"});
  control::TrajGoal g;
  g.joint_names = {"shoulder", "elbow"};
  g.points.push_back({{-0.5, 0.5}, {}, {}, 2.0});
  std::string why;
  int code = 0;
  ASSERT_TRUE(trajectory_ctl(rc, "traj").set_trajectory(g, 3, w->time(), &why, &code)) << why;
  w->step(3001);  // t = 3.001 s: the goal's time plus goal_time, plus the step that publishes
  const auto results = w->take_outputs<control::TrajectoryResultOutput>();
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].error_code, 0) << results[0].error_string;  // SUCCESSFUL, no path or goal violation
  EXPECT_GE(results[0].tick, 2001u);                                // not before its time
  w->step(7000);  // t = 10 s
  const double tau_e = 1.0 * kG * 0.5;                                                   // [N m]
  const double tau_s = kG * (0.5 * std::cos(0.5) + std::cos(0.5) + 0.5 * std::cos(tau_e / 500));  // [N m]
  EXPECT_NEAR(tau_s, 17.800, 1e-3);
  EXPECT_NEAR(joint(*w, "arm", "shoulder").position, -0.5, 1e-4);
  EXPECT_NEAR(joint(*w, "arm", "elbow").position, 0.5 + tau_e / 500, 1e-4);
  auto states = w->take_outputs<control::JointStatesOutput>();
  ASSERT_FALSE(states.empty());
  const auto& s = states.back();
  ASSERT_EQ(s.joints.size(), 2u);
  EXPECT_EQ(s.joints[0].name, "shoulder");
  EXPECT_EQ(s.joints[1].name, "elbow");
  EXPECT_NEAR(s.effort[0], -tau_s, 1e-3);
  EXPECT_NEAR(s.effort[1], -tau_e * std::cos(tau_e / 500), 1e-3);
}

// ---- starting at the first update (controller_manager's manageSwitch in update()) ---------------------------

// A world paused: the controllers are switched on, then the joints are set (spawn_model -J, set_model_configuration),
// then it plays. Each controller holds where the joints are at its first update, not where they were at the switch.
// The turntable's joints carry no gravity torque and no load, so a held joint stays at its command up to the
// solver's precision.
TEST(ControllerStart, APositionControllerHoldsTheJointWhereItIsAtItsFirstUpdate) {
  auto w = world_with("turntable.urdf", "tt");
  RosControl& rc = manager(*w, "tt");
  rc.load("a_pos", "position_controllers/JointPositionController", Params{{"joint", {"a"}}});
  start(rc, {"a_pos"});
  w->set_joint_positions("tt", {"a"}, {0.3});
  w->step(1000);
  EXPECT_NEAR(joint(*w, "tt", "a").position, 0.3, 1e-6);  // held 0 (the position at the switch) before the fix
}

TEST(ControllerStart, ATrajectoryControllerHoldsTheJointWhereItIsAtItsFirstUpdate) {
  auto w = world_with("turntable.urdf", "tt");
  RosControl& rc = manager(*w, "tt");
  rc.load("traj", "position_controllers/JointTrajectoryController", Params{{"joints", {"a", "b"}}});
  start(rc, {"traj"});
  w->set_joint_positions("tt", {"a", "b"}, {0.3, -0.2});
  w->step(1000);
  EXPECT_NEAR(joint(*w, "tt", "a").position, 0.3, 1e-6);
  EXPECT_NEAR(joint(*w, "tt", "b").position, -0.2, 1e-6);
}

TEST(ControllerStart, AnEffortPidPositionControllerHoldsTheJointWhereItIsAtItsFirstUpdate) {
  auto w = world_with("turntable.urdf", "tt");
  RosControl& rc = manager(*w, "tt");
  rc.load("a_pid", "effort_controllers/JointPositionController",
          Params{{"joint", {"a"}}, {"pid/p", {"100"}}, {"pid/i", {"0"}}, {"pid/d", {"10"}}});
  start(rc, {"a_pid"});
  w->set_joint_positions("tt", {"a"}, {0.3});
  w->step(1000);
  // no load: the set point is the position at starting, and the error stays 0
  EXPECT_NEAR(joint(*w, "tt", "a").position, 0.3, 1e-6);
}

TEST(ControllerStart, ACommandSentBeforeTheFirstUpdateIsKept) {
  // sent after the switch answered, while paused: starting() does not overwrite it (upstream's switch returns only
  // once the controller started, so a command after it is never lost)
  auto w = world_with("turntable.urdf", "tt");
  RosControl& rc = manager(*w, "tt");
  rc.load("a_pos", "position_controllers/JointPositionController", Params{{"joint", {"a"}}});
  start(rc, {"a_pos"});
  command(rc, "a_pos", {0.5});
  w->step(2000);
  EXPECT_NEAR(joint(*w, "tt", "a").position, 0.5, 1e-6);
}
