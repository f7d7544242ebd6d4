// The physics guards itself: after every step each body's pose and velocity (and each multibody's joint
// coordinates) must be finite, so a blow-up stops the world with the body's name instead of spreading NaN.
#include "guard.hpp"

#include <btBulletDynamicsCommon.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include <cmath>
#include <sstream>

namespace car_sim {
namespace physics {

namespace {

bool finite(const btVector3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

// A pose is finite when its origin and its rotation matrix are (the matrix's quaternion is then finite too; reading
// the matrix costs no conversion).
bool finite(const btTransform& T) {
  const btMatrix3x3& R = T.getBasis();
  return finite(T.getOrigin()) && finite(R[0]) && finite(R[1]) && finite(R[2]);
}

std::string vec(const btVector3& v) {
  std::ostringstream os;
  os << "(" << v.x() << " " << v.y() << " " << v.z() << ")";
  return os.str();
}

std::string name_of(const btCollisionObject* o, const std::vector<std::string>& names) {
  const int i = o ? o->getUserIndex() : -1;
  return i >= 0 && i < static_cast<int>(names.size()) ? names[i] : std::string("an unnamed body");
}

// A multibody's name: that of its base collider, else of any link collider.
std::string name_of(const btMultiBody* mb, const std::vector<std::string>& names) {
  if (mb->getBaseCollider()) return name_of(mb->getBaseCollider(), names);
  for (int i = 0; i < mb->getNumLinks(); ++i)
    if (mb->getLink(i).m_collider) return name_of(mb->getLink(i).m_collider, names);
  return "a robot without colliders";
}

// Adds x - x for every value: 0 for a finite one, NaN for an infinite one or NaN (so the sum stays 0 only while all
// are finite), without a branch per value.
void add(double& sum, const btVector3& v) { sum += (v.x() - v.x()) + (v.y() - v.y()) + (v.z() - v.z()); }
void add(double& sum, const btTransform& T) {
  add(sum, T.getOrigin());
  for (int r = 0; r < 3; ++r) add(sum, T.getBasis()[r]);
}

// Whether every value first_non_finite reads is finite (its test, in one pass without branches).
bool all_finite(const btMultiBodyDynamicsWorld& world) {
  double sum = 0;
  const btCollisionObjectArray& objs = world.getCollisionObjectArray();
  for (int i = 0; i < objs.size(); ++i) {
    const btCollisionObject* o = objs[i];
    if (o->getInternalType() == btCollisionObject::CO_COLLISION_OBJECT && o->isStaticObject()) continue;
    add(sum, o->getWorldTransform());
    if (const btRigidBody* rb = btRigidBody::upcast(o)) {
      add(sum, rb->getLinearVelocity());
      add(sum, rb->getAngularVelocity());
    }
  }
  for (int m = 0; m < world.getNumMultibodies(); ++m) {
    const btMultiBody* mb = world.getMultiBody(m);
    add(sum, mb->getBaseWorldTransform());
    add(sum, mb->getBaseVel());
    add(sum, mb->getBaseOmega());
    for (int l = 0; l < mb->getNumLinks(); ++l) {
      const double q = mb->getJointPos(l), qd = mb->getJointVel(l);
      sum += (q - q) + (qd - qd);
    }
  }
  return sum == 0;
}

}  // namespace

std::string first_non_finite(const btMultiBodyDynamicsWorld& world, const std::vector<std::string>& names) {
  // the usual case in one pass; the first culprit and its message from the tests below
  if (all_finite(world)) return "";
  const btCollisionObjectArray& objs = world.getCollisionObjectArray();
  for (int i = 0; i < objs.size(); ++i) {
    const btCollisionObject* o = objs[i];
    // the world's static shapes never move (a robot's fixed base is checked with its multibody below)
    if (o->getInternalType() == btCollisionObject::CO_COLLISION_OBJECT && o->isStaticObject()) continue;
    if (!finite(o->getWorldTransform()))
      return name_of(o, names) + ": position " + vec(o->getWorldTransform().getOrigin());
    if (const btRigidBody* rb = btRigidBody::upcast(o)) {
      if (!finite(rb->getLinearVelocity())) return name_of(o, names) + ": velocity " + vec(rb->getLinearVelocity());
      if (!finite(rb->getAngularVelocity()))
        return name_of(o, names) + ": angular velocity " + vec(rb->getAngularVelocity());
    }
  }
  for (int m = 0; m < world.getNumMultibodies(); ++m) {
    const btMultiBody* mb = world.getMultiBody(m);
    if (!finite(mb->getBaseWorldTransform())) return name_of(mb, names) + ": position " + vec(mb->getBasePos());
    if (!finite(mb->getBaseVel())) return name_of(mb, names) + ": velocity " + vec(mb->getBaseVel());
    if (!finite(mb->getBaseOmega())) return name_of(mb, names) + ": angular velocity " + vec(mb->getBaseOmega());
    for (int l = 0; l < mb->getNumLinks(); ++l) {
      const double q = mb->getJointPos(l), qd = mb->getJointVel(l);
      if (std::isfinite(q) && std::isfinite(qd)) continue;
      std::ostringstream os;
      os << ": joint coordinate " << q << ", rate " << qd << " (link " << l + 1 << ")";
      const btCollisionObject* c = mb->getLink(l).m_collider;
      return (c ? name_of(c, names) : name_of(mb, names)) + os.str();
    }
  }
  return "";
}

}  // namespace physics
}  // namespace car_sim
