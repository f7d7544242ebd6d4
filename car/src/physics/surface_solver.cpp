// SurfaceSolver's iterations (surface.hpp): Bullet's projected Gauss-Seidel over the rows, car's resolve with the
// rows' responses referenced once, the solve of the pushes ODE's depth cap holds back, and Bullet's finish.
#include <algorithm>
#include <cmath>

#include "row_math.hpp"
#include "surface.hpp"

namespace car_sim {
namespace physics {

// Bullet's finish reads two friction rows at every normal row's friction index: normal rows without friction
// rows point at two idle rows (no body, no impulse) appended here, which write back nothing.
btScalar SurfaceSolver::solveGroupCacheFriendlyFinish(btCollisionObject** bodies, int count,
                                                     const btContactSolverInfo& info) {
  if (no_friction_rows_.size()) {
    const int idle = m_multiBodyFrictionContactConstraints.size();
    for (int k = 0; k < 2; ++k) {
      btMultiBodySolverConstraint& c = m_multiBodyFrictionContactConstraints.expand();
      c.m_orgConstraint = nullptr;
      c.m_multiBodyA = c.m_multiBodyB = nullptr;
      c.m_appliedImpulse = 0;
    }
    for (int i = 0; i < no_friction_rows_.size(); ++i)
      m_multiBodyNormalContactConstraints[no_friction_rows_[i]].m_frictionIndex = idle;
  }
  return btMultiBodyConstraintSolver::solveGroupCacheFriendlyFinish(bodies, count, info);
}

// Bullet's iterations, then each multibody's accumulated velocity change handed to it once. Bullet adds every row's
// change to the multibody (applyDeltaVeeMultiDof2) as well as to the solver's array, the same terms in the same
// order from zero; nothing reads the multibody's copy before the iterations end (Bullet's own comment says as
// much), so adding the array once at the end gives it the same bits.
btScalar SurfaceSolver::solveGroupCacheFriendlyIterations(btCollisionObject** bodies, int num_bodies,
                                                          btPersistentManifold** manifolds, int num_manifolds,
                                                          btTypedConstraint** constraints, int num_constraints,
                                                          const btContactSolverInfo& info, btIDebugDraw* draw) {
  own_iterations_ = false;
  make_refs(info);
  const btScalar r = btMultiBodyConstraintSolver::solveGroupCacheFriendlyIterations(
      bodies, num_bodies, manifolds, num_manifolds, constraints, num_constraints, info, draw);
  if (!own_iterations_) return r;
  touched_.clear();
  auto note = [&](btMultiBody* mb, int index) {
    if (!mb) return;
    for (const auto& t : touched_)
      if (t.first == mb) return;
    touched_.emplace_back(mb, index);
  };
  for (const auto* rows : {&m_multiBodyNonContactConstraints, &m_multiBodyNormalContactConstraints,
                           &m_multiBodyFrictionContactConstraints})
    for (int i = 0; i < rows->size(); ++i) {
      note((*rows)[i].m_multiBodyA, (*rows)[i].m_deltaVelAindex);
      note((*rows)[i].m_multiBodyB, (*rows)[i].m_deltaVelBindex);
    }
  for (const auto& t : touched_) t.first->applyDeltaVeeMultiDof2(&m_data.m_deltaVelocities[t.second], btScalar(1));
  solve_push(info);
  return r;
}

// ODE's split correction (Gazebo's quickstep: the velocity solve's correction is capped by max_vel, the positions
// move with the uncapped one, and the velocities then drop it again): what the cap held back is solved as a
// second problem on the normal rows alone (impulses >= 0, no friction), its velocity change handed to each
// multibody as its split velocity, which the position step adds and then removes (IslandWorld::integrate).
void SurfaceSolver::solve_push(const btContactSolverInfo& info) {
  if (push_.empty()) return;
  push_dv_.assign(m_data.m_deltaVelocities.size(), 0);
  const btScalar* jac = &m_data.m_jacobians[0];
  const btScalar* unit = &m_data.m_deltaVelocitiesUnitImpulse[0];
  for (int it = 0; it < info.m_numIterations; ++it) {
    btScalar change = 0;
    for (auto& r : push_) {
      const btMultiBodySolverConstraint& c = m_multiBodyNormalContactConstraints[r.row];
      btScalar dv = 0;
      int na = 0, nb = 0;
      if (c.m_multiBodyA) {
        na = c.m_multiBodyA->getNumDofs() + 6;
        dv = add_dot(dv, jac + c.m_jacAindex, &push_dv_[c.m_deltaVelAindex], na);
      }
      if (c.m_multiBodyB) {
        nb = c.m_multiBodyB->getNumDofs() + 6;
        dv = add_dot(dv, jac + c.m_jacBindex, &push_dv_[c.m_deltaVelBindex], nb);
      }
      btScalar delta = r.rhs - dv * c.m_jacDiagABInv;
      if (r.impulse + delta < 0) delta = -r.impulse;
      r.impulse += delta;
      for (int i = 0; i < na; ++i) push_dv_[c.m_deltaVelAindex + i] += unit[c.m_jacAindex + i] * delta;
      for (int i = 0; i < nb; ++i) push_dv_[c.m_deltaVelBindex + i] += unit[c.m_jacBindex + i] * delta;
      change = btMax(change, delta * delta);
    }
    if (change <= info.m_leastSquaresResidualThreshold) break;
  }
  std::vector<std::pair<btMultiBody*, int>> pushed;
  for (const auto& r : push_) {
    const btMultiBodySolverConstraint& c = m_multiBodyNormalContactConstraints[r.row];
    for (auto [mb, index] : {std::make_pair(c.m_multiBodyA, c.m_deltaVelAindex),
                             std::make_pair(c.m_multiBodyB, c.m_deltaVelBindex)}) {
      if (!mb) continue;
      bool seen = false;
      for (const auto& q : pushed) seen = seen || q.first == mb;
      if (seen) continue;
      pushed.emplace_back(mb, index);
      mb->applyDeltaSplitVeeMultiDof(&push_dv_[index], btScalar(1));
    }
  }
}

// The unbounded impulse change [N s] a row asks for now (resolve's first part; nothing applied).
btScalar SurfaceSolver::wanted(const btMultiBodySolverConstraint& c) {
  btScalar delta = c.m_rhs - btScalar(c.m_appliedImpulse) * c.m_cfm;
  const btScalar* jac = &m_data.m_jacobians[0];
  const btScalar* dv = &m_data.m_deltaVelocities[0];
  btScalar dva = 0, dvb = 0;
  if (c.m_multiBodyA) dva = add_dot(dva, jac + c.m_jacAindex, dv + c.m_deltaVelAindex, c.m_multiBodyA->getNumDofs() + 6);
  else if (c.m_solverBodyIdA >= 0) {
    btSolverBody& b = m_tmpSolverBodyPool[c.m_solverBodyIdA];
    dva += c.m_contactNormal1.dot(b.internalGetDeltaLinearVelocity()) + c.m_relpos1CrossNormal.dot(b.internalGetDeltaAngularVelocity());
  }
  if (c.m_multiBodyB) dvb = add_dot(dvb, jac + c.m_jacBindex, dv + c.m_deltaVelBindex, c.m_multiBodyB->getNumDofs() + 6);
  else if (c.m_solverBodyIdB >= 0) {
    btSolverBody& b = m_tmpSolverBodyPool[c.m_solverBodyIdB];
    dvb += c.m_contactNormal2.dot(b.internalGetDeltaLinearVelocity()) + c.m_relpos2CrossNormal.dot(b.internalGetDeltaAngularVelocity());
  }
  delta -= dva * c.m_jacDiagABInv;
  delta -= dvb * c.m_jacDiagABInv;
  return delta;
}

// Adds an impulse change to a row's bodies (resolve's last part).
void SurfaceSolver::nudge(btMultiBodySolverConstraint& c, btScalar delta) {
  c.m_appliedImpulse += delta;
  const btScalar* unit = &m_data.m_deltaVelocitiesUnitImpulse[0];
  btScalar* dv = &m_data.m_deltaVelocities[0];
  if (c.m_multiBodyA) {
    const int na = c.m_multiBodyA->getNumDofs() + 6;
    for (int i = 0; i < na; ++i) dv[c.m_deltaVelAindex + i] += unit[c.m_jacAindex + i] * delta;
  } else if (c.m_solverBodyIdA >= 0) {
    btSolverBody& b = m_tmpSolverBodyPool[c.m_solverBodyIdA];
    b.internalApplyImpulse(c.m_contactNormal1 * b.internalGetInvMass(), c.m_angularComponentA, delta);
  }
  if (c.m_multiBodyB) {
    const int nb = c.m_multiBodyB->getNumDofs() + 6;
    for (int i = 0; i < nb; ++i) dv[c.m_deltaVelBindex + i] += unit[c.m_jacBindex + i] * delta;
  } else if (c.m_solverBodyIdB >= 0) {
    btSolverBody& b = m_tmpSolverBodyPool[c.m_solverBodyIdB];
    b.internalApplyImpulse(c.m_contactNormal2 * b.internalGetInvMass(), c.m_angularComponentB, delta);
  }
}

// The sides of every multibody row (pointers into the solver's arrays, which keep their size through the
// iterations), and the multibodies with rows, each once.
void SurfaceSolver::make_refs(const btContactSolverInfo& info) {
  btScalar* jac = m_data.m_jacobians.size() ? &m_data.m_jacobians[0] : nullptr;
  btScalar* unit = m_data.m_deltaVelocitiesUnitImpulse.size() ? &m_data.m_deltaVelocitiesUnitImpulse[0] : nullptr;
  btScalar* dv = m_data.m_deltaVelocities.size() ? &m_data.m_deltaVelocities[0] : nullptr;
  row_bodies_.clear();
  // the bodies Bullet's iteration marks: those of the joint rows (when it solves them) and of the contact rows (a
  // friction row's are its normal row's)
  bool mark = false;
  auto side = [&](btMultiBody* mb, int jac_index, int vel_index, int body_id) {
    Side r;
    if (mb) {
      r.n = mb->getNumDofs() + 6;
      r.jac = jac + jac_index;
      r.unit = unit + jac_index;
      r.dv = dv + vel_index;
      if (mark && std::find(row_bodies_.begin(), row_bodies_.end(), mb) == row_bodies_.end()) row_bodies_.push_back(mb);
    } else if (body_id >= 0) {
      btSolverBody& b = m_tmpSolverBodyPool[body_id];
      if (b.m_originalBody) r.body = &b;
    }
    return r;
  };
  auto refs = [&](const btMultiBodyConstraintArray& rows, std::vector<RowRef>& out) {
    out.resize(rows.size());
    for (int i = 0; i < rows.size(); ++i) {
      const btMultiBodySolverConstraint& c = rows[i];
      out[i].a = side(c.m_multiBodyA, c.m_jacAindex, c.m_deltaVelAindex, c.m_solverBodyIdA);
      out[i].b = side(c.m_multiBodyB, c.m_jacBindex, c.m_deltaVelBindex, c.m_solverBodyIdB);
      RowRef& r = out[i];
      // a multibody side whose Jacobian and response are all zero (a joint motor's second side) adds only zeros to
      // the sums and velocities: left out, which changes no finite value (a state already infinite stays
      // non-finite either way, and the guard stops the world)
      auto zero = [](const Side& q) {
        for (int k = 0; k < q.n; ++k)
          if (q.jac[k] != 0 || q.unit[k] != 0) return false;
        return true;
      };
      if (r.a.n && r.b.n && zero(r.b)) r.b = Side();
      if (r.a.n && r.b.n && zero(r.a)) r.a = Side();
      const bool still_a = !r.a.n && !r.a.body, still_b = !r.b.n && !r.b.body;
      if (r.a.n && r.b.n) {
        r.shape = 2;
      } else if (r.a.n && still_b) {
        r.shape = 1;
      } else if (r.b.n && still_a) {
        // the side that moves first: resolve_one reads a
        std::swap(r.a, r.b);
        r.shape = 1;
      } else {
        r.shape = 0;
      }
    }
  };
  mark = info.m_numNonContactInnerIterations > 0;
  refs(m_multiBodyNonContactConstraints, joint_refs_);
  mark = true;
  refs(m_multiBodyNormalContactConstraints, normal_refs_);
  mark = false;
  refs(m_multiBodyFrictionContactConstraints, friction_refs_);
}

// Bullet's row update, written for the compiler: the Jacobian, the unit-impulse response and the accumulated
// velocity change of each side are read through the row's sides (make_refs), and the sums run in Bullet's order (no
// reassociation, no fused multiply-add on this build), so every impulse is Bullet's to the bit. A side without a
// moving body adds +0 to its sum, as Bullet's zero velocity changes do.
namespace {

// A row's impulse change clamped to its limits (resolveSingleConstraintRowGeneric's clamp); sets the new impulse.
inline btScalar clamp_impulse(const btMultiBodySolverConstraint& c, btScalar delta) {
  const btScalar sum = btScalar(c.m_appliedImpulse) + delta;
  if (sum < c.m_lowerLimit) {
    delta = c.m_lowerLimit - c.m_appliedImpulse;
    c.m_appliedImpulse = c.m_lowerLimit;
  } else if (sum > c.m_upperLimit) {
    delta = c.m_upperLimit - c.m_appliedImpulse;
    c.m_appliedImpulse = c.m_upperLimit;
  } else {
    c.m_appliedImpulse = sum;
  }
  return delta;
}

// resolve() for a row with one multibody side s (N = its 6 + dofs when > 0) and a side that moves nothing: the other
// side's term is +0 and delta - (+0) = delta, so leaving it out changes no bit.
template <int N>
btScalar resolve_one(const btMultiBodySolverConstraint& c, const SurfaceSolver::Side& s) {
  btScalar delta = c.m_rhs - btScalar(c.m_appliedImpulse) * c.m_cfm;
  const btScalar dv = N > 0 ? add_dot_fixed<N>(btScalar(0), s.jac, s.dv) : add_dot(btScalar(0), s.jac, s.dv, s.n);
  delta -= dv * c.m_jacDiagABInv;
  delta = clamp_impulse(c, delta);
  if (N > 0)
    add_scaled_fixed<N>(s.dv, s.unit, delta);
  else
    add_scaled_n(s.dv, s.unit, delta, s.n);
  return delta / c.m_jacDiagABInv;
}

// resolve() for a row with two multibody sides.
btScalar resolve_two(const btMultiBodySolverConstraint& c, const SurfaceSolver::RowRef& r) {
  btScalar delta = c.m_rhs - btScalar(c.m_appliedImpulse) * c.m_cfm;
  const btScalar dva = add_dot_n(btScalar(0), r.a.jac, r.a.dv, r.a.n);
  const btScalar dvb = add_dot_n(btScalar(0), r.b.jac, r.b.dv, r.b.n);
  delta -= dva * c.m_jacDiagABInv;
  delta -= dvb * c.m_jacDiagABInv;
  delta = clamp_impulse(c, delta);
  add_scaled_n(r.a.dv, r.a.unit, delta, r.a.n);
  add_scaled_n(r.b.dv, r.b.unit, delta, r.b.n);
  return delta / c.m_jacDiagABInv;
}

}  // namespace

btScalar SurfaceSolver::resolve(const btMultiBodySolverConstraint& c, const RowRef& r) {
  if (r.shape == 1) {
    switch (r.a.n) {
      case 7: return resolve_one<7>(c, r.a);
      case 8: return resolve_one<8>(c, r.a);
      case 9: return resolve_one<9>(c, r.a);
      case 10: return resolve_one<10>(c, r.a);
      case 11: return resolve_one<11>(c, r.a);
      case 12: return resolve_one<12>(c, r.a);
      default: return resolve_one<0>(c, r.a);
    }
  }
  if (r.shape == 2) return resolve_two(c, r);
  btScalar delta = c.m_rhs - btScalar(c.m_appliedImpulse) * c.m_cfm;
  btScalar dva = 0, dvb = 0;
  if (r.a.n) {
    dva = add_dot_n(dva, r.a.jac, r.a.dv, r.a.n);
  } else if (r.a.body) {
    dva += c.m_contactNormal1.dot(r.a.body->internalGetDeltaLinearVelocity()) +
           c.m_relpos1CrossNormal.dot(r.a.body->internalGetDeltaAngularVelocity());
  }
  if (r.b.n) {
    dvb = add_dot_n(dvb, r.b.jac, r.b.dv, r.b.n);
  } else if (r.b.body) {
    dvb += c.m_contactNormal2.dot(r.b.body->internalGetDeltaLinearVelocity()) +
           c.m_relpos2CrossNormal.dot(r.b.body->internalGetDeltaAngularVelocity());
  }
  delta -= dva * c.m_jacDiagABInv;
  delta -= dvb * c.m_jacDiagABInv;
  delta = clamp_impulse(c, delta);
  if (r.a.n)
    add_scaled_n(r.a.dv, r.a.unit, delta, r.a.n);
  else if (r.a.body)
    r.a.body->internalApplyImpulse(c.m_contactNormal1 * r.a.body->internalGetInvMass(), c.m_angularComponentA, delta);
  if (r.b.n)
    add_scaled_n(r.b.dv, r.b.unit, delta, r.b.n);
  else if (r.b.body)
    r.b.body->internalApplyImpulse(c.m_contactNormal2 * r.b.body->internalGetInvMass(), c.m_angularComponentB, delta);
  return delta / c.m_jacDiagABInv;
}

btScalar SurfaceSolver::solveSingleIteration(int iteration, btCollisionObject** bodies, int num_bodies,
                                             btPersistentManifold** manifolds, int num_manifolds,
                                             btTypedConstraint** constraints, int num_constraints,
                                             const btContactSolverInfo& info, btIDebugDraw* draw) {
  const bool cone = (info.m_solverMode & SOLVER_USE_2_FRICTION_DIRECTIONS) &&
                    !(info.m_solverMode & SOLVER_DISABLE_IMPLICIT_CONE_FRICTION);
  own_iterations_ = !cone;
  if (cone)
    return btMultiBodyConstraintSolver::solveSingleIteration(iteration, bodies, num_bodies, manifolds, num_manifolds,
                                                             constraints, num_constraints, info, draw);
  // Bullet's rigid-body pass (rows between rigid bodies, typed constraints); with none it would only walk empty
  // pools, and the order shuffles it may do touch no random state then
  btScalar residual = 0;
  if (num_constraints || m_tmpSolverNonContactConstraintPool.size() || m_tmpSolverContactConstraintPool.size() ||
      m_tmpSolverContactFrictionConstraintPool.size() || m_tmpSolverContactRollingFrictionConstraintPool.size())
    residual = btSequentialImpulseConstraintSolver::solveSingleIteration(
        iteration, bodies, num_bodies, manifolds, num_manifolds, constraints, num_constraints, info, draw);

  // Every multibody with a row is marked as having no updated positions (Bullet marks each row's bodies as it
  // solves the row; nothing reads the mark before the positions are integrated)
  for (btMultiBody* mb : row_bodies_) mb->setPosUpdated(false);
  // joint rows (motors, limits), forwards and backwards on alternate iterations
  btScalar joints = 0;
  const int nj = m_multiBodyNonContactConstraints.size();
  for (int k = 0; k < info.m_numNonContactInnerIterations; ++k) {
    joints = 0;
    for (int j = 0; j < nj; ++j) {
      const int row = iteration & 1 ? j : nj - 1 - j;
      const btScalar r = resolve(m_multiBodyNonContactConstraints[row], joint_refs_[row]);
      joints = btMax(joints, r * r);
    }
  }
  residual = btMax(residual, joints);
  // contact rows are not solved past the iteration count (Bullet's rule); their residual counts as 0
  if (iteration >= info.m_numIterations) return residual;
  // normal rows
  for (int j = 0; j < m_multiBodyNormalContactConstraints.size(); ++j) {
    const btScalar r = resolve(m_multiBodyNormalContactConstraints[j], normal_refs_[j]);
    residual = btMax(residual, r * r);
  }
  // friction rows, each bounded by its coefficient times its normal row's impulse
  for (int j = 0; j < m_multiBodyFrictionContactConstraints.size(); ++j) {
    btMultiBodySolverConstraint& c = m_multiBodyFrictionContactConstraints[j];
    const btScalar normal = m_multiBodyNormalContactConstraints[c.m_frictionIndex].m_appliedImpulse;
    if (normal > btScalar(0)) {
      c.m_lowerLimit = -(c.m_friction * normal);
      c.m_upperLimit = c.m_friction * normal;
      if (j >= static_cast<int>(circle_.size()) || !circle_[j]) {
        const btScalar r = resolve(c, friction_refs_[j]);
        residual = btMax(residual, r * r);
        continue;
      }
      // Coulomb's law for the pair (docs: "Skid steering"): both rows' unbounded changes together; inside the
      // circle mu N the contact sticks, outside it slides with the force mu N against its slip velocity (the
      // rows' velocity errors [m/s] along their unit directions)
      btMultiBodySolverConstraint& c2 = m_multiBodyFrictionContactConstraints[++j];
      const btScalar d1 = wanted(c), d2 = wanted(c2);
      const btScalar limit = c.m_friction * normal;
      btScalar n1 = c.m_appliedImpulse + d1, n2 = c2.m_appliedImpulse + d2;
      if (n1 * n1 + n2 * n2 > limit * limit) {
        const btScalar e1 = d1 / c.m_jacDiagABInv, e2 = d2 / c2.m_jacDiagABInv;
        const btScalar e = btSqrt(e1 * e1 + e2 * e2);
        const btScalar t = btSqrt(n1 * n1 + n2 * n2);
        // no slip to follow: scaled back onto the circle
        n1 = limit * (e > 0 ? e1 / e : n1 / t);
        n2 = limit * (e > 0 ? e2 / e : n2 / t);
      }
      const btScalar a1 = n1 - c.m_appliedImpulse, a2 = n2 - c2.m_appliedImpulse;
      nudge(c, a1);
      nudge(c2, a2);
      // Bullet's residual term: the rows' velocity change squared
      residual = btMax(residual, btMax(a1 * a1 / (c.m_jacDiagABInv * c.m_jacDiagABInv),
                                       a2 * a2 / (c2.m_jacDiagABInv * c2.m_jacDiagABInv)));
    } else if (j < static_cast<int>(circle_.size()) && circle_[j]) {
      ++j;
    }
  }
  return residual;
}

}  // namespace physics
}  // namespace car_sim
