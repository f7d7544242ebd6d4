// libgazebo_ros_tricycle_drive.so: a steered, driven front wheel (cmd_vel linear.x = its surface speed, angular.z =
// the steering ANGLE, as upstream) and two free encoder wheels; odometry from the world or the encoders.
#pragma once

#include "car_sim/drive.hpp"
#include "car_sim/plugin.hpp"

namespace car_sim {

// Upstream's wheel speed ramp: within `tolerance` of the target keep the current speed; more than accel*dt away
// step by accel*dt (decel*dt when speeding up — upstream's naming is reversed); else the target. accel <= 0: target.
double tricycle_wheel_speed(double current, double target, double accel, double decel, double tolerance, double dt);

const PluginKind& tricycle_drive_kind();

}  // namespace car_sim
