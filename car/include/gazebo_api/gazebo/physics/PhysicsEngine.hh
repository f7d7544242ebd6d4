// car's Gazebo 11 API (docs/PLUGINS.md): gazebo::physics::PhysicsEngine, what car's world tells of its physics.
#pragma once

#include <string>

#include "gazebo/msgs/msgs.hh"
#include "gazebo/physics/PhysicsTypes.hh"
#include "gazebo/transport/TransportTypes.hh"

namespace car_sim {
class World;
}

namespace gazebo {
namespace physics {

class PhysicsEngine {
 public:
  explicit PhysicsEngine(car_sim::World* _world);
  virtual ~PhysicsEngine();
  // [s] the world's fixed step (<max_step_size>).
  double GetMaxStepSize() const;
  // car's Bullet: "bullet".
  std::string GetType() const;

 private:
  car_sim::World* world;
};

}  // namespace physics
}  // namespace gazebo
