// The Bullet world: robots as btMultiBody (reduced coordinates, fixed joints merged), world models as rigid
// bodies and static objects, Gazebo's friction rule, the wheel and ball-caster contact rules, motors, and the
// ray scene mirroring the collision geometry.
#include "physics.hpp"

#include <btBulletDynamicsCommon.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointLimitConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointFeedback.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <vector>

#include "bodies.hpp"
#include "guard.hpp"
#include "materials.hpp"
#include "island_world.hpp"
#include "physics_impl.hpp"
#include "surface.hpp"

namespace car_sim {
namespace physics {

using detail::Body;
using detail::BodyTree;

namespace {

// Gazebo (ODE) combines two surfaces' friction as the smaller of the two.
btScalar min_friction(const btCollisionObject* a, const btCollisionObject* b) {
  return std::min(a->getFriction(), b->getFriction());
}

btScalar no_restitution(const btCollisionObject*, const btCollisionObject*) { return 0.0; }

// How a URDF link looks to the sensors.
SurfaceLook urdf_look(const Link& l) {
  SurfaceLook look;
  look.laser_retro = l.gazebo.laser_retro.value_or(0.0);
  look.rgba = link_colour(l);
  return look;
}

// How an SDF link looks: its first visual's colour, its first laser retro.
SurfaceLook sdf_look(const WorldLink& l) {
  SurfaceLook look;
  look.rgba = l.visuals.empty() ? kDefaultColour : visual_colour(l.visuals.front());
  // one retro per link (car's ray scene knows the body a ray hit): the first collision's that sets one
  for (const auto& c : l.collisions)
    if (c.laser_retro) {
      look.laser_retro = *c.laser_retro;
      break;
    }
  return look;
}

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

// The surfaces of a world (SDF) object, one per collision: mu and mu2 (SDF sets no fdir1 or contact values here).
std::unique_ptr<SurfaceSet> world_surface(const std::vector<WorldCollision>& collisions) {
  auto set = std::make_unique<SurfaceSet>();
  for (const auto& c : collisions) {
    Surface s;
    s.mu1 = c.friction.mu;
    s.mu2 = c.friction.mu2;
    set->shapes.push_back(s);
  }
  return set;
}

}  // namespace

// ---- Bullet state -------------------------------------------------------------------------------------------

// ---- robots -------------------------------------------------------------------------------------------------

class BulletRobot : public Robot {
 public:
  BulletRobot(Physics::Impl& P, const RobotModel& model, const std::string& name, const Eigen::Isometry3d& pose,
              const std::set<std::string>& driven)
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

  ~BulletRobot() override {
    for (auto& c : constraints_) P_.world.removeMultiBodyConstraint(c.get());
    for (auto& c : colliders_) P_.world.removeCollisionObject(c.get());
    P_.world.removeMultiBody(mb_.get());
  }

  const std::string& name() const { return name_; }
  const BodyTree& tree() const { return tree_; }
  const RobotModel& model() const { return model_; }
  btMultiBody* mb() const { return mb_.get(); }
  btMultiBody* multibody() const override { return mb_.get(); }
  int body_of_link(const std::string& link) const override {
    const auto it = tree_.body_of_link.find(link);
    if (it == tree_.body_of_link.end())
      throw std::invalid_argument("robot '" + name_ + "' has no link '" + link + "'");
    return it->second - 1;
  }

  int joint(const std::string& name) const override {
    const auto it = joint_link_.find(name);
    return it == joint_link_.end() ? -1 : it->second;
  }
  double joint_position(int j) const override { return mb_->getJointPos(j); }
  double joint_velocity(int j) const override { return mb_->getJointVel(j); }

  // A motor's effort is capped by the joint's <limit effort> (when > 0).
  int add_motor(int joint, double max_effort) override {
    const Joint* j = link_joint_.at(joint);
    if (j->limits && j->limits->effort > 0.0) max_effort = std::min(max_effort, j->limits->effort);
    auto* m = new JointMotor(mb_.get(), joint, 0, 0.0, max_effort * P_.options.dt);
    add_constraint(m);
    motors_.push_back(m);
    motor_impulse_.push_back(max_effort * P_.options.dt);
    motor_joint_.push_back(j);
    return static_cast<int>(motors_.size()) - 1;
  }

  // The target velocity is clamped by the joint's <limit velocity> (when > 0).
  void set_motor(int motor, const MotorTarget& t) override {
    btMultiBodyJointMotor* m = motors_.at(motor);
    const Joint* j = motor_joint_.at(motor);
    double v = t.velocity;
    if (j->limits && j->limits->velocity > 0.0) v = std::clamp(v, -j->limits->velocity, j->limits->velocity);
    m->setVelocityTarget(v, t.kd);
    m->setPositionTarget(t.position, t.kp);
    m->setMaxAppliedImpulse(t.enabled ? motor_impulse_.at(motor) : 0.0);
  }

  bool has_link(const std::string& link) const override { return tree_.body_of_link.count(link) > 0; }

  Eigen::Isometry3d link_pose(const std::string& link) const override {
    const auto it = tree_.body_of_link.find(link);
    if (it == tree_.body_of_link.end())
      throw std::invalid_argument("robot '" + name_ + "' has no link '" + link + "'");
    const Body& b = tree_.bodies[it->second];
    return body_com_pose(it->second) * b.top_to_com.inverse() * tree_.link_in_top.at(link);
  }

  ModelState link_state(const std::string& link) const override {
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

  ModelState root_state() const override {
    ModelState s;
    s.pose = eig(mb_->getBaseWorldTransform()) * tree_.bodies[0].top_to_com.inverse();
    s.angular = eig(mb_->getBaseOmega());
    const Eigen::Vector3d com = eig(mb_->getBasePos());
    // velocity of the root frame's origin
    s.linear = eig(mb_->getBaseVel()) + s.angular.cross(s.pose.translation() - com);
    return s;
  }

  void set_root_state(const ModelState& st) override {
    const Eigen::Isometry3d com = st.pose * tree_.bodies[0].top_to_com;
    mb_->setBaseWorldTransform(bt(com));
    mb_->setBaseOmega(bt(st.angular));
    mb_->setBaseVel(bt(Eigen::Vector3d(st.linear + st.angular.cross(com.translation() - st.pose.translation()))));
    update_colliders();
  }

  // Pose of a body's com frame in the world.
  Eigen::Isometry3d body_com_pose(int body) const {
    if (body == 0) return eig(mb_->getBaseWorldTransform());
    btAlignedObjectArray<btQuaternion> q;
    btAlignedObjectArray<btVector3> v;
    mb_->forwardKinematics(q, v);
    return eig(mb_->getLink(body - 1).m_cachedWorldTransform);
  }

  const btCollisionObject* collider(int body) const {
    return body == 0 ? mb_->getBaseCollider() : mb_->getLink(body - 1).m_collider;
  }

 private:
  void add_constraint(btMultiBodyConstraint* c) {
    constraints_.emplace_back(c);
    P_.world.addMultiBodyConstraint(c);
  }

  void update_colliders() {
    btAlignedObjectArray<btQuaternion> q;
    btAlignedObjectArray<btVector3> v;
    mb_->updateCollisionObjectWorldTransforms(q, v);
  }

  Physics::Impl& P_;
  RobotModel model_;
  std::string name_;
  BodyTree tree_;
  std::unique_ptr<btMultiBody> mb_;
  std::vector<std::unique_ptr<btMultiBodyLinkCollider>> colliders_;
  std::vector<std::unique_ptr<btMultiBodyConstraint>> constraints_;  // joint limits and motors
  std::vector<btMultiBodyJointMotor*> motors_;
  std::vector<double> motor_impulse_;         // motor id -> its cap [N s] or [N m s] per step
  std::map<std::string, int> joint_link_;     // non-fixed joint -> multibody link index
  std::vector<const Joint*> link_joint_;      // multibody link index -> its joint
  std::vector<const Joint*> motor_joint_;     // motor id -> its joint

  // A link's share of its body for the per-step forces: gravity off and velocity decay (dampingFactor).
  struct LinkForce {
    int body = 0;                               // 0 = base, i = multibody link i - 1
    double mass = 0.0;                          // [kg]
    Eigen::Vector3d com = Eigen::Vector3d::Zero();       // [m] link centre of mass, body com frame
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();   // [kg m^2] about the link com, body com frame
    bool no_gravity = false;
    double decay = 0.0;                         // [-] per step
  };
  std::vector<LinkForce> link_forces_;
  std::vector<std::pair<int, double>> joint_damping_;  // (multibody link, damping) for joints with damping > 0

  void collect_link_forces() {
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

 public:
  // Forces for the coming step [N], [N m], world frame: joint damping -d q', gravity cancelled on links that
  // feel none, and ODE's per-step velocity decay v <- v (1 - f) as the force -m f v / dt.
  void apply_forces(double dt, const Eigen::Vector3d& gravity) {
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

 public:
  // ---- motion and contact (issue 11; defined at the end of this file) ----
  void apply_wrench(const std::string& link, const Eigen::Vector3d& force, const Eigen::Vector3d& torque,
                    const Eigen::Vector3d& point) override;
  Eigen::Vector3d body_com(const std::string& link) const override;
  void set_root_velocity(const Eigen::Vector3d& linear, const Eigen::Vector3d& angular) override;
  void set_joint_position(int joint, double position) override;
  void set_joint_velocity(int joint, double velocity) override { mb_->setJointVel(joint, velocity); }
  void enable_joint_wrench(int joint) override;
  Wrench joint_wrench(int joint) const override;
  std::vector<LinkContact> link_contacts(const std::string& link) const override;

 private:
  int body_index(const std::string& link) const;
  std::vector<std::unique_ptr<btMultiBodyJointFeedback>> feedback_;  // joint reaction sensors
};

Physics::Impl::Impl(const WorldDescription& d, const Options& o) : options(o) {
  world.setGravity(bt(d.gravity));
  btContactSolverInfo& si = world.getSolverInfo();
  si.m_numIterations = o.solver_iterations;
  // stop iterating once the solution has converged
  si.m_leastSquaresResidualThreshold = o.residual_threshold;
  // two friction directions per contact (ODE's friction pyramid, as Gazebo) instead of Bullet's cone
  si.m_solverMode |= SOLVER_DISABLE_IMPLICIT_CONE_FRICTION;
  // carry the whole previous impulse over, so a resting solution keeps converging from step to step
  si.m_warmstartingFactor = 1.0;
  world.set_row_setup(o.rows);
  world.set_reuse_at_rest(o.reuse_at_rest);
  world.set_own_island_sort(o.own_island_sort);
  gCalculateCombinedFrictionCallback = &min_friction;
  gCalculateCombinedRestitutionCallback = &no_restitution;
}

Physics::Impl::~Impl() {
  robots.clear();
  for (auto& o : objects) {
    if (auto* rb = btRigidBody::upcast(o.get()))
      world.removeRigidBody(rb);
    else
      world.removeCollisionObject(o.get());
  }
}

// ---- world models -------------------------------------------------------------------------------------------

void Physics::Impl::add_world_model(const WorldModelDesc& m) {
  if (m.is_static) {
    static_models.push_back({&m, m.pose, {}, {}});
    for (const auto& l : m.links) {
      const Eigen::Isometry3d T_link = m.pose * l.pose;
      for (const auto& c : l.collisions) {
        btCollisionShape* shape = nullptr;
        Eigen::Isometry3d T = T_link * c.shape.origin;
        if (c.shape.type == ShapeType::Plane) {
          // plane through the collision frame's origin, normal in that frame
          const Eigen::Vector3d n = (T.linear() * c.shape.normal).normalized();
          shape = own(new btStaticPlaneShape(bt(n), n.dot(T.translation())));
          T = Eigen::Isometry3d::Identity();
        } else {
          shape = make_shape(c.shape, false);
        }
        if (!shape) continue;
        auto* obj = new btCollisionObject();
        obj->setCollisionShape(shape);
        obj->setWorldTransform(bt(T));
        obj->setFriction(c.friction.mu);
        obj->setRestitution(0.0);
        attach(obj, world_surface({c}));
        objects.emplace_back(obj);
        name_object(obj, m.name + "/" + l.name);
        model_objects[m.name].push_back(obj);
        if (c.shape.type != ShapeType::Plane) static_models.back().parts.push_back({obj, &l, &c});
        // Static objects are asleep, as Bullet makes static rigid bodies (btDiscreteDynamicsWorld::addRigidBody):
        // a pair of a static object and a sleeping body then has no narrow phase and no island manifold (an awake
        // object still wakes nothing static: activate() leaves CF_STATIC_OBJECT alone).
        obj->setActivationState(ISLAND_SLEEPING);
        world.addCollisionObject(obj, btBroadphaseProxy::StaticFilter,
                                 btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter);
      }
    }
    return;
  }
  DynModel dm;
  dm.name = m.name;
  dm.desc = &m;
  for (const auto& l : m.links) {
    // principal frame of the link's inertia at its centre of mass
    const Inertial& in = *l.inertial;
    Eigen::Vector3d principal;
    const Eigen::Matrix3d R = detail::principal_axes(simulated_inertia(in.inertia), &principal);
    Eigen::Isometry3d link_to_com = in.origin;
    link_to_com.linear() = in.origin.linear() * R;
    std::vector<std::pair<Shape, Eigen::Isometry3d>> parts;
    double mu = 1.0;
    for (const auto& c : l.collisions) {
      parts.emplace_back(c.shape, link_to_com.inverse() * c.shape.origin);
      mu = c.friction.mu;
    }
    std::vector<int> kept;
    btCollisionShape* shape = make_body_shape(parts, &kept);
    std::vector<WorldCollision> kept_collisions;
    for (int i : kept) kept_collisions.push_back(l.collisions[i]);
    if (!shape) shape = own(new btEmptyShape());
    const Eigen::Isometry3d T = m.pose * l.pose * link_to_com;
    auto* ms = new btDefaultMotionState(bt(T));
    motion_states.emplace_back(ms);
    btRigidBody::btRigidBodyConstructionInfo ci(in.mass, ms, shape, bt(principal));
    ci.m_friction = mu;
    ci.m_restitution = 0.0;
    ci.m_linearDamping = 0.0;
    ci.m_angularDamping = 0.0;
    auto* rb = new btRigidBody(ci);
    // SDF <link><gravity>false: Bullet's own per-body switch (the body's gravity stays 0, world changes skip it)
    if (!l.gravity) rb->setFlags(rb->getFlags() | BT_DISABLE_WORLD_GRAVITY);
    attach(rb, world_surface(kept_collisions));
    // Resting world objects sleep (no work) until something touches them; the robot never sleeps.
    objects.emplace_back(rb);
    name_object(rb, m.name + "/" + l.name);
    model_objects[m.name].push_back(rb);
    world.addRigidBody(rb);
    dm.bodies.push_back(rb);
    dm.link_to_com.push_back(link_to_com);
  }
  dyn_models.push_back(std::move(dm));
}

const Physics::Impl::DynModel* Physics::Impl::canonical(const DynModel& dm) const {
  if (!dm.bodies.empty()) return &dm;
  for (const auto& other : dyn_models)
    if (!other.bodies.empty() && nested_in(other.name, dm.name)) return &other;
  return nullptr;
}

Eigen::Isometry3d Physics::Impl::dyn_model_pose(const DynModel& dm) const {
  // model frame from the canonical (first) link
  const Eigen::Isometry3d com = eig(dm.bodies[0]->getWorldTransform());
  return com * dm.link_to_com[0].inverse() * dm.desc->links[0].pose.inverse();
}

// ---- ray scene ----------------------------------------------------------------------------------------------

// The ray scene mirrors the collision geometry: static shapes at their world poses, every moving body (world
// rigid bodies, robot bodies split per link for their colours) as an instance in its Bullet com frame.
// Robot wheels are seen as the cylinders they are, not the spheres they roll on.
void Physics::Impl::build_rays() {
  rays = std::make_unique<RayScene>();
  moving_ray_bodies.clear();
  for (StaticModel& sm : static_models) {
    const WorldModelDesc* m = sm.desc;
    sm.ray_bodies.clear();
    for (const auto& l : m->links) {
      // a link's planes are a body apart (it stays where it was loaded), before the body of its other shapes
      std::vector<std::pair<Shape, Eigen::Isometry3d>> shapes, planes;
      for (const auto& c : l.collisions)
        (c.shape.type == ShapeType::Plane ? planes : shapes).emplace_back(c.shape, m->pose * l.pose * c.shape.origin);
      if (!planes.empty()) rays->add_body(planes, sdf_look(l));
      if (!shapes.empty()) sm.ray_bodies.push_back(rays->add_body(shapes, sdf_look(l)));
    }
    place_rays(sm);
  }
  for (const auto& dm : dyn_models) {
    for (size_t i = 0; i < dm.bodies.size(); ++i) {
      const WorldLink& l = dm.desc->links[i];
      std::vector<std::pair<Shape, Eigen::Isometry3d>> s;
      for (const auto& c : l.collisions) s.emplace_back(c.shape, dm.link_to_com[i].inverse() * c.shape.origin);
      if (s.empty()) continue;
      moving_ray_bodies.emplace_back(rays->add_body(s, sdf_look(l)), dm.bodies[i]);
    }
  }
  for (auto& r : robots) {
    const BodyTree& tree = r->tree();
    for (size_t b = 0; b < tree.bodies.size(); ++b) {
      const Body& body = tree.bodies[b];
      const btCollisionObject* col = r->collider(static_cast<int>(b));
      if (!col) continue;
      for (const auto& name : body.links) {
        const Link* l = r->model().find_link(name);
        std::vector<std::pair<Shape, Eigen::Isometry3d>> s;
        for (const auto& c : l->collisions)
          s.emplace_back(c, body.top_to_com.inverse() * tree.link_in_top.at(name) * c.origin);
        if (s.empty()) continue;
        moving_ray_bodies.emplace_back(rays->add_body(s, urdf_look(*l)), col);
      }
    }
  }
  rays_stamp = ~0ull;
}

// ---- Physics ------------------------------------------------------------------------------------------------

Physics::Physics(const WorldDescription& desc, const Options& options, const std::set<std::string>& removed)
    : impl_(std::make_unique<Impl>(desc, options)) {
  for (const auto& m : desc.models)
    if (!removed.count(m.name)) impl_->add_world_model(m);
}

Physics::~Physics() = default;

Robot& Physics::add_robot(const RobotModel& model, const std::string& name, const Eigen::Isometry3d& pose,
                          const std::set<std::string>& driven) {
  impl_->robots.push_back(std::make_unique<BulletRobot>(*impl_, model, name, pose, driven));
  impl_->rays.reset();
  return *impl_->robots.back();
}

void Physics::remove_robot(const std::string& name) {
  auto& rs = impl_->robots;
  rs.erase(std::remove_if(rs.begin(), rs.end(), [&](const auto& r) { return r->name() == name; }), rs.end());
  impl_->rays.reset();
}

void Physics::remove_world_model(const std::string& name) {
  for (btCollisionObject* o : impl_->model_objects[name]) {
    if (auto* rb = btRigidBody::upcast(o))
      impl_->world.removeRigidBody(rb);
    else
      impl_->world.removeCollisionObject(o);
    auto& objs = impl_->objects;
    objs.erase(std::remove_if(objs.begin(), objs.end(), [o](const auto& p) { return p.get() == o; }), objs.end());
  }
  impl_->model_objects.erase(name);
  auto& dms = impl_->dyn_models;
  dms.erase(std::remove_if(dms.begin(), dms.end(), [&](const Impl::DynModel& x) { return x.name == name; }), dms.end());
  auto& sms = impl_->static_models;
  sms.erase(std::remove_if(sms.begin(), sms.end(), [&](const Impl::StaticModel& x) { return x.desc->name == name; }),
            sms.end());
  impl_->rays.reset();
}

Robot* Physics::find_robot(const std::string& name) {
  for (auto& r : impl_->robots)
    if (r->name() == name) return r.get();
  return nullptr;
}

const Robot* Physics::find_robot(const std::string& name) const {
  for (const auto& r : impl_->robots)
    if (r->name() == name) return r.get();
  return nullptr;
}

void Physics::step(double dt) {
  const Eigen::Vector3d g = eig(impl_->world.getGravity());
  for (auto& r : impl_->robots) r->apply_forces(dt, g);
  // physics: one fixed step, no internal substepping
  impl_->world.stepSimulation(dt, 0, dt);
  ++impl_->steps;
  if (const std::string bad = first_non_finite(impl_->world, impl_->object_names); !bad.empty()) throw NonFiniteState(bad);
}

btMultiBodyDynamicsWorld& Physics::bullet() { return impl_->world; }

btRigidBody* Physics::world_model_body(const std::string& model, size_t link) {
  for (auto& dm : impl_->dyn_models)
    if (dm.name == model && link < dm.bodies.size()) return dm.bodies[link];
  return nullptr;
}

std::optional<ModelState> Physics::world_model_state(const std::string& name) const {
  for (const auto& dm : impl_->dyn_models) {
    if (dm.name != name) continue;
    ModelState s;
    const Impl::DynModel* c = impl_->canonical(dm);
    if (!c) {
      // no dynamic link anywhere below, at rest: the frame follows the first static nested model with a link
      // (its canonical link, Model::LoadLinks), else it stays where the world put it
      s.pose = dm.desc->pose;
      for (const auto& sm : impl_->static_models) {
        if (!nested_in(sm.desc->name, name) || sm.desc->links.empty()) continue;
        if (sm.pose.matrix() != sm.desc->pose.matrix()) s.pose = sm.pose * sm.desc->pose.inverse() * dm.desc->pose;
        break;
      }
      return s;
    }
    // the point whose velocity is the model's [m], world frame: the model frame's origin, or, for a model with only
    // nested models, the canonical link's origin (Model::WorldLinearVel: the canonical link's velocity)
    Eigen::Vector3d point;
    if (c == &dm) {
      s.pose = impl_->dyn_model_pose(dm);
      point = s.pose.translation();
    } else {
      // its frame keeps its load-time offset from the canonical link
      const Eigen::Isometry3d link = impl_->dyn_model_pose(*c) * c->desc->links[0].pose;
      const Eigen::Isometry3d link_in_model = dm.desc->pose.inverse() * c->desc->pose * c->desc->links[0].pose;
      s.pose = link * link_in_model.inverse();
      point = link.translation();
    }
    const btRigidBody* rb = c->bodies[0];
    const Eigen::Isometry3d com = eig(rb->getWorldTransform());
    s.angular = eig(rb->getAngularVelocity());
    s.linear = eig(rb->getLinearVelocity()) + s.angular.cross(point - com.translation());
    return s;
  }
  // a static model: where it was put, at rest
  for (const auto& sm : impl_->static_models) {
    if (sm.desc->name != name) continue;
    ModelState s;
    s.pose = sm.pose;
    return s;
  }
  return std::nullopt;
}

void Physics::Impl::place(StaticModel& sm, const Eigen::Isometry3d& pose) {
  sm.pose = pose;
  for (const auto& p : sm.parts) {
    // as add_world_model places it; the broad phase takes the new box at the next step (IslandWorld::updateAabbs)
    const btTransform T = bt(Eigen::Isometry3d(pose * p.link->pose * p.collision->shape.origin));
    p.object->setWorldTransform(T);
    p.object->setInterpolationWorldTransform(T);
  }
  if (rays) place_rays(sm);
}

void Physics::Impl::place_rays(const StaticModel& sm) {
  if (sm.pose.matrix() == sm.desc->pose.matrix()) return;  // where it was built
  const Eigen::Isometry3d moved = sm.pose * sm.desc->pose.inverse();
  for (int body : sm.ray_bodies) rays->set_pose(body, moved);
  rays_stamp = ~0ull;  // committed at the next rays()
}

bool Physics::set_world_model_state(const std::string& name, const ModelState& st) {
  const std::optional<ModelState> before = world_model_state(name);
  if (!before) return false;
  // Gazebo 11's Entity::SetWorldPoseModel: the nested models, static or not, move with the model, keeping their
  // poses relative to it; gazebo_ros's twist (Model::SetLinearVel) goes to the model's own links only
  const Eigen::Isometry3d moved = st.pose * before->pose.inverse();
  for (auto& nested : impl_->dyn_models) {
    if (!nested_in(nested.name, name)) continue;
    for (btRigidBody* b : nested.bodies) {
      const btTransform T = bt(Eigen::Isometry3d(moved * eig(b->getWorldTransform())));
      b->setWorldTransform(T);
      b->getMotionState()->setWorldTransform(T);
    }
  }
  // a static model takes the pose; its twist has no body to go to (ODELink::SetLinearVel without a body)
  for (auto& sm : impl_->static_models) {
    if (sm.desc->name == name)
      impl_->place(sm, st.pose);
    else if (nested_in(sm.desc->name, name))
      impl_->place(sm, moved * sm.pose);
  }
  for (auto& dm : impl_->dyn_models) {
    if (dm.name != name) continue;
    for (size_t i = 0; i < dm.bodies.size(); ++i) {
      const Eigen::Isometry3d com = st.pose * dm.desc->links[i].pose * dm.link_to_com[i];
      dm.bodies[i]->setWorldTransform(bt(com));
      dm.bodies[i]->getMotionState()->setWorldTransform(bt(com));
      dm.bodies[i]->setAngularVelocity(bt(st.angular));
      dm.bodies[i]->setLinearVelocity(
          bt(Eigen::Vector3d(st.linear + st.angular.cross(com.translation() - st.pose.translation()))));
    }
  }
  return true;
}

std::vector<Contact> Physics::contacts(double dt) const {
  std::vector<Contact> out;
  btDispatcher* d = impl_->world.getDispatcher();
  const auto& names = impl_->object_names;
  auto name = [&](const btCollisionObject* o) {
    const int i = o->getUserIndex();
    return i >= 0 && i < static_cast<int>(names.size()) ? names[i] : std::string("?");
  };
  for (int i = 0; i < d->getNumManifolds(); ++i) {
    const btPersistentManifold* m = d->getManifoldByIndexInternal(i);
    for (int k = 0; k < m->getNumContacts(); ++k) {
      const btManifoldPoint& p = m->getContactPoint(k);
      if (p.getAppliedImpulse() <= 0.0) continue;
      Contact c;
      c.a = name(m->getBody0());
      c.b = name(m->getBody1());
      c.position = eig(p.getPositionWorldOnB());
      c.normal = eig(p.m_normalWorldOnB);
      c.normal_force = p.getAppliedImpulse() / dt;
      out.push_back(std::move(c));
    }
  }
  return out;
}

const RayScene& Physics::rays() {
  if (!impl_->rays) impl_->build_rays();
  if (impl_->rays_stamp != impl_->steps) {
    for (const auto& [body, obj] : impl_->moving_ray_bodies) impl_->rays->set_pose(body, eig(obj->getWorldTransform()));
    impl_->rays->commit();
    impl_->rays_stamp = impl_->steps;
  }
  return *impl_->rays;
}

void Physics::invalidate_rays() { impl_->rays_stamp = ~0ull; }

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
