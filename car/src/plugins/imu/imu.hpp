// The robot-level libgazebo_ros_imu.so (gazebo_ros_imu.cpp); the IMU sample every IMU kind publishes is in
// common/sensor_outputs.hpp.
#pragma once

#include <string>

#include "car_sim/plugin.hpp"
#include "../common/sensor_outputs.hpp"

namespace car_sim {

const PluginKind& imu_kind();

}  // namespace car_sim
