// libgazebo_ros_imu_sensor.so on a <sensor type="imu">: Gazebo's ImuSensor and the gazebo_ros plug-in on it
// (docs/COMPAT-sensors.md "The two IMU plug-ins").
#pragma once

#include "car_sim/plugin.hpp"

namespace car_sim {

const PluginKind& imu_sensor_kind();

}  // namespace car_sim
