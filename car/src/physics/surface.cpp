// Gazebo's surface rules on Bullet; the rules are written down in docs/COMPAT-physics.md.
#include "row_math.hpp"
#include "surface.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace car_sim {
namespace physics {

namespace {

// The solver whose joint constraints are making their rows on this thread (JointMotor asks it for responses).
thread_local SurfaceSolver* converting_ = nullptr;

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

// Bullet's persistent manifold holds at most this many points per pair.
constexpr int kManifoldPoints = 4;

// What two surfaces make of one contact point (ODEPhysics::Collide's rules).
struct PairSurface {
  double mu1 = 1.0, mu2 = 1.0;           // [-]
  std::optional<btVector3> fdir1;        // [-] world frame, not yet projected onto the contact plane
  bool stiffness = false;                // kp/kd set on either side
  double kp = kDefaultKp, kd = kDefaultKd;
  std::optional<double> min_depth;       // [m]
  std::optional<double> max_vel;         // [m/s]
  std::optional<int> max_contacts;
};

const Surface& default_surface() {
  static const Surface s;
  return s;
}

const Surface& surface_at(const btCollisionObject* o, int child) {
  const SurfaceSet* set = surfaces_of(o);
  return set ? set->at(child) : default_surface();
}

PairSurface combine(const btCollisionObject* a, const Surface& sa, const btCollisionObject* b, const Surface& sb) {
  PairSurface p;
  // friction: the smaller coefficient per direction
  p.mu1 = std::min(sa.mu1, sb.mu1);
  p.mu2 = std::min(sa.mu2, sb.mu2);
  // fdir1: the first surface's, unless the second sets one and the first sets none or has the larger mu1
  if (sa.fdir1) p.fdir1 = a->getWorldTransform().getBasis() * *sa.fdir1;
  if (sb.fdir1 && (!sa.fdir1 || sa.mu1 > sb.mu1)) p.fdir1 = b->getWorldTransform().getBasis() * *sb.fdir1;
  // stiffness: springs in series; damping: dampers in parallel
  if (sa.kp || sa.kd || sb.kp || sb.kd) {
    p.stiffness = true;
    p.kp = 1.0 / (1.0 / sa.kp.value_or(kDefaultKp) + 1.0 / sb.kp.value_or(kDefaultKp));
    p.kd = sa.kd.value_or(kDefaultKd) + sb.kd.value_or(kDefaultKd);
  }
  // correction limits: the larger allowed depth, the smaller correction velocity, the fewer contacts
  for (const Surface* s : {&sa, &sb}) {
    if (s->min_depth) p.min_depth = std::max(p.min_depth.value_or(0.0), *s->min_depth);
    if (s->max_vel) p.max_vel = p.max_vel ? std::min(*p.max_vel, *s->max_vel) : *s->max_vel;
    if (s->max_contacts) p.max_contacts = p.max_contacts ? std::min(*p.max_contacts, *s->max_contacts) : *s->max_contacts;
  }
  return p;
}

// Whether a manifold's contacts need car's conversion (else Bullet's own, unchanged).
bool needs_conversion(const btPersistentManifold* m) {
  const SurfaceSet* a = surfaces_of(m->getBody0());
  const SurfaceSet* b = surfaces_of(m->getBody1());
  if ((a && a->convert) || (b && b->convert)) return true;
  const Surface& sa = a ? a->at(-1) : default_surface();
  const Surface& sb = b ? b->at(-1) : default_surface();
  return std::min(sa.mu1, sb.mu1) != std::min(sa.mu2, sb.mu2);
}

// Whether no point of a manifold has friction by Bullet's combination (sliding, rolling or spinning): then its
// contacts need normal rows only.
bool frictionless(const btPersistentManifold* m) {
  const int n = m->getNumContacts();
  for (int j = 0; j < n; ++j) {
    const btManifoldPoint& cp = m->getContactPoint(j);
    if (cp.m_combinedFriction != 0 || cp.m_combinedRollingFriction != 0 || cp.m_combinedSpinningFriction != 0)
      return false;
  }
  return n > 0;
}

}  // namespace

bool Surface::needs_conversion() const {
  return fdir1 || kp || kd || min_depth || max_vel || (max_contacts && *max_contacts < kManifoldPoints);
}

bool Surface::operator==(const Surface& o) const {
  return mu1 == o.mu1 && mu2 == o.mu2 && fdir1 == o.fdir1 && kp == o.kp && kd == o.kd && min_depth == o.min_depth &&
         max_vel == o.max_vel && max_contacts == o.max_contacts;
}

const Surface& SurfaceSet::at(int child) const {
  if (shapes.size() == 1 || child < 0 || child >= static_cast<int>(shapes.size())) return shapes.front();
  return shapes[child];
}

void SurfaceSet::finish() {
  if (shapes.empty()) shapes.emplace_back();
  convert = false;
  for (const auto& s : shapes) convert = convert || s.needs_conversion() || !(s == shapes.front());
}

Surface link_surface(const GazeboLinkExt& g, const Eigen::Matrix3d& shape_to_object) {
  Surface s;
  s.mu1 = g.mu1.value_or(1.0);
  s.mu2 = g.mu2.value_or(1.0);
  if (g.fdir1 && g.fdir1->norm() > 1e-12) {
    const Eigen::Vector3d f = shape_to_object * g.fdir1->normalized();
    s.fdir1 = btVector3(f.x(), f.y(), f.z());
  }
  s.kp = g.kp;
  s.kd = g.kd;
  s.min_depth = g.min_depth;
  s.max_vel = g.max_vel;
  s.max_contacts = g.max_contacts;
  return s;
}

const SurfaceSet* surfaces_of(const btCollisionObject* o) {
  return o ? static_cast<const SurfaceSet*>(o->getUserPointer()) : nullptr;
}

bool SurfaceCollider::checkCollideWithOverride(const btCollisionObject* co) const {
  const btMultiBodyLinkCollider* other = btMultiBodyLinkCollider::upcast(co);
  if (!other || other->m_multiBody != m_multiBody) return true;
  const SurfaceSet* a = surfaces_of(this);
  const SurfaceSet* b = surfaces_of(other);
  if (!((a && a->self_collide) || (b && b->self_collide))) return false;
  // never across the joint between a body and its parent
  if (m_link >= 0 && m_multiBody->getLink(m_link).m_parent == other->m_link) return false;
  if (other->m_link >= 0 && m_multiBody->getLink(other->m_link).m_parent == m_link) return false;
  return true;
}

void SurfaceSolver::convertContacts(btPersistentManifold** manifolds, int count, const btContactSolverInfo& info) {
  bullet_.resize(0);
  car_.resize(0);
  frictionless_.resize(0);
  no_friction_rows_.resize(0);
  push_.clear();
  circle_.clear();
  for (int i = 0; i < count; ++i) {
    btPersistentManifold* m = manifolds[i];
    const bool multibody = btMultiBodyLinkCollider::upcast(m->getBody0()) || btMultiBodyLinkCollider::upcast(m->getBody1());
    if (multibody && needs_conversion(m))
      car_.push_back(m);
    else if (multibody && frictionless(m))
      frictionless_.push_back(m);
    else
      bullet_.push_back(m);
  }
  own_ = own_rows(info);
  inverse_used_ = 0;
  last_body_ = nullptr;
  frames_used_ = 0;
  // Gazebo's default surface (max_vel 0.01 m/s, min_depth 0) on every pair Bullet's conversion sets up: each
  // point's correction capped before its rows are made, the held-back part kept for the split (solve_push)
  capped_.clear();
  for (int i = 0; i < bullet_.size(); ++i) {
    btPersistentManifold* m = bullet_[i];
    if (!btMultiBodyLinkCollider::upcast(m->getBody0()) && !btMultiBodyLinkCollider::upcast(m->getBody1())) continue;
    for (int j = 0; j < m->getNumContacts(); ++j) {
      btManifoldPoint& cp = m->getContactPoint(j);
      if (cp.getDistance() > m->getContactProcessingThreshold()) continue;
      const btScalar distance = cp.m_distance1;
      const btScalar push = cap_depth(cp, info, contact_erp(cp, info), kDefaultMaxVel, 0.0);
      if (push > 0) capped_.push_back({&cp, distance, push});
    }
  }
  if (!own_) {
    // Bullet's own conversion (it also adds the joint constraints' rows), then car's contacts
    btMultiBodyConstraintSolver::convertContacts(bullet_.size() ? &bullet_[0] : nullptr, bullet_.size(), info);
  } else {
    // Bullet's conversion in Bullet's order, multibody rows set up by car; then the joint constraints' rows
    const bool caching = info.m_solverMode & SOLVER_ENABLE_FRICTION_DIRECTION_CACHING;
    for (int i = 0; i < bullet_.size(); ++i) {
      btPersistentManifold* m = bullet_[i];
      if (!btMultiBodyLinkCollider::upcast(m->getBody0()) && !btMultiBodyLinkCollider::upcast(m->getBody1())) {
        convertContact(m, info);
        continue;
      }
      bool plain = !caching;
      for (int j = 0; j < m->getNumContacts() && plain; ++j) {
        const btManifoldPoint& cp = m->getContactPoint(j);
        plain = cp.m_combinedSpinningFriction <= 0 && cp.m_combinedRollingFriction <= 0;
      }
      if (plain)
        convert_bullet(m, info);
      else
        convertMultiBodyContact(m, info);
    }
    converting_ = this;
    btMultiBodyConstraintSolver::convertContacts(nullptr, 0, info);
    converting_ = nullptr;
  }
  // the capped points' depths back, their normal rows' held-back impulses to the split
  if (!capped_.empty()) {
    for (const auto& c : capped_) c.point->m_distance1 = c.distance;
    for (int r = 0; r < m_multiBodyNormalContactConstraints.size(); ++r) {
      const btMultiBodySolverConstraint& row = m_multiBodyNormalContactConstraints[r];
      for (const auto& c : capped_)
        if (row.m_originalContactPoint == c.point) {
          push_.push_back({r, c.push * row.m_jacDiagABInv, 0});
          break;
        }
    }
  }
  for (int i = 0; i < car_.size(); ++i) convert(car_[i], info, true);
  for (int i = 0; i < frictionless_.size(); ++i) convert(frictionless_[i], info, false);
}

// The erp of a contact point's normal row (setup_row's rule): from its stiffness and damping when car set them,
// else the world's erp2 (Bullet's rigid contact).
double SurfaceSolver::contact_erp(const btManifoldPoint& cp, const btContactSolverInfo& info) {
  if (cp.m_contactPointFlags & BT_CONTACT_FLAG_HAS_CONTACT_ERP) return cp.m_contactERP;
  if (!(cp.m_contactPointFlags & BT_CONTACT_FLAG_HAS_CONTACT_CFM) &&
      (cp.m_contactPointFlags & BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING)) {
    const double denom = info.m_timeStep * cp.m_combinedContactStiffness1 + cp.m_combinedContactDamping1;
    return denom < SIMD_EPSILON ? 0.0 : info.m_timeStep * cp.m_combinedContactStiffness1 / denom;
  }
  return info.m_erp2;
}

// ODE's cap on a contact's correction (contact.cpp getInfo2): the depth the normal row corrects [m] (negative
// distance) less min_depth, and no more than `max_vel` [m/s] (truncated by the world's
// contact_max_correcting_vel) can correct in one step at the row's erp. Sets the point's distance to what the
// velocity solve corrects; returns the correction velocity [m/s] the cap holds back (0 if none).
btScalar SurfaceSolver::cap_depth(btManifoldPoint& cp, const btContactSolverInfo& info, double erp, double max_vel,
                                  double min_depth) {
  btScalar d = cp.m_distance1;
  if (d < 0 && min_depth > 0) d = std::min<btScalar>(d + min_depth, 0);
  btScalar push = 0;
  const double cap = std::min(max_vel, kMaxCorrectingVel);
  if (d < 0 && erp > 0 && -d * erp / info.m_timeStep > cap) {
    push = static_cast<btScalar>(-d * erp / info.m_timeStep - cap);
    d = static_cast<btScalar>(-cap * info.m_timeStep / erp);
  }
  cp.m_distance1 = d;
  return push;
}

// One manifold with a multibody on at least one side: per point one normal row and two friction rows, set up by
// Bullet's own row builders, with Gazebo's pair rules for the coefficients, directions and depth.
void SurfaceSolver::convert(btPersistentManifold* m, const btContactSolverInfo& info, bool rules) {
  auto* co0 = const_cast<btCollisionObject*>(m->getBody0());
  auto* co1 = const_cast<btCollisionObject*>(m->getBody1());
  const btMultiBodyLinkCollider* fcA = btMultiBodyLinkCollider::upcast(co0);
  const btMultiBodyLinkCollider* fcB = btMultiBodyLinkCollider::upcast(co1);
  btMultiBody* mbA = fcA ? fcA->m_multiBody : nullptr;
  btMultiBody* mbB = fcB ? fcB->m_multiBody : nullptr;
  const int bodyA = mbA ? -1 : getOrInitSolverBody(*co0, info.m_timeStep);
  const int bodyB = mbB ? -1 : getOrInitSolverBody(*co1, info.m_timeStep);

  // The points in contact, deepest first (ties by index), cut to the pair's maxContacts.
  const int n = m->getNumContacts();
  std::array<int, kManifoldPoints> order{};
  int used = 0;
  std::optional<int> keep;
  for (int j = 0; j < n && j < kManifoldPoints; ++j) {
    const btManifoldPoint& cp = m->getContactPoint(j);
    if (cp.getDistance() > m->getContactProcessingThreshold()) continue;
    order[used++] = j;
    if (!rules) continue;
    const PairSurface p = combine(co0, surface_at(co0, cp.m_index0), co1, surface_at(co1, cp.m_index1));
    if (p.max_contacts) keep = keep ? std::min(*keep, *p.max_contacts) : *p.max_contacts;
  }
  // deepest first, ties in manifold order (a stable insertion sort: std::stable_sort's order without its buffer,
  // which it allocates on every call)
  for (int i = 1; i < used; ++i) {
    const int x = order[i];
    const btScalar d = m->getContactPoint(x).getDistance();
    int k = i;
    for (; k > 0 && d < m->getContactPoint(order[k - 1]).getDistance(); --k) order[k] = order[k - 1];
    order[k] = x;
  }
  if (keep && *keep < used) used = std::max(*keep, 0);
  std::array<bool, kManifoldPoints> active{};
  for (int k = 0; k < used; ++k) active[order[k]] = true;

  for (int j = 0; j < n; ++j) {
    btManifoldPoint& cp = m->getContactPoint(j);
    if (j >= kManifoldPoints || !active[j]) {
      // not in contact (or cut): no warm start from it
      cp.m_appliedImpulse = 0;
      cp.m_prevRHS = 0;
      continue;
    }
    // without rules: Bullet's normal row (its own stiffness and erp), friction 0
    PairSurface p;
    p.mu1 = p.mu2 = 0.0;
    if (rules) p = combine(co0, surface_at(co0, cp.m_index0), co1, surface_at(co1, cp.m_index1));
    if (p.stiffness) {
      // Bullet's solver turns these into erp = dt kp / (dt kp + kd), cfm = 1 / (dt kp + kd), as ODE
      cp.m_contactPointFlags |= BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING;
      cp.m_combinedContactStiffness1 = p.kp;
      cp.m_combinedContactDamping1 = p.kd;
    }
    if (rules) cp.m_combinedFriction = std::max(p.mu1, p.mu2);

    const int normal_index = m_multiBodyNormalContactConstraints.size();
    btMultiBodySolverConstraint& c = m_multiBodyNormalContactConstraints.expandNonInitializing();
    c.m_orgConstraint = nullptr;
    c.m_orgDofIndex = -1;
    c.m_solverBodyIdA = bodyA;
    c.m_solverBodyIdB = bodyB;
    c.m_multiBodyA = mbA;
    if (mbA) c.m_linkA = fcA->m_link;
    c.m_multiBodyB = mbB;
    if (mbB) c.m_linkB = fcB->m_link;
    c.m_originalContactPoint = &cp;

    // The depth the normal row corrects [m] (negative distance): less minDepth, and no more than maxVel can
    // correct in one step at the row's erp (the surface's maxVel, Gazebo's 0.01 m/s when unset, truncated by the
    // world's contact_max_correcting_vel). What the cap holds back moves positions only (ODE's split: below).
    const btScalar distance = cp.m_distance1;
    const double erp = p.stiffness ? info.m_timeStep * p.kp / (info.m_timeStep * p.kp + p.kd) : info.m_erp2;
    // [m/s] correction velocity held back by the cap
    const btScalar push = cap_depth(cp, info, erp, p.max_vel.value_or(kDefaultMaxVel), p.min_depth.value_or(0.0));
    btScalar relaxation;
    if (own_)
      setup_row(c, cp.m_normalWorldOnB, cp, info, relaxation, false);
    else
      setupMultiBodyContactConstraint(c, cp.m_normalWorldOnB, cp.m_appliedImpulse, cp, info, relaxation, false);
    cp.m_distance1 = distance;
    if (push > 0) push_.push_back({normal_index, push * c.m_jacDiagABInv, 0});
    c.m_frictionIndex = m_multiBodyFrictionContactConstraints.size();
    if (p.mu1 == 0 && p.mu2 == 0) {
      // no friction on this pair: no friction rows (the finish points this row at idle ones)
      no_friction_rows_.push_back(normal_index);
      cp.m_appliedImpulseLateral1 = cp.m_appliedImpulseLateral2 = 0;
      continue;
    }

    // Friction directions: fdir1 projected onto the contact plane, else Bullet's plane space of the normal (as
    // its own path); direction 2 = normal x direction 1.
    const btVector3& normal = cp.m_normalWorldOnB;
    btVector3 d1, d2;
    btPlaneSpace1(normal, d1, d2);
    if (p.fdir1) {
      const btVector3 f = *p.fdir1 - normal * normal.dot(*p.fdir1);
      if (f.length2() > btScalar(1e-12)) {
        d1 = f.normalized();
        d2 = normal.cross(d1);
      }
    }
    cp.m_lateralFrictionDir1 = d1;
    cp.m_lateralFrictionDir2 = d2;
    // each row limited by its own coefficient times the normal impulse (ODE's friction pyramid); with one
    // coefficient for both directions, the pair is solved together by Coulomb's isotropic law (docs: "Skid
    // steering")
    circle_.resize(m_multiBodyFrictionContactConstraints.size(), 0);
    circle_.push_back(p.mu1 == p.mu2 ? 1 : 0);
    circle_.push_back(0);
    if (own_) {
      add_friction_row(cp.m_lateralFrictionDir1, m, normal_index, cp, relaxation, info).m_friction = p.mu1;
      add_friction_row(cp.m_lateralFrictionDir2, m, normal_index, cp, relaxation, info).m_friction = p.mu2;
    } else {
      addMultiBodyFrictionConstraint(cp.m_lateralFrictionDir1, cp.m_appliedImpulseLateral1, m, normal_index, cp, co0,
                                     co1, relaxation, info)
          .m_friction = p.mu1;
      addMultiBodyFrictionConstraint(cp.m_lateralFrictionDir2, cp.m_appliedImpulseLateral2, m, normal_index, cp, co0,
                                     co1, relaxation, info)
          .m_friction = p.mu2;
    }
  }
}

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

  // cfm = 1 / (dt kp + kd), erp = dt kp / (dt kp + kd)
  btScalar cfm, erp;
  if (friction) {
    cfm = info.m_frictionCFM;
    erp = info.m_frictionERP;
  } else {
    cfm = info.m_globalCfm;
    erp = info.m_erp2;
    if ((cp.m_contactPointFlags & BT_CONTACT_FLAG_HAS_CONTACT_CFM) ||
        (cp.m_contactPointFlags & BT_CONTACT_FLAG_HAS_CONTACT_ERP)) {
      if (cp.m_contactPointFlags & BT_CONTACT_FLAG_HAS_CONTACT_CFM) cfm = cp.m_contactCFM;
      if (cp.m_contactPointFlags & BT_CONTACT_FLAG_HAS_CONTACT_ERP) erp = cp.m_contactERP;
    } else if (cp.m_contactPointFlags & BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING) {
      btScalar denom = info.m_timeStep * cp.m_combinedContactStiffness1 + cp.m_combinedContactDamping1;
      if (denom < SIMD_EPSILON) denom = SIMD_EPSILON;
      cfm = btScalar(1) / denom;
      erp = (info.m_timeStep * cp.m_combinedContactStiffness1) / denom;
    }
  }
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


SurfaceSolver* SurfaceSolver::converting() { return converting_; }

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
