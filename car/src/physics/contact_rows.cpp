// The rows SurfaceSolver sets up (surface.hpp): a contact point's normal and friction rows with their Jacobians,
// responses from the factored mass matrix (or Bullet's pass), Bullet's own conversion of a manifold, and a
// JointMotor's rows.
#include <algorithm>
#include <cmath>

#include "row_math.hpp"
#include "surface.hpp"

namespace car_sim {
namespace physics {

namespace {

// A multibody side of a new row in the solver's arrays, as Bullet's row builders make it: the multibody's block of
// velocity changes (one per multibody and solve, made on its first row) and the row's Jacobian and response slots.
// Returns the multibody's 6 + dofs.
int reserve_side(btMultiBodyJacobianData& data, btMultiBody* mb, int* vel_index, int* jac_index) {
  const int ndof = mb->getNumDofs() + 6;
  *vel_index = mb->getCompanionId();
  if (*vel_index < 0) {
    *vel_index = data.m_deltaVelocities.size();
    mb->setCompanionId(*vel_index);
    data.m_deltaVelocities.resize(data.m_deltaVelocities.size() + ndof);
  }
  *jac_index = data.m_jacobians.size();
  data.m_jacobians.resize(data.m_jacobians.size() + ndof);
  data.m_deltaVelocitiesUnitImpulse.resize(data.m_deltaVelocitiesUnitImpulse.size() + ndof);
  return ndof;
}

// A row's constraint force mixing (before the division by dt) and error reduction [-], as Bullet's row builders
// pick them: a friction row the world's friction values; a normal row the contact's own cfm and erp, else those of
// its stiffness and damping (cfm = 1 / (dt kp + kd), erp = dt kp / (dt kp + kd)), else the world's.
void row_cfm_erp(const btManifoldPoint& cp, const btContactSolverInfo& info, bool friction, btScalar* cfm,
                 btScalar* erp) {
  if (friction) {
    *cfm = info.m_frictionCFM;
    *erp = info.m_frictionERP;
  } else {
    *cfm = info.m_globalCfm;
    *erp = info.m_erp2;
    if ((cp.m_contactPointFlags & BT_CONTACT_FLAG_HAS_CONTACT_CFM) ||
        (cp.m_contactPointFlags & BT_CONTACT_FLAG_HAS_CONTACT_ERP)) {
      if (cp.m_contactPointFlags & BT_CONTACT_FLAG_HAS_CONTACT_CFM) *cfm = cp.m_contactCFM;
      if (cp.m_contactPointFlags & BT_CONTACT_FLAG_HAS_CONTACT_ERP) *erp = cp.m_contactERP;
    } else if (cp.m_contactPointFlags & BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING) {
      btScalar denom = info.m_timeStep * cp.m_combinedContactStiffness1 + cp.m_combinedContactDamping1;
      if (denom < SIMD_EPSILON) denom = SIMD_EPSILON;
      *cfm = btScalar(1) / denom;
      *erp = (info.m_timeStep * cp.m_combinedContactStiffness1) / denom;
    }
  }
}

}  // namespace

// ---- row set-up with factored mass matrices -------------------------------------------------------------------

bool SurfaceSolver::own_rows(const btContactSolverInfo& info) const {
  const bool cone = (info.m_solverMode & SOLVER_USE_2_FRICTION_DIRECTIONS) &&
                    !(info.m_solverMode & SOLVER_DISABLE_IMPLICIT_CONE_FRICTION);
  return rows_ != RowSetup::bullet && !cone && !(info.m_solverMode & SOLVER_USE_ARTICULATED_WARMSTARTING);
}

const InverseMass* SurfaceSolver::inverse_mass(const btMultiBody* mb) {
  if (rows_ != RowSetup::factored) return nullptr;
  // the multibody of the last call (a row's Jacobian and response ask twice, a manifold's rows in turn)
  if (mb == last_body_) return last_inverse_;
  last_body_ = mb;
  if (source_)
    if ((last_inverse_ = source_->built(mb))) return last_inverse_;
  for (int i = 0; i < inverse_used_; ++i)
    if (inverse_[i].body() == mb) return last_inverse_ = inverse_ok_[i] ? &inverse_[i] : nullptr;
  if (inverse_used_ == static_cast<int>(inverse_.size())) {
    inverse_.emplace_back();
    inverse_ok_.push_back(0);
  }
  const int i = inverse_used_++;
  inverse_ok_[i] = inverse_[i].build(*mb);
  return last_inverse_ = inverse_ok_[i] ? &inverse_[i] : nullptr;
}

const SurfaceSolver::ContactFrames& SurfaceSolver::contact_frames(const btMultiBody* mb) {
  for (int i = 0; i < frames_used_; ++i)
    if (frames_[i].mb == mb) return frames_[i];
  if (frames_used_ == static_cast<int>(frames_.size())) frames_.emplace_back();
  ContactFrames& f = frames_[frames_used_++];
  f.mb = mb;
  f.base = btMatrix3x3(mb->getWorldToBaseRot());
  f.links.resize(mb->getNumLinks());
  for (int i = 0; i < mb->getNumLinks(); ++i) f.links[i] = btMatrix3x3(mb->getLink(i).m_cachedRotParentToThis);
  return f;
}

// Bullet 3.24's btMultiBody::fillConstraintJacobianMultiDof with normal_ang = 0 (fillContactJacobianMultiDof): the
// normal and the contact point in each frame from the base out to the link, and each joint's entry from them. Bullet
// also multiplies out the frames' rotations from the world, which no entry reads.
void SurfaceSolver::contact_jacobian(const btMultiBody* mb, int link, const btVector3& point, const btVector3& normal,
                                     btScalar* jac) {
  // with the factored matrix, from its world frames (the same Jacobian, to rounding)
  if (const InverseMass* inv = inverse_mass(mb))
    if (inv->contact_jacobian(link, point, normal, jac)) return;
  const ContactFrames& f = contact_frames(mb);
  const int dofs = mb->getNumDofs();
  const btVector3 normal_ang(0, 0, 0);
  const btVector3 p_minus_com_world = point - mb->getBasePos();
  // omega coefficients, then v coefficients
  const btVector3 omega = p_minus_com_world.cross(normal);
  jac[0] = omega[0] + normal_ang[0];
  jac[1] = omega[1] + normal_ang[1];
  jac[2] = omega[2] + normal_ang[2];
  jac[3] = normal[0];
  jac[4] = normal[1];
  jac[5] = normal[2];
  // [m], [-], [-] in the frame of the link last visited (the base first)
  btVector3 p_local = f.base * p_minus_com_world;
  btVector3 n_lin = f.base * normal;
  btVector3 n_ang = f.base * normal_ang;
  for (int i = 6; i < 6 + dofs; ++i) jac[i] = 0;
  if (mb->getNumLinks() == 0 || link < 0) return;
  chain_.clear();
  for (int l = link; l != -1; l = mb->getLink(l).m_parent) chain_.push_back(l);
  for (int a = static_cast<int>(chain_.size()) - 1; a >= 0; --a) {
    const int i = chain_[a];
    const btMultibodyLink& l = mb->getLink(i);
    const btMatrix3x3& mtx = f.links[i];
    n_lin = mtx * n_lin;
    n_ang = mtx * n_ang;
    p_local = mtx * p_local - l.m_cachedRVector;
    btScalar* r = jac + 6 + l.m_dofOffset;
    switch (l.m_jointType) {
      case btMultibodyLink::eRevolute:
        r[0] = n_lin.dot(l.getAxisTop(0).cross(p_local) + l.getAxisBottom(0));
        r[0] += n_ang.dot(l.getAxisTop(0));
        break;
      case btMultibodyLink::ePrismatic:
        r[0] = n_lin.dot(l.getAxisBottom(0));
        break;
      case btMultibodyLink::eSpherical:
        for (int d = 0; d < 3; ++d) r[d] = n_lin.dot(l.getAxisTop(d).cross(p_local) + l.getAxisBottom(d));
        for (int d = 0; d < 3; ++d) r[d] += n_ang.dot(l.getAxisTop(d));
        break;
      case btMultibodyLink::ePlanar:
        r[0] = n_lin.dot(l.getAxisTop(0).cross(p_local));
        r[1] = n_lin.dot(l.getAxisBottom(1));
        r[2] = n_lin.dot(l.getAxisBottom(2));
        break;
      default:
        break;
    }
  }
}

void SurfaceSolver::bind(btMultiBodySolverConstraint& c, btPersistentManifold* m, btManifoldPoint& cp,
                         const btContactSolverInfo& info) {
  auto* co0 = const_cast<btCollisionObject*>(m->getBody0());
  auto* co1 = const_cast<btCollisionObject*>(m->getBody1());
  const btMultiBodyLinkCollider* fcA = btMultiBodyLinkCollider::upcast(co0);
  const btMultiBodyLinkCollider* fcB = btMultiBodyLinkCollider::upcast(co1);
  c.m_orgConstraint = nullptr;
  c.m_orgDofIndex = -1;
  c.m_multiBodyA = fcA ? fcA->m_multiBody : nullptr;
  c.m_multiBodyB = fcB ? fcB->m_multiBody : nullptr;
  c.m_solverBodyIdA = fcA ? -1 : getOrInitSolverBody(*co0, info.m_timeStep);
  c.m_solverBodyIdB = fcB ? -1 : getOrInitSolverBody(*co1, info.m_timeStep);
  if (fcA) c.m_linkA = fcA->m_link;
  if (fcB) c.m_linkB = fcB->m_link;
  c.m_originalContactPoint = &cp;
}

// Bullet 3.24's setupMultiBodyContactConstraint, line for line in its arithmetic, but for the unit-impulse response of
// a multibody side: M^-1 J^T from the factored matrix (InverseMass) instead of a Featherstone pass per row.
void SurfaceSolver::setup_row(btMultiBodySolverConstraint& c, const btVector3& normal, btManifoldPoint& cp,
                              const btContactSolverInfo& info, btScalar& relaxation, bool friction) {
  btMultiBody* mbA = c.m_multiBodyA;
  btMultiBody* mbB = c.m_multiBodyB;
  const btVector3& pos1 = cp.getPositionWorldOnA();
  const btVector3& pos2 = cp.getPositionWorldOnB();
  btSolverBody* bodyA = mbA ? nullptr : &m_tmpSolverBodyPool[c.m_solverBodyIdA];
  btSolverBody* bodyB = mbB ? nullptr : &m_tmpSolverBodyPool[c.m_solverBodyIdB];
  btRigidBody* rb0 = mbA ? nullptr : bodyA->m_originalBody;
  btRigidBody* rb1 = mbB ? nullptr : bodyB->m_originalBody;
  btVector3 rel_pos1, rel_pos2;
  if (bodyA) rel_pos1 = pos1 - bodyA->getWorldTransform().getOrigin();
  if (bodyB) rel_pos2 = pos2 - bodyB->getWorldTransform().getOrigin();
  relaxation = info.m_sor;
  const btScalar inv_dt = btScalar(1) / info.m_timeStep;

  btScalar cfm, erp;
  row_cfm_erp(cp, info, friction, &cfm, &erp);
  cfm *= inv_dt;

  // One multibody side: its Jacobian (Bullet's), its response to a unit impulse along it.
  auto side = [&](btMultiBody* mb, int link, const btVector3& pos, const btVector3& n, int* vel_index,
                  int* jac_index) {
    reserve_side(m_data, mb, vel_index, jac_index);
    btScalar* jac = &m_data.m_jacobians[*jac_index];
    contact_jacobian(mb, link, pos, n, jac);
    response(mb, jac, &m_data.m_deltaVelocitiesUnitImpulse[*jac_index], m_data);
  };

  if (mbA) {
    rel_pos1 = pos1 - (c.m_linkA < 0 ? mbA->getBasePos() : mbA->getLink(c.m_linkA).m_cachedWorldTransform.getOrigin());
    side(mbA, c.m_linkA, pos1, normal, &c.m_deltaVelAindex, &c.m_jacAindex);
    c.m_relpos1CrossNormal = rel_pos1.cross(normal);
    c.m_contactNormal1 = normal;
  } else {
    const btVector3 torque_axis = rel_pos1.cross(normal);
    c.m_relpos1CrossNormal = torque_axis;
    c.m_contactNormal1 = normal;
    c.m_angularComponentA =
        rb0 ? rb0->getInvInertiaTensorWorld() * torque_axis * rb0->getAngularFactor() : btVector3(0, 0, 0);
  }
  if (mbB) {
    rel_pos2 = pos2 - (c.m_linkB < 0 ? mbB->getBasePos() : mbB->getLink(c.m_linkB).m_cachedWorldTransform.getOrigin());
    side(mbB, c.m_linkB, pos2, -normal, &c.m_deltaVelBindex, &c.m_jacBindex);
    c.m_relpos2CrossNormal = -rel_pos2.cross(normal);
    c.m_contactNormal2 = -normal;
  } else {
    const btVector3 torque_axis = rel_pos2.cross(normal);
    c.m_relpos2CrossNormal = -torque_axis;
    c.m_contactNormal2 = -normal;
    c.m_angularComponentB =
        rb1 ? rb1->getInvInertiaTensorWorld() * -torque_axis * rb1->getAngularFactor() : btVector3(0, 0, 0);
  }

  // effective inverse mass along the row
  {
    btScalar denom0 = 0, denom1 = 0;
    if (mbA) {
      const int ndof = mbA->getNumDofs() + 6;
      const btScalar* j = &m_data.m_jacobians[c.m_jacAindex];
      denom0 = add_dot(denom0, j, &m_data.m_deltaVelocitiesUnitImpulse[c.m_jacAindex], ndof);
    } else if (rb0) {
      const btVector3 vec = c.m_angularComponentA.cross(rel_pos1);
      denom0 = rb0->getInvMass() + normal.dot(vec);
    }
    if (mbB) {
      const int ndof = mbB->getNumDofs() + 6;
      const btScalar* j = &m_data.m_jacobians[c.m_jacBindex];
      denom1 = add_dot(denom1, j, &m_data.m_deltaVelocitiesUnitImpulse[c.m_jacBindex], ndof);
    } else if (rb1) {
      const btVector3 vec = (-c.m_angularComponentB).cross(rel_pos2);
      denom1 = rb1->getInvMass() + normal.dot(vec);
    }
    const btScalar d = denom0 + denom1 + cfm;
    // a singular or redundant row is disabled
    c.m_jacDiagABInv = d > SIMD_EPSILON ? relaxation / d : btScalar(0);
  }

  // right-hand side: restitution, penetration and velocity error
  btScalar restitution = 0, distance = 0;
  if (!friction)
    distance = cp.getDistance() + info.m_linearSlop;
  else if (cp.m_contactPointFlags & BT_CONTACT_FLAG_FRICTION_ANCHOR)
    distance = (cp.getPositionWorldOnA() - cp.getPositionWorldOnB()).dot(normal);
  btScalar rel_vel = 0;
  if (mbA) {
    const int ndof = mbA->getNumDofs() + 6;
    const btScalar* j = &m_data.m_jacobians[c.m_jacAindex];
    rel_vel = add_dot(rel_vel, mbA->getVelocityVector(), j, ndof);
  } else if (rb0) {
    rel_vel += (rb0->getVelocityInLocalPoint(rel_pos1) +
                (rb0->getTotalTorque() * rb0->getInvInertiaTensorWorld() * info.m_timeStep).cross(rel_pos1) +
                rb0->getTotalForce() * rb0->getInvMass() * info.m_timeStep)
                   .dot(c.m_contactNormal1);
  }
  if (mbB) {
    const int ndof = mbB->getNumDofs() + 6;
    const btScalar* j = &m_data.m_jacobians[c.m_jacBindex];
    rel_vel = add_dot(rel_vel, mbB->getVelocityVector(), j, ndof);
  } else if (rb1) {
    rel_vel += (rb1->getVelocityInLocalPoint(rel_pos2) +
                (rb1->getTotalTorque() * rb1->getInvInertiaTensorWorld() * info.m_timeStep).cross(rel_pos2) +
                rb1->getTotalForce() * rb1->getInvMass() * info.m_timeStep)
                   .dot(c.m_contactNormal2);
  }
  c.m_friction = cp.m_combinedFriction;
  if (!friction) {
    restitution = restitutionCurve(rel_vel, cp.m_combinedRestitution, info.m_restitutionVelocityThreshold);
    if (restitution <= btScalar(0)) restitution = 0;
  }
  btScalar positional = 0;
  btScalar velocity = restitution - rel_vel;
  if (friction) {
    positional = -distance * erp / info.m_timeStep;
  } else if (distance > 0) {
    velocity -= distance / info.m_timeStep;
  } else {
    positional = -distance * erp / info.m_timeStep;
  }
  const btScalar penetration_impulse = positional * c.m_jacDiagABInv;
  const btScalar velocity_impulse = velocity * c.m_jacDiagABInv;
  c.m_rhs = penetration_impulse + velocity_impulse;
  c.m_rhsPenetration = 0;
  if (!friction) {
    c.m_lowerLimit = 0;
    c.m_upperLimit = 1e10f;
  } else {
    c.m_lowerLimit = -c.m_friction;
    c.m_upperLimit = c.m_friction;
  }
  c.m_cfm = cfm * c.m_jacDiagABInv;
  // no articulated warm starting (own_rows): every row starts from zero, as in Bullet
  c.m_appliedImpulse = 0;
  c.m_appliedPushImpulse = 0;
}

btMultiBodySolverConstraint& SurfaceSolver::add_friction_row(const btVector3& dir, btPersistentManifold* m,
                                                             int normal_index, btManifoldPoint& cp,
                                                             btScalar relaxation, const btContactSolverInfo& info) {
  btMultiBodySolverConstraint& c = m_multiBodyFrictionContactConstraints.expandNonInitializing();
  c.m_frictionIndex = normal_index;
  bind(c, m, cp, info);
  setup_row(c, dir, cp, info, relaxation, true);
  return c;
}

// Bullet 3.24's convertMultiBodyContact for a manifold without spinning or rolling friction: per point in contact a
// normal row and friction rows along btPlaneSpace1 of the normal (two with SOLVER_USE_2_FRICTION_DIRECTIONS), each
// scaled by the objects' anisotropic friction.
void SurfaceSolver::convert_bullet(btPersistentManifold* m, const btContactSolverInfo& info) {
  auto* co0 = const_cast<btCollisionObject*>(m->getBody0());
  auto* co1 = const_cast<btCollisionObject*>(m->getBody1());
  for (int j = 0; j < m->getNumContacts(); ++j) {
    btManifoldPoint& cp = m->getContactPoint(j);
    if (cp.getDistance() > m->getContactProcessingThreshold()) {
      // not in contact: no warm start from it
      cp.m_appliedImpulse = 0;
      cp.m_prevRHS = 0;
      continue;
    }
    btScalar relaxation;
    const int normal_index = m_multiBodyNormalContactConstraints.size();
    btMultiBodySolverConstraint& c = m_multiBodyNormalContactConstraints.expandNonInitializing();
    bind(c, m, cp, info);
    setup_row(c, cp.m_normalWorldOnB, cp, info, relaxation, false);
    c.m_frictionIndex = m_multiBodyFrictionContactConstraints.size();
    btPlaneSpace1(cp.m_normalWorldOnB, cp.m_lateralFrictionDir1, cp.m_lateralFrictionDir2);
    cp.m_lateralFrictionDir1.normalize();
    cp.m_lateralFrictionDir2.normalize();
    applyAnisotropicFriction(co0, cp.m_lateralFrictionDir1, btCollisionObject::CF_ANISOTROPIC_FRICTION);
    applyAnisotropicFriction(co1, cp.m_lateralFrictionDir1, btCollisionObject::CF_ANISOTROPIC_FRICTION);
    add_friction_row(cp.m_lateralFrictionDir1, m, normal_index, cp, relaxation, info);
    if (info.m_solverMode & SOLVER_USE_2_FRICTION_DIRECTIONS) {
      applyAnisotropicFriction(co0, cp.m_lateralFrictionDir2, btCollisionObject::CF_ANISOTROPIC_FRICTION);
      applyAnisotropicFriction(co1, cp.m_lateralFrictionDir2, btCollisionObject::CF_ANISOTROPIC_FRICTION);
      add_friction_row(cp.m_lateralFrictionDir2, m, normal_index, cp, relaxation, info);
    }
    if ((info.m_solverMode & SOLVER_USE_2_FRICTION_DIRECTIONS) &&
        (info.m_solverMode & SOLVER_DISABLE_VELOCITY_DEPENDENT_FRICTION_DIRECTION))
      cp.m_contactPointFlags |= BT_CONTACT_FLAG_LATERAL_FRICTION_INITIALIZED;
  }
}

void SurfaceSolver::response(btMultiBody* mb, const btScalar* jac, btScalar* delta, btMultiBodyJacobianData& data) {
  // a side whose Jacobian is zero (a joint motor's second side) responds with zero, as Bullet's pass gives it
  const int n = mb->getNumDofs() + 6;
  bool zero = true;
  for (int i = 0; i < n && zero; ++i) zero = jac[i] == 0;
  if (zero && own_) {
    for (int i = 0; i < n; ++i) delta[i] = 0;
    return;
  }
  if (const InverseMass* inv = own_ ? inverse_mass(mb) : nullptr)
    inv->solve(jac, delta);
  else
    mb->calcAccelerationDeltasMultiDof(jac, delta, data.scratch_r, data.scratch_v);
}

// Bullet 3.24's btMultiBodyJointMotor::createConstraintRows with fillMultiBodyConstraint written out for its case
// (both sides the motor's own multibody, Jacobians from the constructor, no positional error), the same
// arithmetic; only the unit-impulse response comes from SurfaceSolver::response.
void JointMotor::createConstraintRows(btMultiBodyConstraintArray& rows, btMultiBodyJacobianData& data,
                                      const btContactSolverInfo& info) {
  SurfaceSolver* solver = SurfaceSolver::converting();
  if (!solver || m_bodyA != m_bodyB) {
    btMultiBodyJointMotor::createConstraintRows(rows, data, info);
    return;
  }
  if (m_numDofsFinalized != m_jacSizeBoth) finalizeMultiDof();
  if (m_numDofsFinalized != m_jacSizeBoth) return;
  if (m_maxAppliedImpulse == 0.f) return;
  btMultiBody* mb = m_bodyA;
  const int ndof = mb->getNumDofs() + 6;
  const btVector3 zero(0, 0, 0);
  for (int row = 0; row < getNumRows(); ++row) {
    btMultiBodySolverConstraint& c = rows.expandNonInitializing();
    // the servo's target velocity: position term (kp, erp), velocity term (kd), clamped
    const btScalar position = mb->getJointPosMultiDof(m_linkA)[0];
    const btScalar velocity = mb->getJointVelMultiDof(m_linkA)[0];
    const btScalar stabilisation = m_erp * (m_desiredPosition - position) / info.m_timeStep;
    btScalar rhs = m_kp * stabilisation + velocity + m_kd * (m_desiredVelocity - velocity);
    if (rhs > m_rhsClamp) rhs = m_rhsClamp;
    if (rhs < -m_rhsClamp) rhs = -m_rhsClamp;

    c.m_multiBodyA = c.m_multiBodyB = mb;
    c.m_linkA = m_linkA;
    c.m_linkB = m_linkB;
    // both sides: Jacobian copied, response, torque axis (zero: no linear normal)
    const btScalar* org[2] = {jacobianA(row), jacobianB(row)};
    int* jac_index[2] = {&c.m_jacAindex, &c.m_jacBindex};
    int* vel_index[2] = {&c.m_deltaVelAindex, &c.m_deltaVelBindex};
    const int links[2] = {m_linkA, m_linkB};
    btVector3 torque_axis[2];
    for (int s = 0; s < 2; ++s) {
      const btVector3 rel_pos = zero - (links[s] < 0 ? mb->getBasePos()
                                                     : mb->getLink(links[s]).m_cachedWorldTransform.getOrigin());
      reserve_side(data, mb, vel_index[s], jac_index[s]);
      for (int i = 0; i < ndof; ++i) data.m_jacobians[*jac_index[s] + i] = org[s][i];
      solver->response(mb, &data.m_jacobians[*jac_index[s]], &data.m_deltaVelocitiesUnitImpulse[*jac_index[s]], data);
      torque_axis[s] = rel_pos.cross(zero);
    }
    c.m_relpos1CrossNormal = torque_axis[0];
    c.m_contactNormal1 = zero;
    c.m_relpos2CrossNormal = -torque_axis[1];
    c.m_contactNormal2 = -zero;
    const btScalar denom0 = add_dot(0, &data.m_jacobians[c.m_jacAindex],
                                    &data.m_deltaVelocitiesUnitImpulse[c.m_jacAindex], ndof);
    const btScalar denom1 = add_dot(0, &data.m_jacobians[c.m_jacBindex],
                                    &data.m_deltaVelocitiesUnitImpulse[c.m_jacBindex], ndof);
    const btScalar d = denom0 + denom1;
    c.m_jacDiagABInv = d > SIMD_EPSILON ? btScalar(1) / d : btScalar(0);
    btScalar rel_vel = 0;
    for (int s = 0; s < 2; ++s)
      rel_vel = add_dot(rel_vel, mb->getVelocityVector(), &data.m_jacobians[*jac_index[s]], ndof);
    c.m_friction = 0;
    c.m_appliedImpulse = 0;
    c.m_appliedPushImpulse = 0;
    const btScalar penetration = 0;
    const btScalar positional = -penetration * info.m_erp / info.m_timeStep;
    const btScalar velocity_error = (rhs - rel_vel) * btScalar(1.0);
    c.m_rhs = positional * c.m_jacDiagABInv + velocity_error * c.m_jacDiagABInv;
    c.m_rhsPenetration = 0;
    c.m_cfm = 0;
    c.m_lowerLimit = -m_maxAppliedImpulse;
    c.m_upperLimit = m_maxAppliedImpulse;
    c.m_orgConstraint = this;
    c.m_orgDofIndex = row;
    // the axis the row's impulse acts along, world frame (Bullet's joint feedback reads it)
    const btMultibodyLink& l = mb->getLink(m_linkA);
    if (l.m_jointType == btMultibodyLink::eRevolute) {
      c.m_contactNormal1.setZero();
      c.m_contactNormal2.setZero();
      const btVector3 axis = quatRotate(l.m_cachedWorldTransform.getRotation(), l.m_axes[0].m_topVec);
      c.m_relpos1CrossNormal = axis;
      c.m_relpos2CrossNormal = -axis;
    } else if (l.m_jointType == btMultibodyLink::ePrismatic) {
      const btVector3 axis = quatRotate(l.m_cachedWorldTransform.getRotation(), l.m_axes[0].m_bottomVec);
      c.m_contactNormal1 = axis;
      c.m_contactNormal2 = -axis;
      c.m_relpos1CrossNormal.setZero();
      c.m_relpos2CrossNormal.setZero();
    }
  }
}

}  // namespace physics
}  // namespace car_sim
