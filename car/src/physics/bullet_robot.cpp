// BulletRobot's members: the multibody built from the body tree, its colliders and constraints, link states, the
// per-step forces, and motion and contact (issue 11).
#include "bullet_robot.hpp"

#include <BulletDynamics/Featherstone/btMultiBodyJointLimitConstraint.h>

#include <algorithm>
#include <cmath>

#include "surface.hpp"

namespace car_sim {
namespace physics {

namespace {

// A wheel: one cylinder spinning about its own axis. It collides as a sphere of the wheel radius, so it
// touches the ground at one point under its centre, the way an ideal rolling wheel does.
bool is_wheel(const Body& b) {
  if (!b.joint || b.shapes.size() != 1 || b.shapes[0].shape.type != ShapeType::Cylinder) return false;
  if (b.joint->type != JointType::Continuous && b.joint->type != JointType::Revolute) return false;
  const Eigen::Vector3d cyl_axis = b.shapes[0].in_top.linear() * Eigen::Vector3d::UnitZ();
  return std::abs(cyl_axis.dot(b.joint->axis)) > 0.99;
}

// A ball caster: one sphere centred on an undriven continuous joint. URDF cannot say "rolls in every
// direction", so models write a continuous joint (the seed's casters even with axis 1 1 1, one diagonal
// axis to a physics engine). car simulates the intended part: the sphere carries load and rolls freely in
// every direction, i.e. its contact has no friction.
bool is_ball_caster(const Body& b, const std::set<std::string>& driven) {
  if (!b.joint || b.joint->type != JointType::Continuous || driven.count(b.joint->name)) return false;
  if (b.shapes.size() != 1 || b.shapes[0].shape.type != ShapeType::Sphere) return false;
  return b.shapes[0].in_top.translation().norm() < 1e-9;
}

}  // namespace

BulletRobot::BulletRobot(Physics::Impl& P, const RobotModel& model, const std::string& name,
                         const Eigen::Isometry3d& pose, const std::set<std::string>& driven)
    : P_(P), model_(model), name_(name), tree_(detail::build_bodies(model_)) {
  const int n_links = static_cast<int>(tree_.bodies.size()) - 1;
  const Body& base = tree_.bodies[0];
  // a model anchored to `world` has a fixed base (btMultiBody fixedBase)
  const bool fixed_base = model_.anchored() && base.top == "world";
  mb_ = std::make_unique<btMultiBody>(n_links, base.mass, bt(base.principal), fixed_base, false);
  btMultiBody* mb = mb_.get();
  mb->setBaseWorldTransform(bt(pose * base.top_to_com));
  mb->setLinearDamping(0.0);
  mb->setAngularDamping(0.0);
  mb->setUseGyroTerm(true);
  mb->setHasSelfCollision(false);
  mb->setMaxCoordinateVelocity(1000.0);
  for (int i = 1; i <= n_links; ++i) {
    const Body& b = tree_.bodies[i];
    const Body& p = tree_.bodies[b.parent];
    const Joint& j = *b.joint;
    // child link frame at zero joint position, in the parent body's top frame
    const Eigen::Isometry3d top_to_child = tree_.link_in_top.at(j.parent) * j.origin;
    const Eigen::Isometry3d pcom_to_child = p.top_to_com.inverse() * top_to_child;
    const Eigen::Isometry3d child_to_com = b.top_to_com;
    // rotation from the parent com frame to this com frame
    const Eigen::Matrix3d rot_parent_to_this = (pcom_to_child.linear() * child_to_com.linear()).transpose();
    const Eigen::Vector3d axis_in_com = child_to_com.linear().transpose() * j.axis;
    const Eigen::Vector3d pivot_in_parent = pcom_to_child.translation();
    const Eigen::Vector3d pivot_to_com = child_to_com.linear().transpose() * child_to_com.translation();
    if (j.type == JointType::Prismatic) {
      mb->setupPrismatic(i - 1, b.mass, bt(b.principal), b.parent - 1, bt_quat(rot_parent_to_this), bt(axis_in_com),
                         bt(pivot_in_parent), bt(pivot_to_com), true);
    } else {
      mb->setupRevolute(i - 1, b.mass, bt(b.principal), b.parent - 1, bt_quat(rot_parent_to_this), bt(axis_in_com),
                        bt(pivot_in_parent), bt(pivot_to_com), true);
    }
    joint_link_[j.name] = i - 1;
    link_joint_.push_back(&j);
  }
  mb->finalizeMultiDof();
  P_.world.addMultiBody(mb);

  // Colliders, one per body with shapes, each shape with its link's surface (surface.hpp).
  bool self_collision = false;
  for (int i = 0; i <= n_links; ++i) {
    const Body& b = tree_.bodies[i];
    std::vector<std::pair<Shape, Eigen::Isometry3d>> parts;
    std::vector<const detail::BodyShape*> from;  // the body shape each part came from
    if (is_wheel(b)) {
      Shape sphere;
      sphere.type = ShapeType::Sphere;
      sphere.radius = b.shapes[0].shape.radius;
      Eigen::Isometry3d at = Eigen::Isometry3d::Identity();
      at.translation() = b.shapes[0].in_top.translation();
      parts.emplace_back(sphere, b.top_to_com.inverse() * at);
      from.push_back(&b.shapes[0]);
    } else {
      for (const auto& s : b.shapes) {
        if (s.shape.type == ShapeType::Plane) continue;
        parts.emplace_back(s.shape, b.top_to_com.inverse() * s.in_top);
        from.push_back(&s);
      }
    }
    std::vector<int> kept;
    btCollisionShape* shape = P_.make_body_shape(parts, &kept);
    // A body without shapes still gets a collider (an empty shape): Bullet solves a multibody link's joint
    // limits and motors only in its collider's simulation island.
    if (!shape) shape = P_.own(new btEmptyShape());
    auto surfaces = std::make_unique<SurfaceSet>();
    for (int k : kept) {
      // fdir1 is given in the collision frame: rotate it into the collider (com) frame
      const Eigen::Matrix3d R = (b.top_to_com.inverse() * from[k]->in_top).linear();
      Surface sf = link_surface(*from[k]->gz, R);
      if (is_ball_caster(b, driven)) sf.mu1 = sf.mu2 = 0.0;
      surfaces->shapes.push_back(sf);
    }
    for (const auto& link : b.links)
      surfaces->self_collide = surfaces->self_collide || model_.find_link(link)->gazebo.self_collide.value_or(false);
    self_collision = self_collision || surfaces->self_collide;
    surfaces->finish();
    auto col = std::make_unique<SurfaceCollider>(mb, i - 1);
    col->setCollisionShape(shape);
    col->setFriction(surfaces->shapes.front().mu1);
    col->setRestitution(0.0);
    P_.attach(col.get(), std::move(surfaces));
    P_.name_object(col.get(), name_ + "/" + b.top);
    if (i == 0 && fixed_base) {
      // a fixed base is static: it touches moving things only
      col->setCollisionFlags(col->getCollisionFlags() | btCollisionObject::CF_STATIC_OBJECT);
      P_.world.addCollisionObject(col.get(), btBroadphaseProxy::StaticFilter,
                                  btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter);
    } else {
      P_.world.addCollisionObject(col.get(), btBroadphaseProxy::DefaultFilter, btBroadphaseProxy::AllFilter);
    }
    if (i == 0)
      mb->setBaseCollider(col.get());
    else
      mb->getLink(i - 1).m_collider = col.get();
    colliders_.push_back(std::move(col));
  }
  mb->setHasSelfCollision(self_collision);
  // Hard stops on revolute and prismatic joints; Coulomb joint friction as a zero-velocity motor.
  for (const auto& j : model_.joints) {
    if (j.type == JointType::Fixed) continue;
    const auto found = joint_link_.find(j.name);
    // a joint that hangs from no body of the tree (a loop the loader did not catch)
    if (found == joint_link_.end())
      throw LoadError(model_.source, 0, "joint[" + j.name + "]", "is not connected to the root link '" + model_.root_link + "'");
    const int link = found->second;
    const bool bounded = j.type == JointType::Revolute || j.type == JointType::Prismatic;
    if (bounded && j.limits && j.limits->lower < j.limits->upper)
      add_constraint(new btMultiBodyJointLimitConstraint(mb, link, j.limits->lower, j.limits->upper));
    if (j.friction > 0.0) add_constraint(new JointMotor(mb, link, 0, 0.0, j.friction * P_.options.dt));
  }
  collect_link_forces();
  update_colliders();
}

ModelState BulletRobot::link_state(const std::string& link) const {
  const auto it = tree_.body_of_link.find(link);
  if (it == tree_.body_of_link.end())
    throw std::invalid_argument("robot '" + name_ + "' has no link '" + link + "'");
  const int body = it->second;
  ModelState s;
  const Eigen::Isometry3d com = body_com_pose(body);
  s.pose = com * tree_.bodies[body].top_to_com.inverse() * tree_.link_in_top.at(link);
  Eigen::Vector3d v_com;
  if (body == 0) {
    s.angular = eig(mb_->getBaseOmega());
    v_com = eig(mb_->getBaseVel());
  } else {
    // each body's spatial velocity in its own (com) frame, then into the world
    const int n = mb_->getNumLinks();
    std::vector<btVector3> omega(n + 1), vel(n + 1);
    mb_->compTreeLinkVelocities(omega.data(), vel.data());
    s.angular = com.linear() * eig(omega[body]);
    v_com = com.linear() * eig(vel[body]);
  }
  // velocity of the link frame's origin
  s.linear = v_com + s.angular.cross(s.pose.translation() - com.translation());
  return s;
}

void BulletRobot::collect_link_forces() {
  for (size_t i = 1; i < tree_.bodies.size(); ++i)
    if (tree_.bodies[i].joint->damping > 0.0) joint_damping_.emplace_back(static_cast<int>(i) - 1, tree_.bodies[i].joint->damping);
  for (size_t i = 0; i < tree_.bodies.size(); ++i) {
    const Body& b = tree_.bodies[i];
    for (const auto& name : b.links) {
      const Link* l = model_.find_link(name);
      const auto& g = l->gazebo;
      const bool no_gravity = g.gravity ? !*g.gravity : g.turn_gravity_off.value_or(false);
      const double decay = g.damping_factor.value_or(0.0);
      if (!l->inertial || (!no_gravity && decay <= 0.0)) continue;
      // the link's inertial frame in the body's com frame
      const Eigen::Isometry3d T = b.top_to_com.inverse() * tree_.link_in_top.at(name) * l->inertial->origin;
      LinkForce f;
      f.body = static_cast<int>(i);
      f.mass = l->inertial->mass;
      f.com = T.translation();
      f.inertia = T.linear() * simulated_inertia(l->inertial->inertia) * T.linear().transpose();
      f.no_gravity = no_gravity;
      f.decay = decay;
      link_forces_.push_back(f);
    }
  }
}

void BulletRobot::apply_forces(double dt, const Eigen::Vector3d& gravity) {
  btMultiBody* mb = mb_.get();
  for (const auto& [link, d] : joint_damping_) mb->addJointTorque(link, -d * mb->getJointVel(link));
  if (link_forces_.empty()) return;
  const int n = mb->getNumLinks();
  std::vector<btVector3> omega(n + 1), vel(n + 1);
  mb->compTreeLinkVelocities(omega.data(), vel.data());
  btAlignedObjectArray<btQuaternion> q;
  btAlignedObjectArray<btVector3> v;
  mb->forwardKinematics(q, v);
  for (const auto& f : link_forces_) {
    const Eigen::Isometry3d com =
        f.body == 0 ? eig(mb->getBaseWorldTransform()) : eig(mb->getLink(f.body - 1).m_cachedWorldTransform);
    const Eigen::Matrix3d& R = com.linear();
    const Eigen::Vector3d w = R * eig(omega[f.body]);
    const Eigen::Vector3d r = R * f.com;  // body com -> link com, world
    Eigen::Vector3d force = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
    if (f.no_gravity) force -= f.mass * gravity;
    if (f.decay > 0.0) {
      const Eigen::Vector3d v_link = R * eig(vel[f.body]) + w.cross(r);
      force -= f.mass * f.decay / dt * v_link;
      torque -= f.decay / dt * (R * f.inertia * R.transpose()) * w;
    }
    torque += r.cross(force);
    if (f.body == 0) {
      mb->addBaseForce(bt(force));
      mb->addBaseTorque(bt(torque));
    } else {
      mb->addLinkForce(f.body - 1, bt(force));
      mb->addLinkTorque(f.body - 1, bt(torque));
    }
  }
}

// ---- motion and contact (issue 11) ---------------------------------------------------------------------------

int BulletRobot::body_index(const std::string& link) const {
  const auto it = tree_.body_of_link.find(link);
  if (it == tree_.body_of_link.end()) throw std::invalid_argument("robot '" + name_ + "' has no link '" + link + "'");
  return it->second;
}

Eigen::Vector3d BulletRobot::body_com(const std::string& link) const {
  return body_com_pose(body_index(link)).translation();
}

// Bullet applies a body's force at its centre of mass: a force at another point adds (point - com) x force.
void BulletRobot::apply_wrench(const std::string& link, const Eigen::Vector3d& force, const Eigen::Vector3d& torque,
                               const Eigen::Vector3d& point) {
  const int b = body_index(link);
  const Eigen::Vector3d com = body_com_pose(b).translation();
  const Eigen::Vector3d tau = torque + (point - com).cross(force);
  if (b == 0) {
    mb_->addBaseForce(bt(force));
    mb_->addBaseTorque(bt(tau));
  } else {
    mb_->addLinkForce(b - 1, bt(force));
    mb_->addLinkTorque(b - 1, bt(tau));
  }
}

void BulletRobot::set_root_velocity(const Eigen::Vector3d& linear, const Eigen::Vector3d& angular) {
  const Eigen::Isometry3d origin = eig(mb_->getBaseWorldTransform()) * tree_.bodies[0].top_to_com.inverse();
  const Eigen::Vector3d com = eig(mb_->getBasePos());
  mb_->setBaseOmega(bt(angular));
  mb_->setBaseVel(bt(Eigen::Vector3d(linear + angular.cross(com - origin.translation()))));
}

void BulletRobot::set_joint_position(int joint, double position) {
  mb_->setJointPos(joint, position);
  mb_->setJointVel(joint, 0.0);
  update_colliders();
}

void BulletRobot::enable_joint_wrench(int joint) {
  if (joint < 0 || joint >= mb_->getNumLinks()) throw std::invalid_argument("no moving joint " + std::to_string(joint));
  if (mb_->getLink(joint).m_jointFeedback) return;
  feedback_.push_back(std::make_unique<btMultiBodyJointFeedback>());
  mb_->getLink(joint).m_jointFeedback = feedback_.back().get();
}

// Bullet's reaction: the spatial force on the child body in its centre-of-mass frame (torque about the com);
// car reports it in the child link's frame, torque about the link's origin.
Wrench BulletRobot::joint_wrench(int joint) const {
  Wrench w;
  const btMultibodyLink& l = mb_->getLink(joint);
  if (!l.m_jointFeedback) return w;
  const int body = joint + 1;
  const Eigen::Isometry3d com = body_com_pose(body);
  const Eigen::Vector3d f_world = com.linear() * eig(l.m_jointFeedback->m_reactionForces.getLinear());
  const Eigen::Vector3d t_world = com.linear() * eig(l.m_jointFeedback->m_reactionForces.getAngular());
  const std::string& child = tree_.bodies[body].top;
  const Eigen::Isometry3d link = com * tree_.bodies[body].top_to_com.inverse() * tree_.link_in_top.at(child);
  w.force = link.linear().transpose() * f_world;
  w.torque = link.linear().transpose() * (t_world + (com.translation() - link.translation()).cross(f_world));
  return w;
}

std::vector<LinkContact> BulletRobot::link_contacts(const std::string& link) const {
  std::vector<LinkContact> out;
  const btCollisionObject* mine = collider(body_index(link));
  if (!mine) return out;
  btDispatcher* d = P_.world.getDispatcher();
  for (int i = 0; i < d->getNumManifolds(); ++i) {
    const btPersistentManifold* m = d->getManifoldByIndexInternal(i);
    const bool is_a = m->getBody0() == mine;
    if (!is_a && m->getBody1() != mine) continue;
    const btCollisionObject* other = is_a ? m->getBody1() : m->getBody0();
    const int idx = other->getUserIndex();
    std::string name = idx >= 0 && idx < static_cast<int>(P_.object_names.size()) ? P_.object_names[idx] : "?";
    const auto slash = name.find('/');
    if (slash != std::string::npos) name.replace(slash, 1, "::");
    for (int k = 0; k < m->getNumContacts(); ++k) {
      const btManifoldPoint& p = m->getContactPoint(k);
      if (p.getAppliedImpulse() <= 0.0) continue;
      LinkContact c;
      c.other = name;
      // normalWorldOnB points from B towards A: into this link when it is A
      c.normal = is_a ? eig(p.m_normalWorldOnB) : Eigen::Vector3d(-eig(p.m_normalWorldOnB));
      c.position = eig(is_a ? p.getPositionWorldOnA() : p.getPositionWorldOnB());
      c.depth = std::max(0.0, -static_cast<double>(p.getDistance()));
      c.normal_force = p.getAppliedImpulse() / P_.options.dt;
      out.push_back(std::move(c));
    }
  }
  return out;
}

}  // namespace physics
}  // namespace car_sim
