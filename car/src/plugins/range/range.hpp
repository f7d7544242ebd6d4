// libgazebo_ros_range.so on a <sensor type="ray"> (or gpu_ray): sonar / IR, the nearest hit of the ray grid.
#pragma once

#include <string>

#include "car_sim/plugin.hpp"
#include "../common/sensor_outputs.hpp"

namespace car_sim {

const PluginKind& range_kind();

}  // namespace car_sim
