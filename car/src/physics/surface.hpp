// Gazebo's surface rules on Bullet (private to the core; docs/COMPAT-physics.md): per-shape mu1/mu2 along fdir1,
// contact stiffness and damping from kp/kd, minDepth, maxVel, maxContacts and selfCollide. Surfaces hang off the
// Bullet collision objects (user pointer); a constraint solver converts the contacts that need these rules and
// leaves every other contact to Bullet.
#pragma once

#include <btBulletDynamicsCommon.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include <optional>
#include <vector>

#include "car_sim/model.hpp"
#include "inverse_mass.hpp"
#include "physics.hpp"

namespace car_sim {
namespace physics {

// Gazebo's contact defaults for a surface that sets nothing (sdf 1.6 surface.sdf, contact/ode).
constexpr double kDefaultKp = 1e12;  // [N/m]
constexpr double kDefaultKd = 1.0;   // [N s/m]
// The correction velocity cap for a surface that sets no maxVel (surface.sdf contact/ode/max_vel), and the world's
// contact_max_correcting_vel (physics.sdf ode/constraints), which truncates every surface's.
constexpr double kDefaultMaxVel = 0.01;      // [m/s]
constexpr double kMaxCorrectingVel = 100.0;  // [m/s]

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

// Bullet's joint motor (velocity servo with an impulse cap), its row set up as Bullet's
// btMultiBodyJointMotor::createConstraintRows / fillMultiBodyConstraint do, the response from SurfaceSolver::response.
class JointMotor final : public btMultiBodyJointMotor {
 public:
  using btMultiBodyJointMotor::btMultiBodyJointMotor;
  void createConstraintRows(btMultiBodyConstraintArray& rows, btMultiBodyJacobianData& data,
                            const btContactSolverInfo& info) override;
};

// A robot body's collider: a multibody link collider with Gazebo's self-collision rule. Two bodies of one
// robot collide when either self-collides, except a body and its parent (the joint between them).
class SurfaceCollider : public btMultiBodyLinkCollider {
 public:
  SurfaceCollider(btMultiBody* mb, int link) : btMultiBodyLinkCollider(mb, link) {}
  bool checkCollideWithOverride(const btCollisionObject* co) const override;
};

// Bullet's multibody solver with car's conversion for the contacts whose pair needs Gazebo's surface rules
// (mu1 != mu2, fdir1, kp/kd, minDepth, maxVel, maxContacts, shapes of one body with different surfaces).
// Every other contact goes through Bullet's own conversion, its correction capped by Gazebo's default surface
// (max_vel 0.01 m/s) when a robot is on one side.
// A contact without friction on either side (a ball caster's, mu 0) gets its normal row only: Bullet would add
// friction rows bounded to zero, which cost a Jacobian and an iteration each and never push.
class SurfaceSolver : public btMultiBodyConstraintSolver {
 public:
  void convertContacts(btPersistentManifold** manifolds, int count, const btContactSolverInfo& info) override;

  void set_row_setup(RowSetup rows) { rows_ = rows; }
  // The mass matrices built before this solver's solves (nullptr: none), for inverse_mass.
  void set_inverse_source(const InverseMassSource* source) { source_ = source; }
  // Whether a multibody's free motion may come from its factored mass matrix (InverseMass::free_acceleration): the
  // rows are set up with factored matrices, so no row needs the caches of Bullet's free-motion pass.
  bool factored_free_motion(const btContactSolverInfo& info) const {
    return rows_ == RowSetup::factored && own_rows(info);
  }

  // The solver converting rows on this thread now (its joint constraints' rows are being made), or nullptr.
  static SurfaceSolver* converting();
  // A row's unit-impulse response delta = M^-1 jac of mb: from the factored matrix when this solve sets up its own
  // rows, else Bullet's Featherstone pass.
  void response(btMultiBody* mb, const btScalar* jac, btScalar* delta, btMultiBodyJacobianData& data);

 protected:
  btScalar solveGroupCacheFriendlyFinish(btCollisionObject** bodies, int count,
                                         const btContactSolverInfo& info) override;
  // Bullet's PGS iteration over the multibody rows (btMultiBodyConstraintSolver::solveSingleIteration: joint
  // rows, then normal rows, then friction rows bounded by their normal row's impulse), the same arithmetic in
  // the same order on raw arrays, so the same bits; Bullet's rigid-body pass only when it has rows. Modes this
  // does not cover (implicit cone friction) go to Bullet's.
  btScalar solveGroupCacheFriendlyIterations(btCollisionObject** bodies, int num_bodies,
                                             btPersistentManifold** manifolds, int num_manifolds,
                                             btTypedConstraint** constraints, int num_constraints,
                                             const btContactSolverInfo& info, btIDebugDraw* draw) override;
  btScalar solveSingleIteration(int iteration, btCollisionObject** bodies, int num_bodies,
                                btPersistentManifold** manifolds, int num_manifolds, btTypedConstraint** constraints,
                                int num_constraints, const btContactSolverInfo& info, btIDebugDraw* draw) override;

 private:
  // rules: the pair needs Gazebo's surface rules; else it came here only for having no friction at all
  void convert(btPersistentManifold* m, const btContactSolverInfo& info, bool rules);
 public:
  // One side of a row for the iterations, found once per solve: a multibody's Jacobian, unit-impulse response and
  // velocity changes (n = its 6 + dofs), or a rigid body that moves (body), or neither: no body, or Bullet's fixed
  // solver body (no original body), whose velocity changes stay zero and add +0 to the row's sum.
  struct Side {
    const btScalar* jac = nullptr;
    const btScalar* unit = nullptr;
    btScalar* dv = nullptr;
    int n = 0;
    btSolverBody* body = nullptr;
  };
  struct RowRef {
    Side a, b;
    // the row's shape: 0 any; 1 one multibody side (in a; the other side moves nothing); 2 two multibody sides
    int shape = 0;
  };
 private:
  // The sides of every multibody row, and the multibodies with rows (make_refs, before the iterations).
  void make_refs(const btContactSolverInfo& info);
  // One row (Bullet's resolveSingleConstraintRowGeneric); returns its velocity change, Bullet's residual term.
  btScalar resolve(const btMultiBodySolverConstraint& c, const RowRef& r);
  // Adds delta to a row's impulse and its bodies' velocity changes.
  void nudge(btMultiBodySolverConstraint& c, btScalar delta);
  // The unbounded impulse change [N s] a row asks for now (nothing applied).
  btScalar wanted(const btMultiBodySolverConstraint& c);
  // ODE's split correction: the capped part of each normal row's correction, solved on its own and given to the
  // multibodies as split velocities (positions only).
  void solve_push(const btContactSolverInfo& info);
  // The erp of a contact point's normal row (setup_row's rule).
  static double contact_erp(const btManifoldPoint& cp, const btContactSolverInfo& info);
  // ODE's cap on a point's correction: sets its distance to what the velocity solve corrects, returns the
  // correction velocity [m/s] held back for the split.
  static btScalar cap_depth(btManifoldPoint& cp, const btContactSolverInfo& info, double erp, double max_vel,
                            double min_depth);

  // ---- row set-up with factored mass matrices (docs/COMPAT-physics.md "Row set-up") ----
  // Whether this solve's contact rows are set up by car (Bullet's rules that car's set-up covers: no articulated
  // warm starting, no implicit cone friction).
  bool own_rows(const btContactSolverInfo& info) const;
  // The factored mass matrix of mb for this solve (built on first use); nullptr: Bullet's pass for mb.
  const InverseMass* inverse_mass(const btMultiBody* mb);
  // Bullet's setupMultiBodyContactConstraint (no articulated warm starting), each multibody side's unit-impulse
  // response M^-1 J^T from the factored matrix.
  void setup_row(btMultiBodySolverConstraint& c, const btVector3& normal, btManifoldPoint& cp,
                 const btContactSolverInfo& info, btScalar& relaxation, bool friction);
  // Bullet's fillContactJacobianMultiDof (fillConstraintJacobianMultiDof with no angular part), the same arithmetic
  // in the same order, with the multibody's rotations made once per solve (contact_frames) instead of once per row.
  void contact_jacobian(const btMultiBody* mb, int link, const btVector3& point, const btVector3& normal, btScalar* jac);
  struct ContactFrames {
    const btMultiBody* mb = nullptr;
    btMatrix3x3 base;                // btMatrix3x3(m_baseQuat): world -> base frame
    std::vector<btMatrix3x3> links;  // btMatrix3x3(m_cachedRotParentToThis): parent -> link frame
  };
  const ContactFrames& contact_frames(const btMultiBody* mb);
  // A friction row as Bullet's addMultiBodyFrictionConstraint, set up by setup_row.
  btMultiBodySolverConstraint& add_friction_row(const btVector3& dir, btPersistentManifold* m, int normal_index,
                                                btManifoldPoint& cp, btScalar relaxation,
                                                const btContactSolverInfo& info);
  // Bullet's convertMultiBodyContact with rows from setup_row (manifolds without spinning or rolling friction).
  void convert_bullet(btPersistentManifold* m, const btContactSolverInfo& info);
  // A row's bodies and link indices, as Bullet's converters fill them.
  void bind(btMultiBodySolverConstraint& c, btPersistentManifold* m, btManifoldPoint& cp, const btContactSolverInfo& info);

  RowSetup rows_ = RowSetup::factored;
  const InverseMassSource* source_ = nullptr;
  bool own_iterations_ = false;  // this solve's iterations ran car's pass (the multibodies' changes are held back)
  std::vector<std::pair<btMultiBody*, int>> touched_;  // multibodies with rows, their velocity-change offsets
  bool own_ = false;                 // this solve sets up its contact rows itself
  std::vector<InverseMass> inverse_;  // reused between solves
  int inverse_used_ = 0;
  const btMultiBody* last_body_ = nullptr;      // inverse_mass's last question this solve, and its answer
  const InverseMass* last_inverse_ = nullptr;
  std::vector<char> inverse_ok_;
  std::vector<ContactFrames> frames_;  // reused between solves
  int frames_used_ = 0;
  std::vector<int> chain_;             // a contact Jacobian's links, child to root
  btAlignedObjectArray<btPersistentManifold*> bullet_;
  btAlignedObjectArray<btPersistentManifold*> car_;
  btAlignedObjectArray<btPersistentManifold*> frictionless_;
  btAlignedObjectArray<int> no_friction_rows_;  // normal rows without friction rows
  struct PushRow {
    int row;             // normal row index
    btScalar rhs;        // [N s] impulse for the held-back correction velocity
    btScalar impulse;    // [N s] accumulated
  };
  std::vector<PushRow> push_;
  struct CappedPoint {
    btManifoldPoint* point;  // a point on Bullet's path whose correction the default cap limited
    btScalar distance;       // [m] its own distance, restored after its rows are made
    btScalar push;           // [m/s] correction velocity held back
  };
  std::vector<CappedPoint> capped_;
  std::vector<btScalar> push_dv_;  // split velocity changes, laid out as m_data.m_deltaVelocities
  std::vector<char> circle_;       // per friction row: first of a pair solved by Coulomb's isotropic law
  std::vector<RowRef> joint_refs_, normal_refs_, friction_refs_;  // per row of each kind (make_refs)
  std::vector<btMultiBody*> row_bodies_;                          // the multibodies with rows, each once
};

}  // namespace physics
}  // namespace car_sim
