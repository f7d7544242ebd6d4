// ODE's joint motor for World::set_joint_motor (see velocity_motor.hpp).
#include "velocity_motor.hpp"

#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>

#include "surface.hpp"

namespace car_sim {
namespace physics {

VelocityMotor::VelocityMotor(Physics& physics, Robot& robot, int joint)
    : physics_(physics), motor_(std::make_unique<JointMotor>(robot.multibody(), joint, 0, 0.0, 0.0)) {
  physics_.bullet().addMultiBodyConstraint(motor_.get());
}

VelocityMotor::~VelocityMotor() { physics_.bullet().removeMultiBodyConstraint(motor_.get()); }

void VelocityMotor::set(double velocity, double max_effort, double dt) {
  motor_->setVelocityTarget(velocity, 1.0);
  motor_->setPositionTarget(0.0, 0.0);
  motor_->setMaxAppliedImpulse(max_effort * dt);
}

}  // namespace physics
}  // namespace car_sim
