// The physics side of the gazebo_ros API services (see services.hpp). Bullet clears applied forces after every
// step, so the world re-applies a wrench or an effort on every step it lasts.
#include "services.hpp"

#include <btBulletDynamicsCommon.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>

#include "convert.hpp"

namespace car_sim {
namespace physics {

void set_joint_positions(Robot& robot, const std::map<int, double>& positions, bool keep_speeds) {
  btMultiBody* mb = robot.multibody();
  for (const auto& [joint, q] : positions) {
    mb->setJointPos(joint, q);
    if (!keep_speeds) mb->setJointVel(joint, 0.0);
  }
  btAlignedObjectArray<btQuaternion> q;
  btAlignedObjectArray<btVector3> v;
  mb->updateCollisionObjectWorldTransforms(q, v);
}

Eigen::Vector3d body_com(const Robot& robot, const std::string& link) {
  btMultiBody* mb = robot.multibody();
  const int body = robot.body_of_link(link);
  if (body < 0) return eig(mb->getBasePos());
  btAlignedObjectArray<btQuaternion> qs;
  btAlignedObjectArray<btVector3> vs;
  mb->forwardKinematics(qs, vs);
  return eig(mb->getLink(body).m_cachedWorldTransform.getOrigin());
}

void add_link_wrench(Robot& robot, const std::string& link, const Eigen::Vector3d& force, const Eigen::Vector3d& t) {
  btMultiBody* mb = robot.multibody();
  const int body = robot.body_of_link(link);
  if (body < 0) {
    mb->addBaseForce(bt(force));
    mb->addBaseTorque(bt(t));
  } else {
    mb->addLinkForce(body, bt(force));
    mb->addLinkTorque(body, bt(t));
  }
}

void add_body_wrench(btRigidBody& body, const Eigen::Vector3d& force, const Eigen::Vector3d& torque) {
  body.activate(true);
  body.applyCentralForce(bt(force));
  body.applyTorque(bt(torque));
}

void add_joint_effort(Robot& robot, int joint, double effort) { robot.multibody()->addJointTorque(joint, effort); }

void set_gravity(Physics& physics, const Eigen::Vector3d& gravity) {
  btMultiBodyDynamicsWorld& w = physics.bullet();
  // the world's gravity reaches multibodies at every step; rigid bodies take it here (non-static ones)
  w.setGravity(bt(gravity));
  for (int i = 0; i < w.getNumCollisionObjects(); ++i)
    if (btRigidBody* rb = btRigidBody::upcast(w.getCollisionObjectArray()[i])) {
      rb->setGravity(bt(gravity));
      rb->activate(true);
    }
}

void set_solver_iterations(Physics& physics, int iterations) {
  physics.bullet().getSolverInfo().m_numIterations = iterations;
}

int solver_iterations(Physics& physics) { return physics.bullet().getSolverInfo().m_numIterations; }

}  // namespace physics
}  // namespace car_sim
