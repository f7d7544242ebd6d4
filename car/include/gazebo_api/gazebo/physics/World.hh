// car's Gazebo 11 API (docs/PLUGINS.md): gazebo::physics::World, a handle on car's world (car_sim::World).
#pragma once

#include <boost/enable_shared_from_this.hpp>
#include <cstdint>
#include <ignition/math/Vector3.hh>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <boost/weak_ptr.hpp>
#include <sdf/sdf.hh>

#include "gazebo/common/CommonTypes.hh"
#include "gazebo/common/Event.hh"
#include "gazebo/common/Time.hh"
#include "gazebo/msgs/msgs.hh"
#include "gazebo/physics/Base.hh"
#include "gazebo/physics/PhysicsTypes.hh"
#include "gazebo/transport/TransportTypes.hh"

namespace car_sim {
class World;
}

namespace gazebo {
namespace physics {

class World : public boost::enable_shared_from_this<World> {
 public:
  // car: made by car_gazebo, one per car world.
  explicit World(car_sim::World* _world);
  virtual ~World();

  std::string Name() const;
  // The sim time: the step's end inside WorldUpdateBegin and BeforePhysicsUpdate (as Gazebo counts it), else the
  // time reached.
  common::Time SimTime() const;
  uint64_t Iterations() const;
  ModelPtr ModelByName(const std::string& _name) const;
  Model_V Models() const;
  // The first of the world's models, their links and joints (in that order, model by model) whose scoped name
  // ("MODEL", "MODEL::LINK", "MODEL::JOINT") or plain name is _name, as Gazebo's Base::GetByName from the root; the
  // world's own name gives the root element. Null when none.
  BasePtr BaseByName(const std::string& _name) const;
  // BaseByName as an Entity: a model or a link; null for a joint (a Base, not an Entity, in Gazebo 11) or none.
  EntityPtr EntityByName(const std::string& _name) const;
  unsigned int ModelCount() const;
  ignition::math::Vector3d Gravity() const;
  void SetGravity(const ignition::math::Vector3d& _gravity);
  PhysicsEnginePtr Physics() const;
  bool PhysicsEnabled() const;
  // Off: a step advances sim time and raises the events; nothing moves.
  void SetPhysicsEnabled(const bool _enable);

  // car's pause flag (the one /gazebo/pause_physics sets): SetPaused raises event::Events::pause when it changes.
  bool IsPaused() const;
  void SetPaused(bool _p);
  // reset_simulation: time to 0, every model back, the models' and world's plug-ins' Reset (Gazebo's World::Reset,
  // which pauses for it: the pause event fires twice when the world was running). Called inside an update event,
  // it is done at the end of that step.
  void Reset();
  // Sim time and the iteration count to 0; the models' state, the plug-ins' and the pause flag are kept (Gazebo's
  // World::ResetTime). car's own plug-ins restart their update schedules from 0, as Gazebo's sensors do on the
  // time-reset event. Called inside an update event, it is done at the end of that step.
  void ResetTime();
  // Every model back to its pose at load, at rest, its plug-ins' Reset called; time goes on (reset_world: Gazebo's
  // ResetEntities(Base::MODEL)). car resets whole models: BASE, ENTITY and MODEL do that; another type is an error
  // (gzerr) and nothing is reset. Called inside an update event, it is done at the end of that step.
  void ResetEntities(Base::EntityType _type = Base::BASE);
  // Model insertion (Gazebo's factory): the model appears at the end of the next step (car's pacer also inserts
  // while paused), its plug-ins loaded then; a name taken gets _0, _1, ... (docs/PLUGINS.md "Inserting models").
  // A file: model://NAME through car's model path (GAZEBO_MODEL_PATH, then car's models/), or a path.
  void InsertModelFile(const std::string& _sdfFilename);
  // An SDF document holding a <model> (or a <world> with one).
  void InsertModelString(const std::string& _sdfString);
  void InsertModelSDF(const sdf::SDF& _sdf);

  // car: the core world, and whether a step's WorldUpdateBegin is running (SimTime counts the coming step).
  car_sim::World* Core() const { return world; }
  void SetInStep(bool _in) { inStep = _in; }
  // car: the models whose joint controller exists, updated each step after WorldUpdateBegin.
  void AddControlled(const ModelPtr& _model);
  void UpdateControllers();

 private:
  friend class Model;
  car_sim::World* world;
  // the root element: the models' parent, named after the world (made on first use)
  BasePtr Root() const;
  mutable BasePtr root;
  bool inStep = false;
  mutable std::map<std::string, ModelPtr> models;
  PhysicsEnginePtr physics;
  std::vector<boost::weak_ptr<Model>> controlled;
};

}  // namespace physics
}  // namespace gazebo
