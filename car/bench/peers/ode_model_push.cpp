// ode_model_push: Gazebo 11's model_push example (examples/plugins/model_push: a 1 m cube pushed by
// Model::SetLinearVel(0.3, 0, 0) at every WorldUpdateBegin) on stock ODE (Debian libode-dev 0.16, double), as an
// independent reference for what car does with the same world (docs/PLUGINS.md "Gazebo's tutorials, built
// unchanged"). The cube is the world's <model name="box">: 1 x 1 x 1 m, no <inertial>, so SDF's default 1 kg and
// unit inertia; centre 0.5 m up on ground_plane. Gazebo 11's contact set-up for the pair (ODEPhysics::Collide):
// dContactApprox1 (pyramid friction), mu = min(1, 100) = 1 and mu2 = min(1, 50) = 1, kp 1e13 and kd 1 as soft
// ERP/CFM; the world of sdformat's defaults: quick solver, 50 iterations, SOR 1.3, 1 ms step, cfm 0, erp 0.2,
// contact max correcting vel 100, surface layer 0.001, up to 20 contacts a pair, gravity -9.8. Each step, in
// Gazebo's order: the plug-in's SetLinearVel (dBodySetLinearVel), then collision, then dWorldQuickStep.
//
// Build and run (not part of the build or CI; needs libode-dev):
//   g++ -O2 car/bench/peers/ode_model_push.cpp -lode -o /tmp/ode_model_push && /tmp/ode_model_push [SEED] [SECONDS]
// Prints, once a second: x and z of the cube's centre [m], its x speed [m/s], its pitch rate [rad/s] and its tilt
// [deg]. SEED (default 0) seeds ODE's random constraint order (dRandSetSeed); SECONDS defaults to 12.
#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace {
dWorldID world;
dJointGroupID contacts;

void near_callback(void*, dGeomID a, dGeomID b) {
  dContactGeom g[20];
  const int n = dCollide(a, b, 20, g, sizeof(dContactGeom));
  // [s], [N/m], [N s/m]: Gazebo's soft contact from kp and kd over one step
  const double h = 0.001, kp = 1e13, kd = 1.0;
  for (int i = 0; i < n; ++i) {
    dContact c{};
    c.geom = g[i];
    c.surface.mode = dContactSoftERP | dContactSoftCFM | dContactApprox1 | dContactMu2;
    c.surface.mu = 1.0;
    c.surface.mu2 = 1.0;
    c.surface.soft_erp = h * kp / (h * kp + kd);
    c.surface.soft_cfm = 1.0 / (h * kp + kd);
    dJointID j = dJointCreateContact(world, contacts, &c);
    dJointAttach(j, dGeomGetBody(g[i].g1), dGeomGetBody(g[i].g2));
  }
}
}  // namespace

int main(int argc, char** argv) {
  const unsigned long seed = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 0;
  const int steps = static_cast<int>((argc > 2 ? std::atof(argv[2]) : 12.0) * 1000.0);
  dInitODE2(0);
  dRandSetSeed(seed);
  world = dWorldCreate();
  dSpaceID space = dHashSpaceCreate(nullptr);
  contacts = dJointGroupCreate(0);
  dWorldSetGravity(world, 0, 0, -9.8);
  dWorldSetQuickStepNumIterations(world, 50);
  dWorldSetQuickStepW(world, 1.3);
  dWorldSetERP(world, 0.2);
  dWorldSetCFM(world, 0.0);
  dWorldSetContactMaxCorrectingVel(world, 100.0);
  dWorldSetContactSurfaceLayer(world, 0.001);
  dCreatePlane(space, 0, 0, 1, 0);
  dBodyID body = dBodyCreate(world);
  dMass m;
  dMassSetZero(&m);
  // [kg], [kg m^2]: SDF's defaults for a link without <inertial>
  m.mass = 1.0;
  m.I[0] = m.I[5] = m.I[10] = 1.0;
  dBodySetMass(body, &m);
  dBodySetPosition(body, 0, 0, 0.5);
  dGeomSetBody(dCreateBox(space, 1, 1, 1), body);
  for (int s = 1; s <= steps; ++s) {
    dBodySetLinearVel(body, 0.3, 0, 0);
    dSpaceCollide(space, nullptr, near_callback);
    dWorldQuickStep(world, 0.001);
    dJointGroupEmpty(contacts);
    if (s % 1000 != 0) continue;
    const dReal* p = dBodyGetPosition(body);
    const dReal* q = dBodyGetQuaternion(body);
    const dReal* v = dBodyGetLinearVel(body);
    const dReal* w = dBodyGetAngularVel(body);
    std::printf("t %4.1f s  x %.4f m  z %.4f m  vx %.4f m/s  wy %.4f rad/s  tilt %6.2f deg\n", s * 0.001, p[0], p[2],
                v[0], w[1], 2.0 * std::asin(std::min(1.0, std::hypot(q[1], q[2]))) * 180.0 / M_PI);
  }
  dWorldDestroy(world);
  dCloseODE();
}
