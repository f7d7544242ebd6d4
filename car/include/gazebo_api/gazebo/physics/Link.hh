// car's Gazebo 11 API (docs/PLUGINS.md): gazebo::physics::Link, a handle on a link of one of car's robots.
// Forces and torques act in the coming physics step only (Gazebo's rule): add them each step, in WorldUpdateBegin.
#pragma once

#include <boost/weak_ptr.hpp>
#include <ignition/math/Pose3.hh>
#include <ignition/math/Vector3.hh>
#include <string>

#include "gazebo/common/CommonTypes.hh"
#include "gazebo/common/Event.hh"
#include "gazebo/msgs/msgs.hh"
#include "gazebo/physics/Entity.hh"
#include "gazebo/physics/PhysicsTypes.hh"

namespace gazebo {
namespace physics {

class Link : public Entity {
 public:
  // car: made by the Model handle.
  Link(ModelPtr _model, const std::string& _name);
  ~Link() override;

  ModelPtr GetModel() const;
  InertialPtr GetInertial() const;

  // The link frame, world frame.
  ignition::math::Pose3d WorldPose() const override;
  // The centre of gravity's frame (the link's axes), world frame.
  ignition::math::Pose3d WorldCoGPose() const;
  // Moves the link's whole model rigidly so that the link lands on _pose (joints kept); _notify and _publish have
  // no effect in car.
  void SetWorldPose(const ignition::math::Pose3d& _pose, bool _notify = true, bool _publish = true) override;
  // Velocity of the link frame's origin, world frame.
  ignition::math::Vector3d WorldLinearVel() const override;
  // Velocity of the point _offset (link frame, from the link origin), world frame.
  ignition::math::Vector3d WorldLinearVel(const ignition::math::Vector3d& _offset) const;
  ignition::math::Vector3d WorldCoGLinearVel() const;
  ignition::math::Vector3d WorldAngularVel() const override;
  // The same in the link's axes.
  ignition::math::Vector3d RelativeLinearVel() const override;
  ignition::math::Vector3d RelativeAngularVel() const override;
  // The centre of gravity's velocity / the angular velocity, world frame; the model moves rigidly with the link.
  void SetLinearVel(const ignition::math::Vector3d& _vel);
  void SetAngularVel(const ignition::math::Vector3d& _vel);

  // [N] world frame, at the centre of gravity.
  void AddForce(const ignition::math::Vector3d& _force);
  // [N] link axes, at the centre of gravity.
  void AddRelativeForce(const ignition::math::Vector3d& _force);
  // [N] world frame, at a world position [m].
  void AddForceAtWorldPosition(const ignition::math::Vector3d& _force, const ignition::math::Vector3d& _pos);
  // [N] world frame, at _relPos [m] (link frame, from the link origin).
  void AddForceAtRelativePosition(const ignition::math::Vector3d& _force, const ignition::math::Vector3d& _relPos);
  // [N] link axes, at _offset [m] (link frame, from the link origin).
  void AddLinkForce(const ignition::math::Vector3d& _force,
                    const ignition::math::Vector3d& _offset = ignition::math::Vector3d::Zero);
  // [N m] world axes / link axes.
  void AddTorque(const ignition::math::Vector3d& _torque);
  void AddRelativeTorque(const ignition::math::Vector3d& _torque);
  // The sum of the forces [N] / torques [N m] (about the centre of gravity) added to the link in the current step,
  // world frame: in WorldUpdateBegin and BeforePhysicsUpdate, what the callbacks before added (Gazebo's ODE clears
  // them after the step; car keeps the step's sum until the next one starts).
  ignition::math::Vector3d WorldForce() const;
  ignition::math::Vector3d WorldTorque() const;

  // The link frame relative to its model's frame.
  ignition::math::Pose3d RelativePose() const;
  // car: the link's world pose (Gazebo's pose being written by the physics; car writes none during a callback).
  ignition::math::Pose3d DirtyPose() const;
  // false: gravity no longer acts on the link (from the coming step on; kept over resets).
  void SetGravityMode(bool _mode);
  bool GetGravityMode() const;
  // ODE's dBodyEnable / dBodyDisable, as Gazebo 11's ODELink. ODE enables again, at the next step, a disabled body
  // that a joint links to an enabled one (its islands), so in a model with an enabled link a disabled link is
  // enabled after the coming step; forces, torques and poses set on the link, and SetForce or SetParam on its
  // joints, enable it at once. A model whose every link is disabled: Gazebo's ODE holds it still until a contact or
  // a force enables a link; car goes on simulating it, and says so once (gzwarn).
  void SetEnabled(bool _enable) const;
  bool GetEnabled() const;

 private:
  boost::weak_ptr<Model> model;
  InertialPtr inertial;
  // car: SetEnabled(false) until ODE's island rule enables the link again, checked after each step
  mutable bool disabled = false;
  mutable event::ConnectionPtr islandCheck;
};

}  // namespace physics
}  // namespace gazebo
