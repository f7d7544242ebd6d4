// Four-wheel skid-steer bases driven through ros_control's diff_drive_controller (issue 29): car's fixtures
// test/data/skid/{husky,jackal}_like.urdf with Husky's and Jackal's geometry, contact keys and control.yaml
// multipliers (docs/COMPAT-physics.md "Skid steering").
//
// Expected yaw rate. diff_drive_controller turns a command (v, w) into wheel surface speeds
//   u_l = v - w m b,  u_r = v + w m b        [m/s]
// with b half the track and m the wheel_separation_multiplier. A skid-steer base whose wheels did not slip would
// turn at (u_r - u_l) / (2 b) = m w. Its wheels do slip: the contacts at (+-a, +-b) (a half the wheelbase) drag
// sideways while it turns. With equal loads N and a friction law that is the same in every direction of the ground
// plane (Coulomb's with mu N on each contact, or any law f = -c s), the steady turn has, by symmetry, equal slip
// speeds at the four contacts, so f_i = -k s_i with one k, and the slip of contact i is
//   s_i = (V - W y_i - u_i, W x_i)           (body forward speed V, yaw rate W, no side speed)
// Forces sum to zero:   sum (V - W y_i - u_i) = 0                  -> V = (u_l + u_r) / 2 = v
// Moments sum to zero:  sum [x_i (W x_i) - y_i (V - W y_i - u_i)] = 0
//                       -> W (4 a^2 + 4 b^2) = 2 b (u_r - u_l) = 4 b^2 m w
//                       -> W = w m b^2 / (a^2 + b^2)
// (the centripetal force m_robot V W is 2 % of the friction's, left out). For Husky (a = 0.256, b = 0.2854,
// m = 1.875) W = 0.519 rad/s, radius V / W = 0.962 m; for Jackal (a = 0.131, b = 0.1878, m = 1.5) W = 0.505 rad/s,
// radius 0.991 m: the multipliers Clearpath tuned in Gazebo are 1 + (a/b)^2 (1.80 and 1.49) to 4 % and 1 %.
// A friction limit per direction (a box: |f_x|, |f_y| <= mu N on their own) gives a different turn: the side forces
// saturate, their moment 4 a mu N needs only a/b < 1 of the wheels' longitudinal grip, so the wheels do not slip
// along and the base turns at m w (radius v / (m w): 0.53 m and 0.67 m).
#include <gtest/gtest.h>

#include <cmath>

#include "control_fixture.hpp"

using namespace car_sim;
using namespace car_sim::control_test;
using control::Params;

namespace {

struct Skid {
  const char* file;
  const char* name;
  double a, b, multiplier;
  double mu;  // the tyres' mu1 = mu2 [-]
};
constexpr Skid kHusky{"skid/husky_like.urdf", "husky", 0.256, 0.2854, 1.875, 1.0};
constexpr Skid kJackal{"skid/jackal_like.urdf", "jackal", 0.131, 0.187795, 1.5, 0.5};
// husky_like with husky_description's own centre of mass, 0.085 m to the right of the centre line
constexpr Skid kHuskyOffset{"skid/husky_offset.urdf", "husky", 0.256, 0.2854, 1.875, 1.0};

// The yaw rate [rad/s] of the derivation above for a command w [rad/s].
double expected_yaw_rate(const Skid& s, double w) { return w * s.multiplier * s.b * s.b / (s.a * s.a + s.b * s.b); }

std::unique_ptr<World> spawned(const Skid& s, double z) {
  auto w = std::make_unique<World>(empty_world());
  Eigen::Isometry3d pose = at(0, 0, 0);
  pose.translation().z() = z;
  w->spawn(load_urdf_file(data_path(s.file)), s.name, pose);
  return w;
}

control::DiffDriveController& drive(World& w, const Skid& s) {
  RosControl& rc = manager(w, s.name);
  rc.load("dd", "diff_drive_controller/DiffDriveController",
          Params{{"left_wheel", {"front_left_wheel", "rear_left_wheel"}},
                 {"right_wheel", {"front_right_wheel", "rear_right_wheel"}},
                 {"wheel_separation_multiplier", {std::to_string(s.multiplier)}},
                 {"cmd_vel_timeout", {"0.25"}}});
  start(rc, {"dd"});
  return *dynamic_cast<control::DiffDriveController*>(rc.controller("dd"));
}

// Drives (v, w) for `seconds` of sim time, the command repeated every 0.1 s (the YAMLs' timeout is 0.25 s).
void drive_for(World& w, control::DiffDriveController& dd, double v, double omega, double seconds) {
  const int chunks = static_cast<int>(std::lround(seconds / 0.1));
  for (int i = 0; i < chunks; ++i) {
    dd.set_twist(v, omega, w.time());
    w.step(static_cast<uint64_t>(std::lround(0.1 / w.dt())));
  }
}

double yaw(const ModelState& s) {
  const Eigen::Matrix3d& R = s.pose.linear();
  return std::atan2(R(1, 0), R(0, 0));
}

}  // namespace

// Yaw turned [rad] while driving (v, w) for `seconds`, summed over 0.1 s chunks (no wrap-around).
double turned(World& w, control::DiffDriveController& dd, const char* name, double v, double omega, double seconds) {
  double total = 0, last = yaw(w.model_state(name));
  const int chunks = static_cast<int>(std::lround(seconds / 0.1));
  for (int i = 0; i < chunks; ++i) {
    drive_for(w, dd, v, omega, 0.1);
    const double y = yaw(w.model_state(name));
    total += std::remainder(y - last, 2 * M_PI);
    last = y;
  }
  return total;
}

// A steady turn at (0.5 m/s, 0.5 rad/s): the base's speed V [m/s] and yaw rate W [rad/s], W averaged over 6 s
// after 2 s to settle (spawned at z = 0.3, settled 1 s).
struct Turn {
  double V, W;
};
Turn circle(const Skid& s) {
  auto w = spawned(s, 0.3);
  w->step(1000);
  auto& dd = drive(*w, s);
  drive_for(*w, dd, 0.5, 0.5, 2.0);
  const double W = turned(*w, dd, s.name, 0.5, 0.5, 6.0) / 6.0;
  return {w->model_state(s.name).linear.head<2>().norm(), W};
}

// The speed [m/s] after 3 s of (0.5 m/s, 0).
double straight(const Skid& s) {
  auto w = spawned(s, 0.3);
  w->step(1000);
  auto& dd = drive(*w, s);
  drive_for(*w, dd, 0.5, 0.0, 3.0);
  return w->model_state(s.name).linear.head<2>().norm();
}

// The probe of tools/real_robots_probe.py and bench/peers/ode_skid.cpp: spawned resting (base_link at its rest
// height), stood 1 s, driven (0.5 m/s, 0.5 rad/s) for 14 s; over the last 10 s, the mean of base_link's planar
// speed (sampled every 10 ms) and the mean yaw rate (yaw turned / 10 s).
Turn probe(const Skid& s, double rest_z) {
  auto w = spawned(s, rest_z);
  w->step(1000);
  auto& dd = drive(*w, s);
  drive_for(*w, dd, 0.5, 0.5, 4.0);
  double speed = 0, total = 0, last = yaw(w->model_state(s.name));
  for (int i = 0; i < 1000; ++i) {
    if (i % 10 == 0) dd.set_twist(0.5, 0.5, w->time());
    w->step(static_cast<uint64_t>(std::lround(0.01 / w->dt())));
    const ModelState& m = w->model_state(s.name);
    speed += m.linear.head<2>().norm();
    const double y = yaw(m);
    total += std::remainder(y - last, 2 * M_PI);
    last = y;
  }
  return {speed / 1000, total / 10.0};
}

// Issue 29's target: the ground-truth circle's radius V / W within 15 % of v / w = 1.0 m.
TEST(SkidSteer, HuskyLikeCircleRadiusWithin15PercentOfCommand) {
  const Turn t = circle(kHusky);
  EXPECT_NEAR(t.V / t.W, 1.0, 0.15);
}

TEST(SkidSteer, JackalLikeCircleRadiusWithin15PercentOfCommand) {
  const Turn t = circle(kJackal);
  EXPECT_NEAR(t.V / t.W, 1.0, 0.15);
}

// The turn rate against the derivation above. What it leaves out is the centripetal force m V W, a share
// V W / (mu g) of the friction available (g = 9.8): 0.25 / 9.8 = 2.6 % for Husky (mu 1), 5.1 % for Jackal
// (mu 0.5); that share is the tolerance on W. (A per-direction limit would turn at m w: +80 % and +49 %.)
TEST(SkidSteer, HuskyLikeTurnsAtTheDerivedYawRate) {
  const Turn t = circle(kHusky);
  const double W = expected_yaw_rate(kHusky, 0.5);
  EXPECT_NEAR(W, 0.5195, 1e-4);
  EXPECT_NEAR(t.W, W, W * 0.5 * 0.5 / (kHusky.mu * kG));
}

TEST(SkidSteer, JackalLikeTurnsAtTheDerivedYawRate) {
  const Turn t = circle(kJackal);
  const double W = expected_yaw_rate(kJackal, 0.5);
  EXPECT_NEAR(W, 0.5045, 1e-4);
  EXPECT_NEAR(t.W, W, W * 0.5 * 0.5 / (kJackal.mu * kG));
}

// The Husky-like base with husky_description's centre of mass (0.085 m to the right) against an independent
// reference: stock ODE 0.16 (bench/peers/ode_skid.cpp) with Gazebo 11's contact set-up (friction pyramid, fdir1
// turning with the wheel, kp/kd as soft ERP/CFM, quick solver 50 iterations SOR 1.3) on the same fixture with
// car's wheel rule (a wheel collides as a sphere: one point under its centre), driven and measured as here.
// Stock ODE cannot do Gazebo's split correction (velocities solved with the correction capped at max_vel
// 0.01 m/s, positions moved with the uncapped one), so it stands in for it two ways, which bracket Gazebo's:
// uncapped, R = 1.3109 m (sd 0.0229 over 16 seeds of ODE's random constraint order), and capped at 0.01 m/s (the
// tyres then sink), R = 2.7823 m (sd 0.0156) (`bench/peers/ode_skid.sh`: husky_offset_sphere, _cap0.01). car's
// run is deterministic; it agrees with ODE when it lies between the lower end's mean - 3 sd and the upper end's
// mean + 3 sd (99.7 % of ODE's own runs at either end, if normal): [1.2422, 2.8291] m. (With Gazebo's cylinder
// tyres ODE drives 1.49 to 2.05 m; with the centre of mass on the centre line car drives 0.969 m, below ODE's
// 1.19 to 1.55 m: docs/COMPAT-physics.md "Skid steering against stock ODE".) Spawned at its rest height.
TEST(SkidSteer, HuskyOffsetComCircleWithinODEsBracket) {
  const Turn t = probe(kHuskyOffset, 0.1651 - 0.03282);
  EXPECT_GT(t.V / t.W, 1.3109 - 3 * 0.0229);
  EXPECT_LT(t.V / t.W, 2.7823 + 3 * 0.0156);
}

// Issue 29's target: straight commands within 5 % of the commanded speed.
TEST(SkidSteer, HuskyLikeDrivesStraightAtCommandedSpeed) { EXPECT_NEAR(straight(kHusky), 0.5, 0.05 * 0.5); }

TEST(SkidSteer, JackalLikeDrivesStraightAtCommandedSpeed) { EXPECT_NEAR(straight(kJackal), 0.5, 0.05 * 0.5); }

// Husky as husky_gazebo spawns it, at z = 0 (wheels 0.132 m in the ground). Rest height of base_link: wheel
// radius - wheel joint height = 0.1651 - 0.03282 = 0.13228 m (less m g / (4 kp) = 14 um). Its base is lifted out
// and rests there (within 1 mm) from 2 s of sim time on (checked to 3 s). (At rest it reports a steady vertical
// speed of -3.86 mm/s that never moves it: ODE's capped velocity solve on soft tyres, 0.01 - N / (dt kp + kd);
// docs/COMPAT-physics.md "At rest on a soft contact", asserted in SurfaceContact.SoftContactAtRestKeepsODEsSinkSpeed.)
TEST(SkidSteer, HuskyLikeSpawnedInGroundRestsWithin2s) {
  const double rest = 0.1651 - 0.03282;
  auto w = spawned(kHusky, 0.0);
  w->step(2000);
  double worst = 0;
  for (int i = 0; i < 1000; ++i) {
    w->step(1);
    worst = std::max(worst, std::abs(w->model_state(kHusky.name).pose.translation().z() - rest));
  }
  EXPECT_LT(worst, 1e-3);
}

// Issue 29's target: spawned at z = 0 it never rises more than 0.05 m above its rest height (3 s watched).
TEST(SkidSteer, HuskyLikeSpawnedInGroundNeverRisesAboveRest) {
  const double rest = 0.1651 - 0.03282;
  auto w = spawned(kHusky, 0.0);
  double top = -1e9;
  for (int i = 0; i < 3000; ++i) {
    w->step(1);
    top = std::max(top, w->model_state(kHusky.name).pose.translation().z());
  }
  EXPECT_LT(top, rest + 0.05);
}
