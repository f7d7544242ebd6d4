// A velocity motor made at run time on a robot's joint (private header of the core), for World::set_joint_motor:
// ODE's joint motor (dParamVel, dParamFMax) as Bullet's joint motor row. Kept apart from the motors plug-in kinds
// claim at configure time (Robot::add_motor), which are capped by the joint's <limit effort>; this one is not.
#pragma once

#include <memory>

#include "physics.hpp"

namespace car_sim {
namespace physics {

class JointMotor;

class VelocityMotor {
 public:
  // Adds the motor (off) to the physics world, on the joint's multibody link index.
  VelocityMotor(Physics& physics, Robot& robot, int joint);
  // Takes it out of the physics world again: before the robot or the physics goes.
  ~VelocityMotor();
  VelocityMotor(const VelocityMotor&) = delete;
  VelocityMotor& operator=(const VelocityMotor&) = delete;

  // Each step from now on: the joint's rate held at `velocity` [rad/s] or [m/s] as a hard constraint (gain 1),
  // its impulse capped at max_effort [N m] or [N] times dt [s]: the target within one step when that suffices.
  void set(double velocity, double max_effort, double dt);

 private:
  Physics& physics_;
  std::unique_ptr<JointMotor> motor_;
};

}  // namespace physics
}  // namespace car_sim
