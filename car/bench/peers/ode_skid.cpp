// ode_skid: an independent reference for car's skid-steer fixtures, on stock ODE (Debian libode-dev 0.16, double).
//
// Builds car's fixtures test/data/skid/husky_like.urdf and jackal_like.urdf as Gazebo 11 builds them for ODE
// (fixed joints lumped: one chassis body with its boxes; four wheel bodies with their cylinder collisions on hinge
// joints), with Gazebo 11's contact set-up for each pair (ODEPhysics::Collide): dContactApprox1 (each friction row
// bounded by mu times its contact's normal impulse), mu = min(mu_a, mu_b), mu2 likewise, kp in series and kd in
// parallel as soft ERP/CFM, fdir1 rotated by the collision's world rotation (so it turns with the wheel), and the
// world of sdformat's physics.sdf / worlds/empty.world: quick solver, 50 iterations, SOR 1.3, 1 ms step,
// cfm 0, erp 0.2, gravity -9.8, ground_plane's surface mu 100 / mu2 50. The wheels are driven as gazebo_ros_control's
// DefaultRobotHWSim drives a VelocityJointInterface joint: ODE's hinge velocity motor, dParamVel = command,
// dParamFMax = the URDF effort limit, which is DBL_MAX without a <limit>. The commands are diff_drive_controller's:
// separation = multiplier x the measured separation, with its speed limiter (velocity and acceleration limits).
//
// Spawned resting (base_link at its rest height), it stands 1 s, drives (v, w) for 14 s, stops 2 s, then (v, 0)
// for 8 s. Printed, as tools/real_robots_probe.py and car's skid tests measure the ground truth (base_link's
// origin): the circle's speed and yaw rate averaged over its last 10 s and R = speed / yaw rate; the straight
// run's displacement over its last 5 s / 5 s.
//
// Stock ODE differs from Gazebo's fork (deps/opende) where noted in docs/COMPAT-physics.md ("Skid steering
// against stock ODE"): no per-body max_vel / min_depth (the world's values are used), no split position
// correction (positions follow the solved velocities), no friction_model choice (stock ODE is the pyramid). The
// fork's split is stood in for two ways: max_vel=100 (the default: uncapped, as the fork's positions see it) and
// max_vel=0.01 (the surfaces' cap, as the fork's velocities see it; the tyres then sink).
//
// Usage: ode_skid [husky|jackal] [key=value ...]; keys: com_x, com_y [m] (the chassis' centre of mass in base_link,
// added to the fixture's), fdir (turning | world | none), wheel (cylinder | sphere), max_vel [m/s] (world contact
// max correcting velocity), layer [m] (contact surface layer), iters, sor, damping [1/step] (dWorldSetDamping),
// v [m/s], w [rad/s], seed, trace (1: print t, x, y, yaw, speed, yaw rate every 0.5 s).
#include <ode/ode.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace {

struct Box {
  double size[3];  // [m]
  double xyz[3];   // [m], base_link frame
};

// A fixture's numbers, as its URDF and control YAML give them.
struct Robot {
  const char *name;
  double base_mass;     // [kg]
  double base_inertia[3];  // [kg m^2], ixx iyy izz about the centre of mass
  double com[3];        // [m], base_link frame
  std::vector<Box> boxes;
  double wheel_mass;    // [kg]
  double wheel_inertia[3];  // [kg m^2], ixx iyy izz (spin axis y)
  double radius, width;  // [m], wheel cylinder
  double a, b, h;        // [m], wheel joints at (+-a, +-b, h) in base_link
  double mu;             // mu1 = mu2 of the tyres
  double kp, kd;         // [N/m], [N s/m] of the tyres
  double multiplier;     // wheel_separation_multiplier
  double max_v, max_acc_v, max_w, max_acc_w;  // diff_drive_controller limits [m/s, m/s^2, rad/s, rad/s^2]
};

Robot husky() {
  return Robot{"husky_like", 46.034, {0.6022, 1.7386, 2.0296}, {0, 0, 0.062},
               {{{0.9874, 0.5709, 0.12375}, {0, 0, 0.061875}}, {{0.78992, 0.5709, 0.10375}, {0, 0, 0.175625}}},
               2.637, {0.02467, 0.04411, 0.02467}, 0.1651, 0.1143, 0.256, 0.2854, 0.03282,
               1.0, 1e7, 1.0, 1.875, 1.0, 3.0, 2.0, 6.0};
}

Robot jackal() {
  return Robot{"jackal_like", 16.523, {0.3136, 0.3922, 0.4485}, {0, 0, 0.067},
               {{{0.42, 0.31, 0.184}, {0, 0, 0.092}}},
               0.477, {0.0013, 0.0024, 0.0013}, 0.098, 0.04, 0.131, 0.187795, 0.0345,
               0.5, 1e7, 1.0, 1.5, 2.0, 20.0, 4.0, 25.0};
}

// Gazebo's defaults for a surface that sets nothing (sdformat surface.sdf) and the ground plane's friction.
constexpr double kDefaultKp = 1e12, kDefaultKd = 1.0;
constexpr double kGroundMu = 100.0, kGroundMu2 = 50.0;
constexpr double kDt = 0.001;  // [s]

struct Options {
  double com_x = 0, com_y = 0;
  std::string fdir = "turning";
  std::string wheel = "cylinder";
  double max_vel = 100.0, layer = 0.0;
  int iters = 50;
  double sor = 1.3, damping = 0.0;
  double v = 0.5, w = 0.5;
  unsigned long seed = 0;
  bool trace = false;
};

struct Sim {
  Robot r;
  Options o;
  dWorldID world;
  dSpaceID space;
  dJointGroupID contacts;
  dGeomID ground;
  dBodyID base;
  dBodyID wheel[4];
  dGeomID wheel_geom[4];
  dJointID hinge[4];
  double com[3];  // [m], base_link frame: the chassis' centre of mass
};

bool is_wheel(const Sim &s, dGeomID g) {
  for (dGeomID w : s.wheel_geom)
    if (w == g) return true;
  return false;
}

void near_callback(void *data, dGeomID o1, dGeomID o2) {
  Sim &s = *static_cast<Sim *>(data);
  if (o1 != s.ground && o2 != s.ground) return;  // one model, no self-collision
  // The robot's collision first, the ground second (Gazebo's order puts either first; only fdir1's owner matters).
  if (o1 == s.ground) std::swap(o1, o2);
  dContact c[10];  // collision max_contacts default 10
  int n = dCollide(o1, o2, 10, &c[0].geom, sizeof(dContact));
  const bool tyre = is_wheel(s, o1);
  const double mu1 = tyre ? s.r.mu : 1.0, mu2 = tyre ? s.r.mu : 1.0;
  const double kp1 = tyre ? s.r.kp : kDefaultKp, kd1 = tyre ? s.r.kd : kDefaultKd;
  // Springs in series, dampers in parallel (ODEPhysics::Collide).
  const double kp = 1.0 / (1.0 / kp1 + 1.0 / kDefaultKp), kd = kd1 + kDefaultKd;
  for (int i = 0; i < n; ++i) {
    dContact &k = c[i];
    k.surface.mode = dContactMu2 | dContactSoftERP | dContactSoftCFM | dContactApprox1 | dContactSlip1 |
                     dContactSlip2;
    k.surface.mu = std::min(mu1, kGroundMu);
    k.surface.mu2 = std::min(mu2, kGroundMu2);
    k.surface.slip1 = 0;
    k.surface.slip2 = 0;
    k.surface.soft_erp = kDt * kp / (kDt * kp + kd);
    k.surface.soft_cfm = 1.0 / (kDt * kp + kd);
    if (tyre && s.o.fdir != "none") {
      // fdir1 = (1 0 0) in the collision frame
      double fd[3] = {1, 0, 0};
      if (s.o.fdir == "turning") {
        // rotated by the collision's world rotation, unprojected: it turns with the wheel
        const dReal *R = dGeomGetRotation(o1);
        fd[0] = R[0];
        fd[1] = R[4];
        fd[2] = R[8];
      } else {
        // "world": the chassis' heading, projected onto the ground (what a non-spinning frame would give)
        const dReal *R = dBodyGetRotation(s.base);
        double x = R[0], y = R[4], l = std::hypot(x, y);
        fd[0] = x / l;
        fd[1] = y / l;
        fd[2] = 0;
      }
      k.surface.mode |= dContactFDir1;
      k.fdir1[0] = fd[0];
      k.fdir1[1] = fd[1];
      k.fdir1[2] = fd[2];
    }
    dJointID j = dJointCreateContact(s.world, s.contacts, &k);
    dJointAttach(j, dGeomGetBody(k.geom.g1), dGeomGetBody(k.geom.g2));
  }
}

void build(Sim &s) {
  const Robot &r = s.r;
  s.world = dWorldCreate();
  s.space = dHashSpaceCreate(0);
  s.contacts = dJointGroupCreate(0);
  dWorldSetGravity(s.world, 0, 0, -9.8);
  dWorldSetERP(s.world, 0.2);
  dWorldSetCFM(s.world, 0.0);
  dWorldSetQuickStepNumIterations(s.world, s.o.iters);
  dWorldSetQuickStepW(s.world, s.o.sor);
  dWorldSetContactMaxCorrectingVel(s.world, s.o.max_vel);
  dWorldSetContactSurfaceLayer(s.world, s.o.layer);
  dWorldSetDamping(s.world, s.o.damping, s.o.damping);
  dWorldSetAutoDisableFlag(s.world, 0);
  s.ground = dCreatePlane(s.space, 0, 0, 1, 0);

  // base_link at rest: the wheels' centres at their radius [m], world frame
  const double base_z = r.radius - r.h;
  s.com[0] = r.com[0] + s.o.com_x;
  s.com[1] = r.com[1] + s.o.com_y;
  s.com[2] = r.com[2];
  s.base = dBodyCreate(s.world);
  dBodySetPosition(s.base, s.com[0], s.com[1], base_z + s.com[2]);
  dMass m;
  dMassSetParameters(&m, r.base_mass, 0, 0, 0, r.base_inertia[0], r.base_inertia[1], r.base_inertia[2], 0, 0, 0);
  dBodySetMass(s.base, &m);
  for (const Box &b : r.boxes) {
    dGeomID g = dCreateBox(s.space, b.size[0], b.size[1], b.size[2]);
    dGeomSetBody(g, s.base);
    dGeomSetOffsetPosition(g, b.xyz[0] - s.com[0], b.xyz[1] - s.com[1], b.xyz[2] - s.com[2]);
  }
  const double sx[4] = {1, 1, -1, -1}, sy[4] = {1, -1, 1, -1};  // front left, front right, rear left, rear right
  for (int i = 0; i < 4; ++i) {
    const double x = sx[i] * r.a, y = sy[i] * r.b, z = base_z + r.h;
    s.wheel[i] = dBodyCreate(s.world);
    dBodySetPosition(s.wheel[i], x, y, z);
    dMassSetParameters(&m, r.wheel_mass, 0, 0, 0, r.wheel_inertia[0], r.wheel_inertia[1], r.wheel_inertia[2], 0,
                       0, 0);
    dBodySetMass(s.wheel[i], &m);
    if (s.o.wheel == "sphere") {
      s.wheel_geom[i] = dCreateSphere(s.space, r.radius);
      dGeomSetBody(s.wheel_geom[i], s.wheel[i]);
    } else {
      // the cylinder's axis (ODE: local z) along y: collision rpy (pi/2, 0, 0)
      s.wheel_geom[i] = dCreateCylinder(s.space, r.radius, r.width);
      dGeomSetBody(s.wheel_geom[i], s.wheel[i]);
      dMatrix3 R;
      dRFromAxisAndAngle(R, 1, 0, 0, M_PI / 2);
      dGeomSetOffsetRotation(s.wheel_geom[i], R);
    }
    // Gazebo attaches (child, parent)
    s.hinge[i] = dJointCreateHinge(s.world, 0);
    dJointAttach(s.hinge[i], s.wheel[i], s.base);
    dJointSetHingeAnchor(s.hinge[i], x, y, z);
    dJointSetHingeAxis(s.hinge[i], 0, 1, 0);
    dJointSetHingeParam(s.hinge[i], dParamFMax, std::numeric_limits<double>::max());
    dJointSetHingeParam(s.hinge[i], dParamVel, 0);
  }
}

// base_link's origin [m] and its velocity [m/s], world frame
void base_link(const Sim &s, double p[3], double v[3]) {
  dVector3 wp, wv;
  dBodyGetRelPointPos(s.base, -s.com[0], -s.com[1], -s.com[2], wp);
  dBodyGetRelPointVel(s.base, -s.com[0], -s.com[1], -s.com[2], wv);
  for (int i = 0; i < 3; ++i) {
    p[i] = wp[i];
    v[i] = wv[i];
  }
}

double yaw(const Sim &s) {
  const dReal *R = dBodyGetRotation(s.base);
  return std::atan2(R[4], R[0]);
}

// diff_drive_controller's SpeedLimiter on one axis: velocity, then acceleration limit [per step]
double limit(double cmd, double prev, double max_v, double max_a) {
  double x = std::max(-max_v, std::min(max_v, cmd));
  double dv = std::max(-max_a * kDt, std::min(max_a * kDt, x - prev));
  return prev + dv;
}

struct Window {
  double speed = 0, yaw_rate = 0;
  long n = 0;
};

int run(const Robot &robot, const Options &o) {
  dRandSetSeed(o.seed);
  Sim s{robot, o};
  build(s);
  const Robot &r = s.r;
  // diff_drive_controller: separation = multiplier x the measured one, radius as measured
  const double sep = r.multiplier * 2 * r.b;
  const long rest = 1000, circle = 14000, stop = 2000, straight = 8000;
  const long total = rest + circle + stop + straight;
  double v_prev = 0, w_prev = 0;
  Window c, st;
  double p0[3] = {0, 0, 0}, p1[3] = {0, 0, 0}, zmin = 1e9, zmax = -1e9;
  for (long k = 0; k < total; ++k) {
    double v = 0, w = 0;
    if (k >= rest && k < rest + circle) {
      v = o.v;
      w = o.w;
    } else if (k >= rest + circle + stop) {
      v = o.v;
    }
    v_prev = limit(v, v_prev, r.max_v, r.max_acc_v);
    w_prev = limit(w, w_prev, r.max_w, r.max_acc_w);
    const double ul = (v_prev - w_prev * sep / 2) / r.radius, ur = (v_prev + w_prev * sep / 2) / r.radius;
    for (int i = 0; i < 4; ++i) dJointSetHingeParam(s.hinge[i], dParamVel, (i % 2 == 0) ? ul : ur);

    dSpaceCollide(s.space, &s, near_callback);
    dWorldQuickStep(s.world, kDt);
    dJointGroupEmpty(s.contacts);

    const long t = k + 1;  // steps done
    double p[3], pv[3];
    base_link(s, p, pv);
    zmin = std::min(zmin, p[2]);
    zmax = std::max(zmax, p[2]);
    if (t > rest + circle - 10000 && t <= rest + circle) {
      c.speed += std::hypot(pv[0], pv[1]);
      c.yaw_rate += dBodyGetAngularVel(s.base)[2];
      ++c.n;
    }
    if (t == total - 5000) std::memcpy(p0, p, sizeof p0);
    if (t == total) std::memcpy(p1, p, sizeof p1);
    if (o.trace && t % 500 == 0)
      std::printf("t %6.3f x %8.4f y %8.4f z %7.4f yaw %8.4f speed %7.4f yaw_rate %7.4f\n", t * kDt, p[0], p[1],
                  p[2], yaw(s), std::hypot(pv[0], pv[1]), dBodyGetAngularVel(s.base)[2]);
  }
  const double speed = c.speed / c.n, yaw_rate = c.yaw_rate / c.n;
  const double straight_speed = std::hypot(p1[0] - p0[0], p1[1] - p0[1]) / 5.0;
  std::printf("%s com (%.5f, %.5f) fdir %s wheel %s max_vel %g layer %g iters %d sor %g damping %g: "
              "circle (%.2f, %.2f): speed %.4f m/s, yaw rate %.4f rad/s, R = %.4f m; straight (%.2f, 0): "
              "%.4f m/s; base_link z in [%.5f, %.5f] m\n",
              r.name, s.com[0], s.com[1], o.fdir.c_str(), o.wheel.c_str(), o.max_vel, o.layer, o.iters, o.sor,
              o.damping, o.v, o.w, speed, yaw_rate, speed / yaw_rate, o.v, straight_speed, zmin, zmax);
  dJointGroupDestroy(s.contacts);
  dSpaceDestroy(s.space);
  dWorldDestroy(s.world);
  return 0;
}

}  // namespace

int main(int argc, char **argv) {
  dInitODE2(0);
  Robot r = husky();
  Options o;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "husky") {
      r = husky();
      continue;
    }
    if (a == "jackal") {
      r = jackal();
      continue;
    }
    const size_t eq = a.find('=');
    if (eq == std::string::npos) {
      std::fprintf(stderr, "ode_skid: %s: expected husky, jackal or key=value\n", a.c_str());
      return 2;
    }
    const std::string k = a.substr(0, eq), v = a.substr(eq + 1);
    if (k == "com_x") o.com_x = std::atof(v.c_str());
    else if (k == "com_y") o.com_y = std::atof(v.c_str());
    else if (k == "fdir") o.fdir = v;
    else if (k == "wheel") o.wheel = v;
    else if (k == "max_vel") o.max_vel = std::atof(v.c_str());
    else if (k == "layer") o.layer = std::atof(v.c_str());
    else if (k == "iters") o.iters = std::atoi(v.c_str());
    else if (k == "sor") o.sor = std::atof(v.c_str());
    else if (k == "damping") o.damping = std::atof(v.c_str());
    else if (k == "v") o.v = std::atof(v.c_str());
    else if (k == "w") o.w = std::atof(v.c_str());
    else if (k == "seed") o.seed = std::strtoul(v.c_str(), nullptr, 10);
    else if (k == "trace") o.trace = v == "1";
    else {
      std::fprintf(stderr, "ode_skid: %s: unknown key\n", k.c_str());
      return 2;
    }
  }
  if (o.fdir != "turning" && o.fdir != "world" && o.fdir != "none") {
    std::fprintf(stderr, "ode_skid: fdir: %s is not turning, world or none\n", o.fdir.c_str());
    return 2;
  }
  if (o.wheel != "cylinder" && o.wheel != "sphere") {
    std::fprintf(stderr, "ode_skid: wheel: %s is not cylinder or sphere\n", o.wheel.c_str());
    return 2;
  }
  int rc = run(r, o);
  dCloseODE();
  return rc;
}
