// The Bullet world: robots as btMultiBody (reduced coordinates, fixed joints merged), world models as rigid
// bodies and static objects, Gazebo's friction rule, and the diff-drive plug-in's update cycle.
#include "car_sim/world.hpp"

#include <btBulletDynamicsCommon.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointLimitConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

#include "bodies.hpp"
#include "car_sim/raycast.hpp"

#include <fstream>
#include <sstream>

namespace car_sim {

using detail::Body;
using detail::BodyTree;

namespace {

// Collision margin for boxes and cylinders [m]; Bullet keeps the outer size, so this only rounds edges.
constexpr double kMargin = 0.0005;

btVector3 bt(const Eigen::Vector3d& v) { return btVector3(v.x(), v.y(), v.z()); }
Eigen::Vector3d eig(const btVector3& v) { return Eigen::Vector3d(v.x(), v.y(), v.z()); }

btTransform bt(const Eigen::Isometry3d& T) {
  const Eigen::Quaterniond q(T.linear());
  return btTransform(btQuaternion(q.x(), q.y(), q.z(), q.w()), bt(Eigen::Vector3d(T.translation())));
}

Eigen::Isometry3d eig(const btTransform& t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  const btQuaternion q = t.getRotation();
  T.linear() = Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z()).normalized().toRotationMatrix();
  T.translation() = eig(t.getOrigin());
  return T;
}

btQuaternion bt_quat(const Eigen::Matrix3d& R) {
  const Eigen::Quaterniond q(R);
  return btQuaternion(q.x(), q.y(), q.z(), q.w());
}

// Gazebo (ODE) combines two surfaces' friction as the smaller of the two.
btScalar min_friction(const btCollisionObject* a, const btCollisionObject* b) {
  return std::min(a->getFriction(), b->getFriction());
}

btScalar no_restitution(const btCollisionObject*, const btCollisionObject*) { return 0.0; }

bool is_identity(const Eigen::Isometry3d& T) {
  return T.translation().norm() < 1e-12 && (T.linear() - Eigen::Matrix3d::Identity()).norm() < 1e-12;
}

// Gazebo's standard materials as colours (config/gazebo_materials.txt, shared with the Python tools).
const std::map<std::string, Eigen::Vector4d>& gazebo_colours() {
  static const std::map<std::string, Eigen::Vector4d> table = [] {
    std::map<std::string, Eigen::Vector4d> t;
    std::ifstream in(CAR_CONFIG_DIR "/gazebo_materials.txt");
    std::string line;
    while (std::getline(in, line)) {
      line = line.substr(0, line.find('#'));
      std::istringstream ls(line);
      std::string name;
      Eigen::Vector4d c;
      if (ls >> name >> c[0] >> c[1] >> c[2] >> c[3]) t[name] = c;
    }
    return t;
  }();
  return table;
}

// How a URDF link looks: its <gazebo><material> (what Gazebo renders), else its URDF colour, else grey.
SurfaceLook urdf_look(const Link& l) {
  SurfaceLook look;
  look.laser_retro = l.gazebo.laser_retro.value_or(0.0);
  const auto it = gazebo_colours().find(l.gazebo.material);
  if (it != gazebo_colours().end()) {
    look.rgba = it->second;
    return look;
  }
  for (const auto& v : l.visuals)
    if (v.material.has_rgba) {
      look.rgba = v.material.rgba;
      return look;
    }
  return look;
}

// How an SDF link looks: its first visual's script (when known), else <diffuse>, else <ambient>, else grey.
SurfaceLook sdf_look(const WorldLink& l) {
  SurfaceLook look;
  if (l.visuals.empty()) return look;
  const WorldVisual& v = l.visuals.front();
  const auto it = gazebo_colours().find(v.script_name);
  if (it != gazebo_colours().end()) look.rgba = it->second;
  else if (v.material.has_rgba) look.rgba = v.material.rgba;
  else if (v.has_ambient) look.rgba = v.ambient;
  return look;
}

}  // namespace

struct World::Impl {
  // ---- Bullet ----
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btMultiBodyConstraintSolver solver;
  btMultiBodyDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btCollisionObject>> objects;  // static objects and rigid bodies
  std::vector<std::unique_ptr<btMotionState>> motion_states;
  std::vector<std::unique_ptr<btMultiBodyConstraint>> constraints;

  struct DynModel {
    std::string name;
    const WorldModelDesc* desc;
    std::vector<btRigidBody*> bodies;          // one per link (nullptr for links without inertial)
    std::vector<Eigen::Isometry3d> link_to_com;
  };
  std::vector<DynModel> dyn_models;            // dynamic world models
  std::map<std::string, std::vector<btCollisionObject*>> model_objects;  // world model -> its Bullet objects

  struct Drive {
    DiffDriveConfig cfg;
    int left = -1, right = -1;                 // multibody link indices
    double cmd_v = 0.0, cmd_w = 0.0;           // [m/s], [rad/s] last command
    double instr[2] = {0.0, 0.0};              // [m/s] wheel surface speeds being commanded
    EncoderOdometry encoder;
    uint64_t period = 1;                       // [ticks] between updates
    btMultiBodyJointMotor* motor[2] = {nullptr, nullptr};
    double omega[2] = {0.0, 0.0};              // [rad/s] motor velocity targets
    double q_ref[2] = {0.0, 0.0};              // [rad] integrated motor targets, anchored near the joint
  };

  struct Robot {
    RobotInfo info;
    BodyTree tree;
    btMultiBody* mb = nullptr;
    std::unique_ptr<btMultiBody> mb_owner;
    std::vector<std::unique_ptr<btMultiBodyLinkCollider>> colliders;
    std::vector<Drive> drives;
    std::map<std::string, int> joint_link;     // non-fixed joint -> multibody link index
  };
  std::vector<std::unique_ptr<Robot>> robots;
  std::vector<OdometrySample> odom_out;

  // ---- sensors ----
  struct SensorRt {
    SensorInfo info;
    std::unique_ptr<Sensor> sensor;
    Eigen::Isometry3d link_to_sensor = Eigen::Isometry3d::Identity();
    double period = 0.0;      // [s], 0 = every step
    double next_time = 0.0;   // [s] of the next measurement
    bool active = false;
    std::mt19937_64 rng;
    Eigen::Isometry3d history[3];
    int history_count = 0;
  };
  std::vector<SensorRt> sensors;
  SensorOutputs sensor_out;
  std::unique_ptr<RayScene> rays;
  std::set<std::pair<std::string, std::string>> active;  // (robot, plug-in) that someone listens to
  std::vector<std::pair<int, const btCollisionObject*>> moving_ray_bodies;  // ray body -> its Bullet object
  std::vector<std::string> object_names;      // btCollisionObject user index -> "model/link"

  void name_object(btCollisionObject* o, const std::string& name) {
    o->setUserIndex(static_cast<int>(object_names.size()));
    object_names.push_back(name);
  }

  Impl(const WorldDescription& d, const WorldOptions& o) {
    world.setGravity(bt(d.gravity));
    btContactSolverInfo& si = world.getSolverInfo();
    si.m_numIterations = o.solver_iterations;
    // stop iterating once the solution has converged
    si.m_leastSquaresResidualThreshold = o.residual_threshold;
    // two friction directions per contact (ODE's friction pyramid, as Gazebo) instead of Bullet's cone
    si.m_solverMode |= SOLVER_DISABLE_IMPLICIT_CONE_FRICTION;
    // carry the whole previous impulse over, so a resting solution keeps converging from step to step
    si.m_warmstartingFactor = 1.0;
    gCalculateCombinedFrictionCallback = &min_friction;
    gCalculateCombinedRestitutionCallback = &no_restitution;
  }

  ~Impl() {
    for (auto& r : robots) {
      for (auto& c : r->colliders) world.removeCollisionObject(c.get());
      world.removeMultiBody(r->mb);
    }
    for (auto& c : constraints) world.removeMultiBodyConstraint(c.get());
    for (auto& o : objects) {
      if (auto* rb = btRigidBody::upcast(o.get()))
        world.removeRigidBody(rb);
      else
        world.removeCollisionObject(o.get());
    }
  }

  btCollisionShape* own(btCollisionShape* s) {
    shapes.emplace_back(s);
    return s;
  }

  // A Bullet shape for a primitive; nullptr for what Bullet cannot collide here (meshes for now).
  btCollisionShape* make_shape(const Shape& s) {
    switch (s.type) {
      case ShapeType::Box: {
        auto* b = new btBoxShape(bt(Eigen::Vector3d(s.size / 2.0)));
        b->setMargin(kMargin);
        return own(b);
      }
      case ShapeType::Cylinder: {
        auto* c = new btCylinderShapeZ(btVector3(s.radius, s.radius, s.length / 2.0));
        c->setMargin(kMargin);
        return own(c);
      }
      case ShapeType::Sphere:
        return own(new btSphereShape(s.radius));
      default:
        return nullptr;
    }
  }

  // One shape, or a compound of several, placed relative to a frame (com for moving bodies).
  btCollisionShape* make_body_shape(const std::vector<std::pair<Shape, Eigen::Isometry3d>>& parts) {
    std::vector<std::pair<btCollisionShape*, Eigen::Isometry3d>> made;
    for (const auto& p : parts)
      if (btCollisionShape* s = make_shape(p.first)) made.emplace_back(s, p.second);
    if (made.empty()) return nullptr;
    if (made.size() == 1 && is_identity(made[0].second)) return made[0].first;
    auto* compound = new btCompoundShape(true, static_cast<int>(made.size()));
    for (const auto& m : made) compound->addChildShape(bt(m.second), m.first);
    return own(compound);
  }

  void add_world_model(const WorldModelDesc& m) {
    if (m.is_static) {
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
            shape = make_shape(c.shape);
          }
          if (!shape) continue;
          auto* obj = new btCollisionObject();
          obj->setCollisionShape(shape);
          obj->setWorldTransform(bt(T));
          obj->setFriction(c.friction.mu);
          obj->setRestitution(0.0);
          objects.emplace_back(obj);
          name_object(obj, m.name + "/" + l.name);
          model_objects[m.name].push_back(obj);
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
      const Eigen::Matrix3d R = detail::principal_axes(in.inertia, &principal);
      Eigen::Isometry3d link_to_com = in.origin;
      link_to_com.linear() = in.origin.linear() * R;
      std::vector<std::pair<Shape, Eigen::Isometry3d>> parts;
      double mu = 1.0;
      for (const auto& c : l.collisions) {
        parts.emplace_back(c.shape, link_to_com.inverse() * c.shape.origin);
        mu = c.friction.mu;
      }
      btCollisionShape* shape = make_body_shape(parts);
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

  // A wheel: one cylinder spinning about its own axis. It collides as a sphere of the wheel radius, so it
  // touches the ground at one point under its centre, the way an ideal rolling wheel does.
  static bool is_wheel(const Body& b) {
    if (!b.joint || b.shapes.size() != 1 || b.shapes[0].shape.type != ShapeType::Cylinder) return false;
    if (b.joint->type != JointType::Continuous && b.joint->type != JointType::Revolute) return false;
    const Eigen::Vector3d cyl_axis = b.shapes[0].in_top.linear() * Eigen::Vector3d::UnitZ();
    return std::abs(cyl_axis.dot(b.joint->axis)) > 0.99;
  }

  // A ball caster: one sphere centred on an undriven continuous joint. URDF cannot say "rolls in every
  // direction", so models write a continuous joint (the seed's casters even with axis 1 1 1, one diagonal
  // axis to a physics engine). car simulates the intended part: the sphere carries load and rolls freely in
  // every direction, i.e. its contact has no friction.
  static bool is_ball_caster(const Body& b, const std::set<std::string>& driven) {
    if (!b.joint || b.joint->type != JointType::Continuous || driven.count(b.joint->name)) return false;
    if (b.shapes.size() != 1 || b.shapes[0].shape.type != ShapeType::Sphere) return false;
    return b.shapes[0].in_top.translation().norm() < 1e-9;
  }

  void add_robot(std::unique_ptr<Robot> r, double dt) {
    Robot& R = *r;
    const int n_links = static_cast<int>(R.tree.bodies.size()) - 1;
    const Body& base = R.tree.bodies[0];
    R.mb_owner = std::make_unique<btMultiBody>(n_links, base.mass, bt(base.principal), false, false);
    R.mb = R.mb_owner.get();
    btMultiBody* mb = R.mb;
    mb->setBaseWorldTransform(bt(R.info.spawn_pose * base.top_to_com));
    mb->setLinearDamping(0.0);
    mb->setAngularDamping(0.0);
    mb->setUseGyroTerm(true);
    mb->setHasSelfCollision(false);
    mb->setMaxCoordinateVelocity(1000.0);
    for (int i = 1; i <= n_links; ++i) {
      const Body& b = R.tree.bodies[i];
      const Body& p = R.tree.bodies[b.parent];
      const Joint& j = *b.joint;
      // child link frame at zero joint position, in the parent body's top frame
      const Eigen::Isometry3d top_to_child = R.tree.link_in_top.at(j.parent) * j.origin;
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
      mb->getLink(i - 1).m_jointDamping = j.damping;
      mb->getLink(i - 1).m_jointFriction = j.friction;
      R.joint_link[j.name] = i - 1;
    }
    mb->finalizeMultiDof();
    world.addMultiBody(mb);

    // Colliders, one per body with shapes.
    std::set<std::string> driven;
    for (const auto& cfg : R.info.drives) driven.insert({cfg.left_joint, cfg.right_joint});
    for (int i = 0; i <= n_links; ++i) {
      const Body& b = R.tree.bodies[i];
      std::vector<std::pair<Shape, Eigen::Isometry3d>> parts;
      double mu = 1.0;
      if (is_wheel(b)) {
        Shape sphere;
        sphere.type = ShapeType::Sphere;
        sphere.radius = b.shapes[0].shape.radius;
        Eigen::Isometry3d at = Eigen::Isometry3d::Identity();
        at.translation() = b.shapes[0].in_top.translation();
        parts.emplace_back(sphere, b.top_to_com.inverse() * at);
        mu = b.shapes[0].mu;
      } else {
        for (const auto& s : b.shapes) {
          if (s.shape.type == ShapeType::Plane) continue;
          parts.emplace_back(s.shape, b.top_to_com.inverse() * s.in_top);
          mu = s.mu;
        }
      }
      if (is_ball_caster(b, driven)) mu = 0.0;
      btCollisionShape* shape = make_body_shape(parts);
      if (!shape) continue;
      auto col = std::make_unique<btMultiBodyLinkCollider>(mb, i - 1);
      col->setCollisionShape(shape);
      col->setFriction(mu);
      col->setRestitution(0.0);
      name_object(col.get(), R.info.name + "/" + b.top);
      world.addCollisionObject(col.get(), btBroadphaseProxy::DefaultFilter, btBroadphaseProxy::AllFilter);
      if (i == 0)
        mb->setBaseCollider(col.get());
      else
        mb->getLink(i - 1).m_collider = col.get();
      R.colliders.push_back(std::move(col));
    }
    for (const auto& j : R.info.model.joints) {
      if (j.type != JointType::Revolute || !j.limits || j.limits->lower >= j.limits->upper) continue;
      auto* c = new btMultiBodyJointLimitConstraint(mb, R.joint_link.at(j.name), j.limits->lower, j.limits->upper);
      constraints.emplace_back(c);
      world.addMultiBodyConstraint(c);
    }
    btAlignedObjectArray<btQuaternion> q;
    btAlignedObjectArray<btVector3> v;
    mb->updateCollisionObjectWorldTransforms(q, v);

    // Diff drives: velocity motors on the wheel joints, capped at wheelTorque.
    for (const auto& cfg : R.info.drives) {
      Drive d;
      d.cfg = cfg;
      d.left = R.joint_link.at(cfg.left_joint);
      d.right = R.joint_link.at(cfg.right_joint);
      d.period = cfg.update_rate > 0 ? std::max<uint64_t>(1, std::llround(1.0 / (cfg.update_rate * dt))) : 1;
      for (int side = 0; side < 2; ++side) {
        auto* m = new btMultiBodyJointMotor(mb, side == 0 ? d.left : d.right, 0, 0.0, cfg.wheel_torque * dt);
        constraints.emplace_back(m);
        world.addMultiBodyConstraint(m);
        d.motor[side] = m;
      }
      R.drives.push_back(d);
    }
    robots.push_back(std::move(r));
  }

  // The ray scene mirrors the collision geometry: static shapes at their world poses, every moving body (world
  // rigid bodies, robot bodies split per link for their colours) as an instance in its Bullet com frame.
  // Robot wheels are seen as the cylinders they are, not the spheres they roll on.
  void build_rays(const WorldDescription& desc) {
    rays = std::make_unique<RayScene>();
    moving_ray_bodies.clear();
    for (const auto& m : desc.models) {
      if (!m.is_static) continue;
      for (const auto& l : m.links) {
        std::vector<std::pair<Shape, Eigen::Isometry3d>> shapes;
        for (const auto& c : l.collisions) shapes.emplace_back(c.shape, m.pose * l.pose * c.shape.origin);
        if (!shapes.empty()) rays->add_body(shapes, sdf_look(l));
      }
    }
    for (const auto& dm : dyn_models) {
      for (size_t i = 0; i < dm.bodies.size(); ++i) {
        const WorldLink& l = dm.desc->links[i];
        std::vector<std::pair<Shape, Eigen::Isometry3d>> shapes;
        for (const auto& c : l.collisions) shapes.emplace_back(c.shape, dm.link_to_com[i].inverse() * c.shape.origin);
        if (shapes.empty()) continue;
        moving_ray_bodies.emplace_back(rays->add_body(shapes, sdf_look(l)), dm.bodies[i]);
      }
    }
    for (auto& r : robots) {
      for (size_t b = 0; b < r->tree.bodies.size(); ++b) {
        const Body& body = r->tree.bodies[b];
        const btCollisionObject* col = b == 0 ? r->mb->getBaseCollider() : r->mb->getLink(static_cast<int>(b) - 1).m_collider;
        if (!col) continue;
        for (const auto& name : body.links) {
          const Link* l = r->info.model.find_link(name);
          std::vector<std::pair<Shape, Eigen::Isometry3d>> shapes;
          for (const auto& c : l->collisions)
            shapes.emplace_back(c, body.top_to_com.inverse() * r->tree.link_in_top.at(name) * c.origin);
          if (shapes.empty()) continue;
          moving_ray_bodies.emplace_back(rays->add_body(shapes, urdf_look(*l)), col);
        }
      }
    }
  }

  void update_rays() {
    for (const auto& [body, obj] : moving_ray_bodies) rays->set_pose(body, eig(obj->getWorldTransform()));
    rays->commit();
  }

  Robot* find_robot(const std::string& name) {
    for (auto& r : robots)
      if (r->info.name == name) return r.get();
    return nullptr;
  }

  // Pose of a body's com frame in the world.
  Eigen::Isometry3d body_com_pose(Robot& R, int body) {
    if (body == 0) return eig(R.mb->getBaseWorldTransform());
    btAlignedObjectArray<btQuaternion> q;
    btAlignedObjectArray<btVector3> v;
    R.mb->forwardKinematics(q, v);
    return eig(R.mb->getLink(body - 1).m_cachedWorldTransform);
  }

  Eigen::Isometry3d root_pose(Robot& R) {
    return eig(R.mb->getBaseWorldTransform()) * R.tree.bodies[0].top_to_com.inverse();
  }

  ModelState robot_state(Robot& R) {
    ModelState s;
    s.pose = root_pose(R);
    s.angular = eig(R.mb->getBaseOmega());
    const Eigen::Vector3d com = eig(R.mb->getBasePos());
    // velocity of the root frame's origin
    s.linear = eig(R.mb->getBaseVel()) + s.angular.cross(s.pose.translation() - com);
    return s;
  }

  JointState joint_state(Robot& R, const std::string& joint) {
    const int i = R.joint_link.at(joint);
    return {joint, R.mb->getJointPos(i), R.mb->getJointVel(i)};
  }

  // The plug-in's update: odometry out, then new motor targets.
  void update_drive(Robot& R, size_t k, uint64_t tick, double dt) {
    Drive& d = R.drives[k];
    const double r = d.cfg.wheel_diameter / 2.0;
    if (d.cfg.publish_tf) {
      OdometrySample o;
      o.model = R.info.name;
      o.drive = k;
      o.tick = tick;
      o.left = joint_state(R, d.cfg.left_joint);
      o.right = joint_state(R, d.cfg.right_joint);
      if (d.cfg.encoder_odometry) {
        o.pose.translation() = Eigen::Vector3d(d.encoder.x, d.encoder.y, 0.0);
        o.pose.linear() = Eigen::AngleAxisd(d.encoder.theta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
        o.linear = Eigen::Vector3d(d.encoder.v, 0.0, 0.0);
        o.angular = Eigen::Vector3d(0.0, 0.0, d.encoder.w);
      } else {
        const ModelState s = robot_state(R);
        o.pose = s.pose;
        // twist in the base frame, by yaw, as the plug-in does
        const Eigen::Matrix3d Rm = s.pose.linear();
        const double yaw = std::atan2(Rm(1, 0), Rm(0, 0));
        o.linear = Eigen::Vector3d(std::cos(yaw) * s.linear.x() + std::sin(yaw) * s.linear.y(),
                                   std::cos(yaw) * s.linear.y() - std::sin(yaw) * s.linear.x(), 0.0);
        o.angular = Eigen::Vector3d(0.0, 0.0, s.angular.z());
      }
      odom_out.push_back(o);
    }
    double target[2];
    wheel_speeds(d.cmd_v, d.cmd_w, d.cfg.wheel_separation, &target[0], &target[1]);
    const double max_step = d.cfg.wheel_acceleration * static_cast<double>(d.period) * dt;
    for (int side = 0; side < 2; ++side) {
      d.instr[side] = rate_limit(d.instr[side], target[side], max_step);
      d.omega[side] = d.instr[side] / r;
      d.motor[side]->setVelocityTarget(d.omega[side], 1.0);
    }
  }

  // The wheel motors are velocity motors (as Gazebo's) that also pull gently toward the angle their target
  // speed integrates to. An iterative solver leaves a small velocity error each step; without this anchor it
  // would add up to a creep of about 0.3 mm per 10 s at rest. The anchor stays within kAnchorWindow of the
  // actual angle, so a wheel that slips or is blocked never winds up.
  void anchor_motors(Robot& R, double dt) {
    constexpr double kAnchorWindow = 0.02;  // [rad]
    constexpr double kAnchorGain = 0.05;    // [-] fraction of the angle error corrected per step
    for (auto& d : R.drives) {
      for (int side = 0; side < 2; ++side) {
        const int link = side == 0 ? d.left : d.right;
        const double q = R.mb->getJointPos(link);
        d.q_ref[side] = std::clamp(d.q_ref[side] + d.omega[side] * dt, q - kAnchorWindow, q + kAnchorWindow);
        d.motor[side]->setPositionTarget(d.q_ref[side], kAnchorGain);
      }
    }
  }
};

// ---- World -----------------------------------------------------------------------------------------------

World::World(WorldDescription desc, WorldOptions options) : desc_(std::move(desc)), options_(options) {
  impl_ = std::make_unique<Impl>(desc_, options_);
  for (const auto& m : desc_.models) impl_->add_world_model(m);
}

World::~World() = default;

void World::spawn(const RobotModel& model, const std::string& name, const Eigen::Isometry3d& pose,
                  const std::string& robot_namespace) {
  if (name.empty()) throw std::invalid_argument("a model needs a name");
  if (has_model(name)) throw std::invalid_argument("model '" + name + "' exists already");
  auto r = std::make_unique<Impl::Robot>();
  r->info.name = name;
  r->info.robot_namespace = robot_namespace;
  r->info.model = model;
  if (!robot_namespace.empty()) {
    // gazebo_ros's spawn: the namespace given at spawn replaces every plug-in's <robotNamespace>
    auto set_ns = [&](PluginSpec& p) {
      bool found = false;
      for (auto& kv : p.params)
        if (kv.first == "robotNamespace") kv.second = robot_namespace, found = true;
      if (!found) p.params.emplace_back("robotNamespace", robot_namespace);
    };
    for (auto& p : r->info.model.plugins) set_ns(p);
    for (auto& s : r->info.model.sensors)
      for (auto& p : s.plugins) set_ns(p);
  }
  r->info.config = resolve_plugins(r->info.model);
  for (const auto& pc : r->info.config.plugins)
    if (pc.kind == "diff_drive") r->info.drives.push_back(DiffDriveConfig::from(pc, name));
  r->info.spawn_pose = pose;
  r->tree = detail::build_bodies(r->info.model);
  const RobotInfo& info = r->info;
  std::vector<Impl::SensorRt> new_sensors;
  for (const auto& pc : info.config.plugins) {
    if (pc.kind == "diff_drive") continue;
    Impl::SensorRt s;
    s.info.robot = name;
    s.info.config = pc;
    s.info.link = pc.link;
    s.sensor = make_sensor(pc, name);
    if (!s.sensor) continue;
    for (const auto& spec : info.model.sensors)
      if (spec.name == pc.sensor && spec.link == pc.link) s.link_to_sensor = spec.pose;
    const double rate = pc.sensor.empty() ? pc.number("updateRate") : pc.number("update_rate");
    s.info.rate = rate;
    s.period = rate > 0 ? 1.0 / rate : 0.0;
    s.next_time = time() + s.period;
    s.rng = sensor_rng(options_.seed, name, pc.sensor.empty() ? pc.name : pc.sensor);
    s.active = impl_->active.count({name, pc.name}) > 0;
    new_sensors.push_back(std::move(s));
  }
  impl_->add_robot(std::move(r), desc_.step_size);
  for (auto& s : new_sensors) impl_->sensors.push_back(std::move(s));
  impl_->rays.reset();
}

void World::remove(const std::string& name) {
  auto& robots = impl_->robots;
  for (auto it = robots.begin(); it != robots.end(); ++it) {
    if ((*it)->info.name != name) continue;
    Impl::Robot& R = **it;
    for (auto& c : R.colliders) impl_->world.removeCollisionObject(c.get());
    // motors and limits of this multibody
    auto& cs = impl_->constraints;
    for (auto ci = cs.begin(); ci != cs.end();) {
      if ((*ci)->getMultiBodyA() == R.mb) {
        impl_->world.removeMultiBodyConstraint(ci->get());
        ci = cs.erase(ci);
      } else {
        ++ci;
      }
    }
    impl_->world.removeMultiBody(R.mb);
    auto& ss = impl_->sensors;
    ss.erase(std::remove_if(ss.begin(), ss.end(), [&](const Impl::SensorRt& x) { return x.info.robot == name; }),
             ss.end());
    robots.erase(it);
    impl_->rays.reset();
    return;
  }
  if (!desc_.find_model(name)) throw std::invalid_argument("no model named '" + name + "'");
  for (btCollisionObject* o : impl_->model_objects[name]) {
    if (auto* rb = btRigidBody::upcast(o))
      impl_->world.removeRigidBody(rb);
    else
      impl_->world.removeCollisionObject(o);
    auto& objs = impl_->objects;
    objs.erase(std::remove_if(objs.begin(), objs.end(), [o](const auto& p) { return p.get() == o; }), objs.end());
  }
  impl_->model_objects.erase(name);
  impl_->rays.reset();
  auto& dms = impl_->dyn_models;
  dms.erase(std::remove_if(dms.begin(), dms.end(), [&](const Impl::DynModel& x) { return x.name == name; }), dms.end());
  // A world model leaves the description too, so a reset does not bring it back (as in Gazebo).
  for (auto& dm : dms) dm.desc = nullptr;
  auto& ms = desc_.models;
  ms.erase(std::remove_if(ms.begin(), ms.end(), [&](const WorldModelDesc& x) { return x.name == name; }), ms.end());
  for (auto& dm : dms) dm.desc = desc_.find_model(dm.name);
}

void World::step(uint64_t n) {
  const double dt = desc_.step_size;
  for (uint64_t s = 0; s < n; ++s) {
    for (auto& r : impl_->robots) impl_->anchor_motors(*r, dt);
    // physics: one fixed step, no internal substepping
    impl_->world.stepSimulation(dt, 0, dt);
    ++tick_;
    for (auto& r : impl_->robots) {
      for (size_t k = 0; k < r->drives.size(); ++k) {
        Impl::Drive& d = r->drives[k];
        if (d.cfg.encoder_odometry) {
          const double rad = d.cfg.wheel_diameter / 2.0;
          d.encoder.integrate(r->mb->getJointVel(d.left) * rad * dt, r->mb->getJointVel(d.right) * rad * dt,
                              d.cfg.wheel_separation, dt);
        }
        if (tick_ % d.period == 0) impl_->update_drive(*r, k, tick_, dt);
      }
    }
    update_sensors();
  }
}

void World::update_sensors() {
  const double t = time();
  bool rays_fresh = false;
  for (auto& s : impl_->sensors) {
    const bool history = s.sensor->needs_history();
    if (history && s.active) {
      // the sensor frame's last three poses, for finite differences
      s.history[0] = s.history[1];
      s.history[1] = s.history[2];
      s.history[2] = link_pose(s.info.robot, s.info.link) * s.link_to_sensor;
      s.history_count = std::min(3, s.history_count + 1);
    }
    const bool due = s.period <= 0.0 || t + 1e-9 >= s.next_time;
    if (!due) continue;
    if (s.period > 0.0) {
      s.next_time += s.period;
      if (s.next_time <= t) s.next_time = t + s.period;  // after a pause in activity, no burst
    }
    if (!s.active || (history && s.history_count < 3)) continue;
    SensorInput in;
    in.tick = tick_;
    in.dt = desc_.step_size;
    in.pose = link_pose(s.info.robot, s.info.link) * s.link_to_sensor;
    in.gravity = desc_.gravity;
    in.sun_direction = desc_.sun_direction;
    in.ambient = desc_.ambient;
    in.background = desc_.background;
    in.history = s.history;
    if (s.sensor->needs_rays()) {
      if (!impl_->rays) impl_->build_rays(desc_);
      if (!rays_fresh) impl_->update_rays();
      rays_fresh = true;
      in.scene = impl_->rays.get();
    }
    s.sensor->update(in, s.rng, &impl_->sensor_out);
  }
}

std::vector<SensorInfo> World::sensors() const {
  std::vector<SensorInfo> out;
  for (const auto& s : impl_->sensors) out.push_back(s.info);
  return out;
}

void World::set_sensor_active(const std::string& robot, const std::string& plugin, bool active) {
  bool found = false;
  for (auto& s : impl_->sensors) {
    if (s.info.robot != robot || s.info.config.name != plugin) continue;
    found = true;
    if (active && !s.active) s.history_count = 0;
    s.active = active;
  }
  if (!found) throw std::invalid_argument("robot '" + robot + "' has no sensor plug-in '" + plugin + "'");
  if (active)
    impl_->active.insert({robot, plugin});
  else
    impl_->active.erase({robot, plugin});
}

SensorOutputs World::take_sensor_outputs() {
  SensorOutputs out;
  std::swap(out, impl_->sensor_out);
  return out;
}

void World::reset() {
  // time first: the sensors' schedules restart from it
  tick_ = 0;
  reset_poses();
}

void World::reset_poses() {
  std::vector<RobotInfo> infos;
  for (auto& r : impl_->robots) infos.push_back(r->info);
  const auto active = impl_->active;
  impl_ = std::make_unique<Impl>(desc_, options_);
  impl_->active = active;
  for (const auto& m : desc_.models) impl_->add_world_model(m);
  for (const auto& info : infos) spawn(info.model, info.name, info.spawn_pose, info.robot_namespace);
  impl_->odom_out.clear();
}

std::vector<std::string> World::model_names() const {
  std::vector<std::string> out;
  for (const auto& m : desc_.models) out.push_back(m.name);
  for (const auto& r : impl_->robots) out.push_back(r->info.name);
  return out;
}

bool World::has_model(const std::string& name) const {
  return desc_.find_model(name) != nullptr || impl_->find_robot(name) != nullptr;
}

std::vector<std::string> World::robot_names() const {
  std::vector<std::string> out;
  for (const auto& r : impl_->robots) out.push_back(r->info.name);
  return out;
}

const RobotInfo& World::robot(const std::string& name) const {
  auto* r = impl_->find_robot(name);
  if (!r) throw std::invalid_argument("no robot named '" + name + "'");
  return r->info;
}

ModelState World::model_state(const std::string& name) const {
  if (auto* r = impl_->find_robot(name)) return impl_->robot_state(*r);
  for (const auto& dm : impl_->dyn_models) {
    if (dm.name != name) continue;
    ModelState s;
    const btRigidBody* rb = dm.bodies[0];
    const Eigen::Isometry3d com = eig(rb->getWorldTransform());
    // model frame from the canonical (first) link
    s.pose = com * dm.link_to_com[0].inverse() * dm.desc->links[0].pose.inverse();
    s.angular = eig(rb->getAngularVelocity());
    s.linear = eig(rb->getLinearVelocity()) + s.angular.cross(s.pose.translation() - com.translation());
    return s;
  }
  if (const auto* m = desc_.find_model(name)) {
    ModelState s;
    s.pose = m->pose;
    return s;
  }
  throw std::invalid_argument("no model named '" + name + "'");
}

void World::set_model_state(const std::string& name, const ModelState& st) {
  if (auto* r = impl_->find_robot(name)) {
    btMultiBody* mb = r->mb;
    const Eigen::Isometry3d com = st.pose * r->tree.bodies[0].top_to_com;
    mb->setBaseWorldTransform(bt(com));
    mb->setBaseOmega(bt(st.angular));
    mb->setBaseVel(bt(Eigen::Vector3d(st.linear + st.angular.cross(com.translation() - st.pose.translation()))));
    btAlignedObjectArray<btQuaternion> q;
    btAlignedObjectArray<btVector3> v;
    mb->updateCollisionObjectWorldTransforms(q, v);
    return;
  }
  for (auto& dm : impl_->dyn_models) {
    if (dm.name != name) continue;
    for (size_t i = 0; i < dm.bodies.size(); ++i) {
      const Eigen::Isometry3d com = st.pose * dm.desc->links[i].pose * dm.link_to_com[i];
      dm.bodies[i]->setWorldTransform(bt(com));
      dm.bodies[i]->getMotionState()->setWorldTransform(bt(com));
      dm.bodies[i]->setAngularVelocity(bt(st.angular));
      dm.bodies[i]->setLinearVelocity(bt(Eigen::Vector3d(st.linear + st.angular.cross(com.translation() -
                                                                                       st.pose.translation()))));
    }
    return;
  }
  if (desc_.find_model(name)) throw std::invalid_argument("model '" + name + "' is static");
  throw std::invalid_argument("no model named '" + name + "'");
}

std::vector<JointState> World::joint_states(const std::string& robot) const {
  auto* r = impl_->find_robot(robot);
  if (!r) throw std::invalid_argument("no robot named '" + robot + "'");
  std::vector<JointState> out;
  for (const auto& j : r->info.model.joints)
    if (j.type != JointType::Fixed) out.push_back(impl_->joint_state(*r, j.name));
  return out;
}

Eigen::Isometry3d World::link_pose(const std::string& robot, const std::string& link) const {
  auto* r = impl_->find_robot(robot);
  if (!r) throw std::invalid_argument("no robot named '" + robot + "'");
  const auto it = r->tree.body_of_link.find(link);
  if (it == r->tree.body_of_link.end()) throw std::invalid_argument("robot '" + robot + "' has no link '" + link + "'");
  const Body& b = r->tree.bodies[it->second];
  return impl_->body_com_pose(*r, it->second) * b.top_to_com.inverse() * r->tree.link_in_top.at(link);
}

void World::set_cmd_vel(const std::string& robot, double v, double w) {
  if (!std::isfinite(v) || !std::isfinite(w)) throw std::invalid_argument("cmd_vel must be finite");
  auto* r = impl_->find_robot(robot);
  if (!r) throw std::invalid_argument("no robot named '" + robot + "'");
  for (auto& d : r->drives) {
    d.cmd_v = v;
    d.cmd_w = w;
  }
}

std::vector<Contact> World::contacts() const {
  std::vector<Contact> out;
  btDispatcher* d = impl_->world.getDispatcher();
  auto name = [&](const btCollisionObject* o) {
    const int i = o->getUserIndex();
    return i >= 0 && i < static_cast<int>(impl_->object_names.size()) ? impl_->object_names[i] : std::string("?");
  };
  for (int i = 0; i < d->getNumManifolds(); ++i) {
    const btPersistentManifold* m = d->getManifoldByIndexInternal(i);
    for (int k = 0; k < m->getNumContacts(); ++k) {
      const btManifoldPoint& p = m->getContactPoint(k);
      if (p.getAppliedImpulse() <= 0.0) continue;
      out.push_back({name(m->getBody0()), name(m->getBody1()), eig(p.getPositionWorldOnB()),
                     p.getAppliedImpulse() / desc_.step_size});
    }
  }
  return out;
}

std::vector<OdometrySample> World::take_odometry() {
  std::vector<OdometrySample> out;
  out.swap(impl_->odom_out);
  return out;
}

}  // namespace car_sim
