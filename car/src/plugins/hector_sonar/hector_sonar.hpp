// hector_gazebo_plugins' libhector_gazebo_ros_sonar.so on a <sensor type="ray">: sensor_msgs/Range from the
// nearest hit of the ray grid through hector's SensorModel (scale error, offset, drift, Gaussian noise).
#pragma once

#include "car_sim/plugin.hpp"

namespace car_sim {

const PluginKind& hector_sonar_kind();

}  // namespace car_sim
