// The world's models in Bullet: static models as collision objects, dynamic ones as rigid bodies, one per link;
// their state (Gazebo 11's canonical link, nested models) and placing them (set_model_state), and removing them.
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "bodies.hpp"
#include "physics_impl.hpp"

namespace car_sim {
namespace physics {

namespace {

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

}  // namespace physics
}  // namespace car_sim
