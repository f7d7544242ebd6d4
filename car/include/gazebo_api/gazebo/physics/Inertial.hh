// car's Gazebo 11 API (docs/PLUGINS.md): gazebo::physics::Inertial, a link's mass properties (read only).
#pragma once

#include <ignition/math/Matrix3.hh>
#include <ignition/math/Pose3.hh>
#include <ignition/math/Vector3.hh>

namespace gazebo {
namespace physics {

class Inertial {
 public:
  Inertial();
  virtual ~Inertial();
  // [kg]
  double Mass() const;
  // [m] the centre of gravity in the link frame.
  const ignition::math::Vector3d& CoG() const;
  // [kg m^2] about the centre of gravity, link axes.
  double IXX() const;
  double IYY() const;
  double IZZ() const;
  double IXY() const;
  double IXZ() const;
  double IYZ() const;
  ignition::math::Vector3d PrincipalMoments() const;
  ignition::math::Matrix3d MOI() const;


 private:
  friend class Link;  // car: the Link fills it from car's model
  double mass = 0.0;
  ignition::math::Vector3d cog;
  ignition::math::Matrix3d moi = ignition::math::Matrix3d::Zero;
};

}  // namespace physics
}  // namespace gazebo
