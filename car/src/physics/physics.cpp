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
#include "bullet_robot.hpp"
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

}  // namespace physics
}  // namespace car_sim
