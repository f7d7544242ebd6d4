// Gazebo's surface rules on Bullet (docs/COMPAT-physics.md): surfaces, the pair rules, and each manifold's conversion
// into rows (set up in contact_rows.cpp, solved in surface_solver.cpp).
#include "surface.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace car_sim {
namespace physics {

namespace {

// The solver whose joint constraints are making their rows on this thread (JointMotor asks it for responses).
thread_local SurfaceSolver* converting_ = nullptr;

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

SurfaceSolver* SurfaceSolver::converting() { return converting_; }

}  // namespace physics
}  // namespace car_sim
