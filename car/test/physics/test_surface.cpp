// Surface physics (docs/COMPAT-physics.md): friction on a slope, anisotropic friction along fdir1, contact
// stiffness from kp/kd, maxVel, per-link gravity and dampingFactor. Expected values are derived by hand in the
// comments; g = 10 m/s^2, dt = 1 ms.
#include <gtest/gtest.h>

#include "physics_fixtures.hpp"

using namespace car_sim;
using namespace car_sim::test_physics;

namespace {

// A 0.2 m cube of 1 kg on a slope of angle theta with the block's friction mu (the slope's is 100, and the
// pair takes the smaller). Returns the block's velocity along the slope (downhill positive) at 0.5 s and 1.5 s.
std::pair<double, double> slide(double theta, double mu) {
  physics::Physics p(slope(theta), options(), {});
  const RobotModel m = block(1.0, 0.2, 0.2, 0.2, fmt("<mu1>%g</mu1><mu2>%g</mu2>", mu, mu));
  // resting on the slope: the cube's centre 0.1 m above the slope's surface, turned with it
  const Eigen::Isometry3d T = pose(0, 0, 0, 0, -theta) * pose(0, 0, 0.1);
  physics::Robot& r = p.add_robot(m, "block", T, {});
  // downhill, world frame: the slope rises towards +x
  const Eigen::Vector3d down(-std::cos(theta), 0.0, -std::sin(theta));
  run(p, 500);
  const double v1 = r.root_state().linear.dot(down);
  run(p, 1000);
  return {v1, r.root_state().linear.dot(down)};
}

}  // namespace

TEST(SurfaceFriction, BlockSlidesDownSlopeAtGSinMinusMuCos) {
  // theta = 0.3 rad, mu = 0.2 < tan 0.3 = 0.3093: a = g (sin t - mu cos t) = 10 (0.295520 - 0.2 * 0.955336)
  // = 1.044529 m/s^2; over the second [0.5 s, 1.5 s] the speed grows by a * 1 s. Tolerance 1 %.
  const auto [v1, v2] = slide(0.3, 0.2);
  const double a = 10.0 * (std::sin(0.3) - 0.2 * std::cos(0.3));
  EXPECT_NEAR(a, 1.044529, 1e-6);
  EXPECT_NEAR(v2 - v1, a, 0.01 * a);
}

TEST(SurfaceFriction, BlockStaysOnSlopeWhenMuAboveTan) {
  // mu = 0.4 > tan 0.3 = 0.3093: static friction holds (needed mu g cos t >= g sin t); the block does not move.
  const auto [v1, v2] = slide(0.3, 0.4);
  EXPECT_NEAR(v1, 0.0, 1e-4);
  EXPECT_NEAR(v2, 0.0, 1e-4);
}

namespace {

// A flat 0.4 x 0.4 x 0.05 m plate of 1 kg, turned by `yaw`, with mu1 along its own x (fdir1 1 0 0) and mu2
// across, on ground with mu = mu2 = 1 (the pair takes the block's). It is pushed (given 1 m/s) along its own
// x (along = true) or y; returns its speed along the push after t_ms milliseconds.
double pushed(double mu1, double mu2, double yaw, bool along, int t_ms) {
  physics::Physics p(flat(1.0, 1.0), options(), {});
  const RobotModel m = block(1.0, 0.4, 0.4, 0.05, fmt("<mu1>%g</mu1><mu2>%g</mu2><fdir1>1 0 0</fdir1>", mu1, mu2));
  physics::Robot& r = p.add_robot(m, "plate", pose(0, 0, 0.025, yaw), {});
  run(p, 100);  // settle
  const Eigen::Vector3d dir = pose(0, 0, 0, yaw).linear() * (along ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY());
  ModelState s = r.root_state();
  s.linear = dir;
  r.set_root_state(s);
  run(p, t_ms);
  return r.root_state().linear.dot(dir);
}

}  // namespace

TEST(SurfaceFriction, AnisotropicSlidesAcrossFdir1Only) {
  // mu1 = 1 along the plate's x, mu2 = 0 across, plate turned by 0.5 rad (fdir1 is in the link's frame).
  // Pushed along its x: decelerates at mu1 g = 10 m/s^2 and stops within 0.1 s, so at 0.3 s v = 0.
  // Pushed along its y: no friction that way, so at 0.3 s still v = 1 m/s.
  EXPECT_NEAR(pushed(1.0, 0.0, 0.5, true, 300), 0.0, 1e-3);
  EXPECT_NEAR(pushed(1.0, 0.0, 0.5, false, 300), 1.0, 1e-3);
}

TEST(SurfaceFriction, EachDirectionDeceleratesWithItsOwnMu) {
  // mu1 = 1, mu2 = 0.3, turned by 0.5 rad. Across fdir1: a = mu2 g = 3 m/s^2, after 0.1 s v = 1 - 0.3 = 0.7.
  // Along fdir1: a = mu1 g = 10 m/s^2, after 0.05 s v = 1 - 0.5 = 0.5. Tolerance 2 % of the 1 m/s push.
  EXPECT_NEAR(pushed(1.0, 0.3, 0.5, false, 100), 0.7, 0.02);
  EXPECT_NEAR(pushed(1.0, 0.3, 0.5, true, 50), 0.5, 0.02);
}

TEST(SurfaceContact, KpSetsRestingPenetrationMgOver4Kp) {
  // A 1 kg plate resting flat touches the ground at its 4 corners: 4 contact springs in parallel, each with the
  // pair's kp = 1 / (1/kp + 1/1e12) ~ kp (the ground keeps Gazebo's default 1e12). At rest 4 kp d = m g:
  // kp = 2500 N/m -> d = 10 / 10000 = 1 mm; kp = 10000 N/m -> d = 0.25 mm. kd = 50 N s/m (+1 from the ground)
  // damps the bounce. The plate's centre rests at 0.025 - d; tolerance 2 % of d. maxVel 100: the spring's
  // correction velocity erp d / dt (~0.05 m/s here) stays under the cap (Gazebo's default 0.01 m/s would bind
  // and leave the plate deeper: docs/COMPAT-physics.md "Penetration: ODE's split correction").
  for (const double kp : {2500.0, 10000.0}) {
    physics::Physics p(flat(), options(), {});
    const RobotModel m = block(1.0, 0.4, 0.4, 0.05, fmt("<kp>%g</kp><kd>50</kd><maxVel>100</maxVel>", kp));
    physics::Robot& r = p.add_robot(m, "plate", pose(0, 0, 0.025), {});
    run(p, 3000);
    const double d = 1.0 * kG / (4.0 * kp);
    EXPECT_NEAR(0.025 - r.root_state().pose.translation().z(), d, 0.02 * d) << "kp " << kp;
  }
}

TEST(SurfaceContact, MaxVelCapsPenetrationCorrection) {
  // A plate started 20 mm deep in the ground with maxVel 0.1 m/s (no kp: Bullet's erp2 0.2 per step). The
  // velocity solve corrects at most 0.1 m/s; what the cap holds back moves positions only (ODE's split), so
  // the plate never moves up faster than 0.1 m/s (tolerance 1e-3) and is out of the ground (depth < 0.5 mm)
  // by 0.1 s, where the velocity-only cap would have lifted it 10 mm (still 10 mm deep).
  physics::Physics p(flat(), options(), {});
  const RobotModel m = block(1.0, 0.4, 0.4, 0.05, "<maxVel>0.1</maxVel>");
  physics::Robot& r = p.add_robot(m, "plate", pose(0, 0, 0.025 - 0.020), {});
  double fastest = -1;
  for (int i = 0; i < 100; ++i) {
    run(p, 1);
    fastest = std::max(fastest, r.root_state().linear.z());
  }
  EXPECT_LE(fastest, 0.1 + 1e-3);
  EXPECT_GT(r.root_state().pose.translation().z(), 0.025 - 5e-4);
}

TEST(SurfaceContact, MinDepthIsPenetrationLeftUncorrected) {
  // minDepth 5 mm: the contact corrects only depth - 5 mm. A plate started 3 mm deep is not pushed out (the
  // contact only stops it sinking further): after 0.5 s it is still 3 mm deep (tolerance 0.05 mm). Without
  // minDepth the same plate is pushed out to (nearly) no depth: < 0.1 mm.
  for (const bool min_depth : {true, false}) {
    physics::Physics p(flat(), options(), {});
    const RobotModel m = block(1.0, 0.4, 0.4, 0.05, min_depth ? "<minDepth>0.005</minDepth>" : "");
    physics::Robot& r = p.add_robot(m, "plate", pose(0, 0, 0.025 - 0.003), {});
    run(p, 500);
    const double depth = 0.025 - r.root_state().pose.translation().z();
    if (min_depth)
      EXPECT_NEAR(depth, 0.003, 5e-5);
    else
      EXPECT_LT(depth, 1e-4);
  }
}

TEST(SurfaceContact, MaxContactsZeroMakesNoContact) {
  // Gazebo keeps at most maxContacts points per pair: 0 keeps none, so the plate falls through the ground.
  // Free fall for 0.2 s (symplectic Euler): z = z0 - g dt^2 n (n + 1) / 2 = 0.025 - 10e-6 * 200 * 201 / 2 = -0.176.
  physics::Physics p(flat(), options(), {});
  const RobotModel m = block(1.0, 0.4, 0.4, 0.05, "<maxContacts>0</maxContacts>");
  physics::Robot& r = p.add_robot(m, "plate", pose(0, 0, 0.025), {});
  run(p, 200);
  EXPECT_NEAR(r.root_state().pose.translation().z(), 0.025 - kG * kDt * kDt * 200 * 201 / 2, 1e-9);
}

TEST(LinkPhysics, GravityOffFloats) {
  // Without ground: a link with <gravity>false</gravity> (or <turnGravityOff>true</turnGravityOff>) stays where
  // it is; one with gravity falls g dt^2 n (n + 1) / 2 = 10e-6 * 1000 * 1001 / 2 = 5.005 m in 1 s.
  for (const std::string g : {"<gravity>false</gravity>", "<turnGravityOff>true</turnGravityOff>", ""}) {
    physics::Physics p(world(""), options(), {});
    physics::Robot& r = p.add_robot(block(2.0, 0.1, 0.1, 0.1, g), "b", pose(0, 0, 1.0), {});
    run(p, 1000);
    const double fall = g.empty() ? kG * kDt * kDt * 1000 * 1001 / 2 : 0.0;
    EXPECT_NEAR(r.root_state().pose.translation().z(), 1.0 - fall, 1e-9) << g;
  }
}

TEST(LinkPhysics, DampingFactorDecaysVelocityPerStep) {
  // dampingFactor f: every step v <- v (1 - f) (ODE's linear damping scale). A floating link (gravity off)
  // pushed at 1 m/s with f = 0.01 has 0.99^100 = 0.366032 m/s after 100 steps.
  physics::Physics p(world(""), options(), {});
  physics::Robot& r =
      p.add_robot(block(2.0, 0.1, 0.1, 0.1, "<gravity>false</gravity><dampingFactor>0.01</dampingFactor>"), "b",
                  pose(0, 0, 1.0), {});
  ModelState s = r.root_state();
  s.linear = Eigen::Vector3d(1.0, 0.0, 0.0);
  r.set_root_state(s);
  run(p, 100);
  EXPECT_NEAR(r.root_state().linear.x(), std::pow(0.99, 100), 1e-9);
  EXPECT_NEAR(std::pow(0.99, 100), 0.366032, 1e-6);
}

TEST(SurfaceLoad, BadValuesNameTheBlockAndKey) {
  const std::string robot = "<robot name=\"r\"><link name=\"base\">" + box_inertial(1, 1, 1, 1) +
                            "</link><gazebo reference=\"base\">";
  const auto error = [&](const std::string& body) {
    try {
      load_urdf_string(robot + body + "</gazebo></robot>", "bad.urdf");
    } catch (const LoadError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error("<fdir1>1 0</fdir1>").find("gazebo[base]/fdir1"), std::string::npos);
  EXPECT_NE(error("<fdir1>1 0</fdir1>").find("not three numbers"), std::string::npos);
  EXPECT_NE(error("<kp>0</kp>").find("gazebo[base]/kp"), std::string::npos);
  EXPECT_NE(error("<maxContacts>2.5</maxContacts>").find("non-negative integer"), std::string::npos);
  EXPECT_NE(error("<minDepth>-1</minDepth>").find("gazebo[base]/minDepth"), std::string::npos);
  EXPECT_NE(error("<dampingFactor>x</dampingFactor>").find("bad.urdf"), std::string::npos);
}

TEST(SurfaceContact, DeepPenetrationIsLiftedOutNotThrown) {
  // docs/COMPAT-physics.md "Penetration: ODE's split correction". A 1 kg box with the tyres' kp 1e7, kd 1 (no
  // maxVel: Gazebo's 0.01 m/s), 0.2 m tall, started 0.1 m into the ground (its centre on the ground): 0.4 x 0.4
  // and a 0.2 m cube. The pair's kp = 1/(1/1e7 + 1/1e12) ~ 1e7, kd = 1 + 1 = 2, so erp = dt kp / (dt kp + kd) =
  // 1e4 / (1e4 + 2) ~ 1: the uncapped correction is 0.1 m * erp / dt ~ 100 m/s. The velocity solve takes at most
  // max_vel = 0.01 m/s of it, the positions the rest: the box is lifted out, its upward speed never above
  // 0.01 m/s (tolerance 1e-4), and by 1 s it rests at 0.1 - m g / (4 kp) = 0.1 - 2.5e-7 m (tolerance 0.1 mm),
  // never higher than that + 1 mm. Uncapped, as Bullet's own correction, it would leave the ground at ~100 m/s;
  // with one contact point per step (Bullet's plane algorithm without its multipoint option: docs "Contact
  // points") the cube's pushes, one corner at a time, overshoot by 12.5 mm.
  for (const double side : {0.4, 0.2}) {
    physics::Physics p(flat(), options(), {});
    const RobotModel m = block(1.0, side, side, 0.2, "<kp>1e7</kp><kd>1</kd>");
    physics::Robot& r = p.add_robot(m, "box", pose(0, 0, 0.1 - 0.1), {});
    double top = -1, fastest = -1;
    for (int i = 0; i < 1000; ++i) {
      run(p, 1);
      top = std::max(top, r.root_state().pose.translation().z());
      fastest = std::max(fastest, r.root_state().linear.z());
    }
    EXPECT_LE(fastest, 0.01 + 1e-4) << "side " << side;
    EXPECT_LE(top, 0.1 + 1e-3) << "side " << side;
    EXPECT_NEAR(r.root_state().pose.translation().z(), 0.1, 1e-4) << "side " << side;
  }
}

TEST(SurfaceContact, UnkeyedPairIsLiftedOutNotThrown) {
  // docs/COMPAT-physics.md "Penetration", "Every pair": Gazebo's default surface caps every contact's correction
  // at max_vel 0.01 m/s, also where the description sets no key. A plain 1 kg box (no <gazebo> keys: Bullet's rows,
  // erp2 0.2), 0.4 x 0.4 x 0.2 m, started 0.1 m into the ground. Uncapped, the correction 0.2 * 0.1 m / 1 ms =
  // 20 m/s throws it. Capped, its upward speed never exceeds 0.01 m/s (tolerance 1e-4); the split moves it out by
  // 20 % of the depth a step, 0.1 m * 0.8^n < 1 um after 52 steps, so it rests at 0.1 m (tolerance 0.1 mm) by
  // 0.5 s and never rises above that + 1 mm.
  physics::Physics p(flat(), options(), {});
  const RobotModel m = block(1.0, 0.4, 0.4, 0.2, "");
  physics::Robot& r = p.add_robot(m, "box", pose(0, 0, 0.1 - 0.1), {});
  double top = -1, fastest = -1;
  for (int i = 0; i < 500; ++i) {
    run(p, 1);
    top = std::max(top, r.root_state().pose.translation().z());
    fastest = std::max(fastest, r.root_state().linear.z());
  }
  EXPECT_LE(fastest, 0.01 + 1e-4);
  EXPECT_LE(top, 0.1 + 1e-3);
  EXPECT_NEAR(r.root_state().pose.translation().z(), 0.1, 1e-4);
}

TEST(SurfaceContact, SoftContactAtRestKeepsODEsSinkSpeed) {
  // docs/COMPAT-physics.md "At rest on a soft contact": the capped velocity solve reads J v + (cfm / dt) lambda =
  // min(c, max_vel) with lambda = N dt at rest, so the body's vertical velocity is max_vel - N / (dt kp + kd) while
  // the split holds its position (Gazebo's quickstep: velocities from the capped solve). A 1 kg, 0.4 x 0.4 x 0.05 m
  // plate with kp 1e5, kd 1 on its 4 corners: N = 10 / 4 = 2.5 N; the pair's kp = 1 / (1/1e5 + 1/1e12), kd = 2,
  // dt kp + kd = 101.9999999 (1e-12 relative below 102); speed 0.01 - 2.5 / 101.9999999 = -0.0145098 m/s (tolerance
  // 1e-6), and its height steady (moved < 1e-9 m over the last 0.1 s).
  physics::Physics p(flat(), options(), {});
  const RobotModel m = block(1.0, 0.4, 0.4, 0.05, "<kp>1e5</kp><kd>1</kd>");
  physics::Robot& r = p.add_robot(m, "plate", pose(0, 0, 0.025), {});
  run(p, 900);
  const double z0 = r.root_state().pose.translation().z();
  run(p, 100);
  const double kp = 1.0 / (1.0 / 1e5 + 1.0 / 1e12);
  EXPECT_NEAR(r.root_state().linear.z(), 0.01 - 2.5 / (kDt * kp + 2.0), 1e-6);
  EXPECT_NEAR(r.root_state().pose.translation().z(), z0, 1e-9);
}

TEST(SurfaceFriction, EqualMuSlidesAgainstItsSlip) {
  // docs/COMPAT-physics.md "Skid steering": with mu1 = mu2 (here 0.5, fdir1 1 0 0 so car converts the pair) the
  // friction force of a sliding contact is mu N against its slip, whatever fdir1 says. The plate pushed at 1 m/s
  // 30 deg off fdir1 decelerates at mu g = 5 m/s^2 along its own velocity: after 0.08 s it moves at
  // 1 - 0.4 = 0.6 m/s, still 30 deg off: (0.6 cos 30, 0.6 sin 30) = (0.5196, 0.3). A friction limit per direction
  // (a pyramid: each row mu N on its own) would slow each component at 5 m/s^2: (0.466, 0.1). Tolerance 0.01.
  physics::Physics p(flat(1.0, 1.0), options(), {});
  const RobotModel m = block(1.0, 0.4, 0.4, 0.05, "<mu1>0.5</mu1><mu2>0.5</mu2><fdir1>1 0 0</fdir1>");
  physics::Robot& r = p.add_robot(m, "plate", pose(0, 0, 0.025), {});
  run(p, 100);  // settle
  ModelState s = r.root_state();
  s.linear = Eigen::Vector3d(std::cos(M_PI / 6), std::sin(M_PI / 6), 0);
  r.set_root_state(s);
  run(p, 80);
  EXPECT_NEAR(r.root_state().linear.x(), 0.6 * std::cos(M_PI / 6), 0.01);
  EXPECT_NEAR(r.root_state().linear.y(), 0.6 * std::sin(M_PI / 6), 0.01);
}
