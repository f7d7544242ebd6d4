// car's Gazebo 11 API (docs/PLUGINS.md): gazebo/physics/HingeJoint.hh, which plug-ins include (gazebo_ros_laser,
// ...) without using it: Gazebo's physics engines derive their hinge joints from this template. car's joints are
// physics::Joint handles; the template is declared so that the include builds, and instantiating it does not.
#pragma once

#include "gazebo/physics/Joint.hh"

namespace gazebo {
namespace physics {

template <class T>
class HingeJoint : public T {
  static_assert(sizeof(T) == 0, "car: physics::HingeJoint<T> (a physics engine's base) is not offered");
};

}  // namespace physics
}  // namespace gazebo
