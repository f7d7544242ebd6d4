// car's Gazebo 11 API: physics::Base and Entity (names, parents, types) and the World calls on them (BaseByName,
// EntityByName, ResetTime, ResetEntities), after Gazebo 11's gazebo/physics/Base.cc, Entity.cc and World.cc
// (docs/PLUGINS.md "Entities").
#include <boost/pointer_cast.hpp>

#include "car_sim/world.hpp"
#include "gazebo/common/Console.hh"
#include "gazebo/physics/physics.hh"
#include "hub.hpp"

namespace gazebo {
namespace physics {

namespace {

// The world's root element (Gazebo's World::rootElement): a Base named after the world, the models' parent.
class RootBase : public Base {
 public:
  RootBase(const WorldPtr& _world, const std::string& _name) : Base(BasePtr()) {
    name = _name;
    world = _world;
  }
};

bool named(const BasePtr& b, const std::string& n) { return b->GetScopedName() == n || b->GetName() == n; }

// Work that must not run inside a step (it rebuilds the physics or moves time) comes at the step's end when asked
// inside an update event, as World::Reset.
void between_steps(car_sim::World* w, const std::string& world_name, std::function<void()> work) {
  car_gazebo::Hub* h = car_gazebo::Hub::named(world_name);
  if (h && h->in_step)
    w->defer(std::move(work));
  else
    work();
}

}  // namespace

// ---- Base ----------------------------------------------------------------------------------------------------

Base::Base(BasePtr _parent) : parentBase(_parent) {
  if (_parent) world = _parent->world;
}
Base::~Base() = default;

std::string Base::GetName() const { return name; }

std::string Base::GetScopedName(bool _prependWorldName) const {
  // each ancestor but the root element, nearest last
  std::string scoped = name;
  for (BasePtr p = parentBase.lock(); p; p = p->parentBase.lock())
    if (p->parentBase.lock()) scoped = p->name + "::" + scoped;
  WorldPtr w = world.lock();
  return _prependWorldName && w ? w->Name() + "::" + scoped : scoped;
}

BasePtr Base::GetParent() const { return parentBase.lock(); }
WorldPtr Base::GetWorld() const { return world.lock(); }
bool Base::HasType(const EntityType& _t) const { return (type & static_cast<unsigned int>(_t)) == static_cast<unsigned int>(_t); }
unsigned int Base::GetType() const { return type; }
void Base::AddType(EntityType _type) { type |= static_cast<unsigned int>(_type); }

// ---- Entity --------------------------------------------------------------------------------------------------

Entity::Entity(BasePtr _parent) : Base(_parent) { AddType(ENTITY); }
Entity::~Entity() = default;

ModelPtr Entity::GetParentModel() {
  if (HasType(MODEL)) return boost::dynamic_pointer_cast<Model>(shared_from_this());
  // the outermost model above it
  BasePtr p = GetParent();
  while (p && p->GetParent() && p->GetParent()->HasType(MODEL)) p = p->GetParent();
  return boost::dynamic_pointer_cast<Model>(p);
}

// ---- World ---------------------------------------------------------------------------------------------------

BasePtr World::Root() const {
  if (!root) root.reset(new RootBase(boost::const_pointer_cast<World>(shared_from_this()), Name()));
  return root;
}

BasePtr World::BaseByName(const std::string& _name) const {
  if (_name == Name()) return Root();
  for (const ModelPtr& m : Models()) {
    if (named(m, _name)) return m;
    for (const LinkPtr& l : m->GetLinks())
      if (named(l, _name)) return l;
    for (const JointPtr& j : m->GetJoints())
      if (named(j, _name)) return j;
  }
  return BasePtr();
}

EntityPtr World::EntityByName(const std::string& _name) const {
  return boost::dynamic_pointer_cast<Entity>(BaseByName(_name));
}

void World::ResetTime() {
  car_sim::World* w = world;
  between_steps(w, Name(), [w] { w->reset_time(); });
}

void World::ResetEntities(Base::EntityType _type) {
  if (_type != Base::BASE && _type != Base::ENTITY && _type != Base::MODEL) {
    gzerr << "World::ResetEntities(" << static_cast<unsigned int>(_type)
          << "): car resets whole models only (Base::BASE, Base::ENTITY or Base::MODEL); nothing was reset\n";
    return;
  }
  car_sim::World* w = world;
  between_steps(w, Name(), [w] { w->reset_poses(); });
}

}  // namespace physics
}  // namespace gazebo
