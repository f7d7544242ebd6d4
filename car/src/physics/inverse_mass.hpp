// The joint-space mass matrix of a Bullet multibody, factored once per step, for the free motion, the contact rows'
// Jacobians and their unit-impulse responses (private to the core; docs/COMPAT-physics.md "Row set-up", "Free
// motion"). Bullet computes each row's response M^-1 J^T with a pass of Featherstone's algorithm over the whole tree
// (btMultiBody::calcAccelerationDeltasMultiDof, two thirds of a car's row set-up) and the free accelerations with
// three more; here M is built once from the same cached frames Bullet's passes use, factored (Cholesky), and each
// row costs two triangular solves.
#pragma once

#include <BulletDynamics/Featherstone/btMultiBody.h>

#include <vector>

namespace car_sim {
namespace physics {

class InverseMass {
 public:
  // M of mb's present configuration, in Bullet's generalised velocities (base angular and linear velocity of the
  // base's centre of mass, world frame, then the joint rates), from the frames Bullet caches with each link's joint
  // position (m_cachedRotParentToThis, m_cachedRVector, the joint axes). false (use Bullet's pass) for a kinematic
  // base or link, or a matrix that is not positive definite.
  bool build(const btMultiBody& mb);

  // x = M^-1 f for 6 + dofs entries (Bullet's layout: base torque [N m] and force [N], world frame, then the joint
  // efforts); a fixed base gets zero base entries, as in Bullet's pass.
  void solve(const btScalar* f, btScalar* x) const;

  const btMultiBody* body() const { return mb_; }

  // The Jacobian of a point contact for the last successful build (6 + dofs entries, Bullet's layout): the rate of
  // n . (velocity of the point p fixed to `link`, -1 the base) per generalised velocity, p [m] and n (unit) in
  // the world frame. Bullet's fillContactJacobianMultiDof gives the same numbers through each frame from the base
  // out; false for a multibody with a joint of several degrees of freedom (use Bullet's).
  bool contact_jacobian(int link, const btVector3& p, const btVector3& n, btScalar* jac) const;

  // Whether free_acceleration gives mb's free accelerations: every joint revolute, prismatic or fixed (one or no
  // degree of freedom) and no joint reporting its forces (Bullet's pass computes those along the way).
  static bool free_motion_supported(const btMultiBody& mb);

  // qdd = M^-1 (tau - c(q, qd)) for the M of the last successful build: the accelerations Bullet's free-motion
  // pass (computeAccelerationsArticulatedBodyAlgorithmMultiDof, no constraint forces) computes, in its layout (base
  // angular and linear acceleration of the base's centre of mass, world frame, then the joint accelerations), from
  // the applied forces and torques, the joint efforts, gravity's share of those, Bullet's damping and gyroscopic
  // terms, and the velocity-product accelerations of the tree. The same dynamics by another route: the rows' M,
  // already factored, and one pass over the bodies instead of Featherstone's three (docs/COMPAT-physics.md "Free
  // motion").
  void free_acceleration(const btMultiBody& mb, btScalar* qdd);

 private:
  const btMultiBody* mb_ = nullptr;
  int n_ = 0;    // 6 + dofs
  int off_ = 0;  // 6 with a fixed base: its rows and columns are left out of M
  std::vector<double> l_;  // lower Cholesky factor of M[off_.., off_..], row major, (n_-off_)^2
  std::vector<double> inv_diag_;  // 1 / its diagonal
  // per body (0 the base, 1 + i link i): world rotation (frame to world) and centre of mass [m]
  std::vector<btMatrix3x3> rot_;
  std::vector<btVector3> com_;
  // per generalised velocity column and body: angular [rad/s] and linear [m/s] world velocity of that body
  std::vector<btVector3> w_, u_;
  std::vector<int> cols_;  // a body's non-zero columns
  // per body: inertia about the centre of mass, world frame [kg m^2]; per dof: its spatial axis (angular, linear
  // part) in the world frame
  std::vector<btMatrix3x3> iw_;
  std::vector<btVector3> top_, bottom_;
  bool one_dof_joints_ = true;  // no joint of several degrees of freedom (contact_jacobian's rule)

  // f(k, a, u) for each degree of freedom k of `link` and its ancestors: a unit rate of k turns a point p fixed to
  // `link` with a (world) and moves it with u = b_k + a x (p - c_j), c_j the centre of mass of k's link
  template <class F>
  void for_each_dof_above(int link, const btVector3& p, F&& f) const;
  // free_acceleration's per body: angular velocity [rad/s] and centre-of-mass velocity [m/s], their rates with no
  // joint acceleration [rad/s^2], [m/s^2], world frame; and the generalised force [N m | N]
  std::vector<btVector3> omega_, vel_, alpha_, acc_;
  std::vector<double> force_;
};

// Where a solver finds the mass matrices this step's free-motion pass built and factored already (IslandWorld), so
// that the rows reuse them instead of building them again from the same frames.
class InverseMassSource {
 public:
  virtual ~InverseMassSource() = default;
  // mb's matrix of this step, or nullptr (the solver builds its own)
  virtual const InverseMass* built(const btMultiBody* mb) const = 0;
};

}  // namespace physics
}  // namespace car_sim
