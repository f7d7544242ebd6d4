// libgazebo_ros_skid_steer_drive.so: four wheel joints as velocity motors, left pair at v − ω·sep/2, right pair at
// v + ω·sep/2; odometry from the world. Behaviour per docs/COMPAT-plugins.md.
#pragma once

#include "car_sim/drive.hpp"
#include "car_sim/plugin.hpp"

namespace car_sim {

const PluginKind& skid_steer_drive_kind();

}  // namespace car_sim
