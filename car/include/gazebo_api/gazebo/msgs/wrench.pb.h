// car's Gazebo 11 API (docs/PLUGINS.md): gazebo::msgs::Wrench, hand-written (vector3d.pb.h). [N], [N m].
#pragma once

#include "gazebo/msgs/vector3d.pb.h"

namespace gazebo {
namespace msgs {

class Wrench {
 public:
  const Vector3d& force() const { return force_; }
  const Vector3d& torque() const { return torque_; }
  const Vector3d& force_offset() const { return force_offset_; }
  Vector3d* mutable_force() { return &force_; }
  Vector3d* mutable_torque() { return &torque_; }
  Vector3d* mutable_force_offset() { return &force_offset_; }

 private:
  Vector3d force_, torque_, force_offset_;
};

}  // namespace msgs
}  // namespace gazebo
