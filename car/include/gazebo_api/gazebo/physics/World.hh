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

#include "gazebo/common/Time.hh"
#include "gazebo/physics/PhysicsTypes.hh"

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
  unsigned int ModelCount() const;
  ignition::math::Vector3d Gravity() const;
  void SetGravity(const ignition::math::Vector3d& _gravity);
  PhysicsEnginePtr Physics() const;
  bool PhysicsEnabled() const;
  // Off: a step advances sim time and raises the events; nothing moves.
  void SetPhysicsEnabled(const bool _enable);

  // car: the core world, and whether a step's WorldUpdateBegin is running (SimTime counts the coming step).
  car_sim::World* Core() const { return world; }
  void SetInStep(bool _in) { inStep = _in; }
  // car: the models whose joint controller exists, updated each step after WorldUpdateBegin.
  void AddControlled(const ModelPtr& _model);
  void UpdateControllers();

 private:
  car_sim::World* world;
  bool inStep = false;
  mutable std::map<std::string, ModelPtr> models;
  PhysicsEnginePtr physics;
  std::vector<boost::weak_ptr<Model>> controlled;
};

}  // namespace physics
}  // namespace gazebo
