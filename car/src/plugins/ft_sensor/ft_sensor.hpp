// libgazebo_ros_ft_sensor.so: the force and torque a joint exerts on its child link (outputs are WrenchOut, in
// the child link's frame).
#pragma once

#include "car_sim/plugin.hpp"
#include "f3d/f3d.hpp"

namespace car_sim {

const PluginKind& ft_sensor_kind();

}  // namespace car_sim
