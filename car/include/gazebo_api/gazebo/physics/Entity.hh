// car's Gazebo 11 API (docs/PLUGINS.md): gazebo::physics::Entity (Gazebo 11's gazebo/physics/Entity.hh), what a Model
// and a Link share: poses, velocities and the model they belong to. boost::dynamic_pointer_cast<physics::Link> or
// <physics::Model> on an EntityPtr (World::EntityByName's) gives the handle or null.
#pragma once

#include <ignition/math/Pose3.hh>
#include <ignition/math/Vector3.hh>

#include "gazebo/common/CommonTypes.hh"
#include "gazebo/msgs/msgs.hh"
#include "gazebo/physics/Base.hh"
#include "gazebo/physics/PhysicsTypes.hh"
#include "gazebo/transport/TransportTypes.hh"

namespace gazebo {
namespace physics {

class Entity : public Base {
 public:
  ~Entity() override;

  // A model: itself; a link: its model (Gazebo's Entity::GetParentModel).
  ModelPtr GetParentModel();

  // The entity's frame (a model's: its root link's), world frame.
  virtual ignition::math::Pose3d WorldPose() const = 0;
  // Moves the entity's model rigidly (joints kept); _notify and _publish have no effect in car.
  virtual void SetWorldPose(const ignition::math::Pose3d& _pose, bool _notify = true, bool _publish = true) = 0;
  // Velocities of the entity's frame origin [m/s] and [rad/s]: world frame, then the entity's axes.
  virtual ignition::math::Vector3d WorldLinearVel() const = 0;
  virtual ignition::math::Vector3d WorldAngularVel() const = 0;
  virtual ignition::math::Vector3d RelativeLinearVel() const = 0;
  virtual ignition::math::Vector3d RelativeAngularVel() const = 0;

 protected:
  // car: made by car_gazebo only.
  explicit Entity(BasePtr _parent);
};

}  // namespace physics
}  // namespace gazebo
