// Gazebo's surface rules on Bullet (private to the core; docs/COMPAT-physics.md): per-shape mu1/mu2 along fdir1,
// contact stiffness and damping from kp/kd, minDepth, maxVel, maxContacts and selfCollide. Surfaces hang off the
// Bullet collision objects (user pointer); a constraint solver converts the contacts that need these rules and
// leaves every other contact to Bullet.
#pragma once

#include <btBulletDynamicsCommon.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include <optional>
#include <vector>

#include "car_sim/model.hpp"

namespace car_sim {
namespace physics {

// Gazebo's contact defaults for a surface that sets nothing (sdf 1.6 surface.sdf, contact/ode).
constexpr double kDefaultKp = 1e12;  // [N/m]
constexpr double kDefaultKd = 1.0;   // [N s/m]

// One shape's surface.
struct Surface {
  double mu1 = 1.0, mu2 = 1.0;       // [-] Coulomb coefficients along friction directions 1 and 2
  std::optional<btVector3> fdir1;    // [-] unit first friction direction, collision-object frame
  std::optional<double> kp, kd;      // [N/m], [N s/m] per contact point
  std::optional<double> min_depth;   // [m] penetration allowed before correction
  std::optional<double> max_vel;     // [m/s] largest penetration-correction velocity
  std::optional<int> max_contacts;   // [-] most contact points per pair

  // Whether contacts with this surface need car's conversion whatever the other side is.
  bool needs_conversion() const;
  bool operator==(const Surface& o) const;
};

// The surfaces of one collision object: one per compound child, or one for the whole object.
struct SurfaceSet {
  std::vector<Surface> shapes;
  bool self_collide = false;  // a robot body: collides with the other bodies of its robot (but its joint's)
  bool convert = false;       // shapes differ, or one needs car's conversion

  // The surface of a compound child (Bullet's contact index); the first one for anything else.
  const Surface& at(int child) const;
  // Fills `convert` once the shapes are in.
  void finish();
};

// A link's surface from its <gazebo reference> block. shape_to_object: rotation from the shape (collision)
// frame to the collision object's frame, for fdir1.
Surface link_surface(const GazeboLinkExt& g, const Eigen::Matrix3d& shape_to_object);

// The surfaces of a collision object (set through its user pointer); nullptr for none.
const SurfaceSet* surfaces_of(const btCollisionObject* o);

// A robot body's collider: a multibody link collider with Gazebo's self-collision rule. Two bodies of one
// robot collide when either self-collides, except a body and its parent (the joint between them).
class SurfaceCollider : public btMultiBodyLinkCollider {
 public:
  SurfaceCollider(btMultiBody* mb, int link) : btMultiBodyLinkCollider(mb, link) {}
  bool checkCollideWithOverride(const btCollisionObject* co) const override;
};

// Bullet's multibody solver with car's conversion for the contacts whose pair needs Gazebo's surface rules
// (mu1 != mu2, fdir1, kp/kd, minDepth, maxVel, maxContacts, shapes of one body with different surfaces).
// Every other contact goes through Bullet's own conversion, unchanged.
// A contact without friction on either side (a ball caster's, mu 0) gets its normal row only: Bullet would add
// friction rows bounded to zero, which cost a Jacobian and an iteration each and never push.
class SurfaceSolver : public btMultiBodyConstraintSolver {
 public:
  void convertContacts(btPersistentManifold** manifolds, int count, const btContactSolverInfo& info) override;

 protected:
  btScalar solveGroupCacheFriendlyFinish(btCollisionObject** bodies, int count,
                                         const btContactSolverInfo& info) override;

 private:
  // rules: the pair needs Gazebo's surface rules; else it came here only for having no friction at all
  void convert(btPersistentManifold* m, const btContactSolverInfo& info, bool rules);
  btAlignedObjectArray<btPersistentManifold*> bullet_;
  btAlignedObjectArray<btPersistentManifold*> car_;
  btAlignedObjectArray<btPersistentManifold*> frictionless_;
  btAlignedObjectArray<int> no_friction_rows_;  // normal rows without friction rows
};

}  // namespace physics
}  // namespace car_sim
