// car's Gazebo 11 API (docs/PLUGINS.md): gazebo::physics::Joint, a handle on a moving joint (revolute, continuous,
// prismatic: one axis, index 0) of one of car's robots.
#pragma once

#include <boost/any.hpp>
#include <boost/weak_ptr.hpp>
#include <ignition/math/Vector3.hh>
#include <string>

#include "gazebo/common/Event.hh"
#include "gazebo/common/Events.hh"
#include "gazebo/common/Time.hh"
#include "gazebo/msgs/MessageTypes.hh"
#include "gazebo/physics/Base.hh"
#include "gazebo/physics/PhysicsTypes.hh"

namespace gazebo {
namespace physics {

class Joint : public Base {
 public:
  // car: made by the Model handle.
  Joint(ModelPtr _model, const std::string& _name);
  ~Joint() override;

  ModelPtr GetModel() const;
  // The parent and child links (these hide Base::GetParent, as in Gazebo 11).
  LinkPtr GetParent() const;
  LinkPtr GetChild() const;
  unsigned int DOF() const;

  // [rad] or [m]; an index other than 0 is an error (gzerr) and NaN.
  double Position(const unsigned int _index = 0) const;
  // [rad/s] or [m/s]
  double GetVelocity(unsigned int _index) const;
  // Sets the joint's rate now; its position stays.
  void SetVelocity(unsigned int _index, double _vel);
  // [N m] or [N] for the coming step, clamped to the effort limit; calls in one step add up.
  void SetForce(unsigned int _index, double _effort);
  // The sum SetForce applied in the current (or, between steps, the last) step with a SetForce.
  double GetForce(unsigned int _index);
  // Sets the position, clamped to the limits (the child side moves, the parent stays): the joint's rate becomes 0,
  // or, with _preserveWorldVelocity, stays (car keeps the joint's rate; Gazebo keeps each moved link's world
  // velocity, or zeroes it: the same for a robot at rest).
  bool SetPosition(const unsigned int _index, const double _position, const bool _preserveWorldVelocity = false);
  double LowerLimit(unsigned int _index = 0) const;
  double UpperLimit(const unsigned int _index = 0) const;
  double GetEffortLimit(unsigned int _index);
  double GetVelocityLimit(unsigned int _index);
  // The axis in the joint frame (a unit vector).
  ignition::math::Vector3d LocalAxis(const unsigned int _index) const;

  // ODE's joint motor (Gazebo 11's ODEJoint::SetParam; docs/PLUGINS.md): "vel" [rad/s] or [m/s] and "fmax" [N m] or
  // [N]: every step the joint is driven to "vel" with at most "fmax" (0: off), until changed; "friction" sets fmax to
  // the value and vel to 0. _value must hold a double (else gzerr and false, as upstream). Other keys: gzerr, false.
  bool SetParam(const std::string& _key, unsigned int _index, const boost::any& _value);
  // "vel", "fmax" and "friction" (fmax) as set; 0 before any SetParam. Other keys: gzerr, 0.
  double GetParam(const std::string& _key, unsigned int _index);

 private:
  boost::weak_ptr<Model> model;
  std::string parent, child;
  double lower, upper, effort, velocity;
  ignition::math::Vector3d axis;
  double forceApplied = 0.0;
  common::Time forceAppliedTime;
  // a fixed joint: no axis (DOF 0), and each call answers as Gazebo 11's ODEFixedJoint
  bool fixed = false;
};

}  // namespace physics
}  // namespace gazebo
