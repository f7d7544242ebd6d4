// car's Gazebo 11 API (docs/PLUGINS.md): #include <gazebo/msgs/msgs.hh>, the messages car offers (hand-written
// classes with protobuf's accessors, vector3d.pb.h) and the conversions to ignition-math.
#pragma once

#include <ignition/math/Vector3.hh>

#include "gazebo/msgs/contact.pb.h"
#include "gazebo/msgs/contacts.pb.h"
#include "gazebo/msgs/joint_wrench.pb.h"
#include "gazebo/msgs/time.pb.h"
#include "gazebo/msgs/vector3d.pb.h"
#include "gazebo/msgs/wrench.pb.h"

namespace gazebo {
namespace msgs {

inline ignition::math::Vector3d ConvertIgn(const Vector3d& _v) { return {_v.x(), _v.y(), _v.z()}; }

}  // namespace msgs
}  // namespace gazebo
