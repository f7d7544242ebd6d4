// Physics's calls (physics.hpp): the Bullet world built with Gazebo's friction rule, robots added and removed
// (bullet_robot.cpp), the step, contacts, and the ray scene mirroring the collision geometry. World models:
// world_models.cpp; the room's map: docs/ARCHITECTURE.md "The physics room".
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
