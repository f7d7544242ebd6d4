// libgazebo_ros_planar_move.so: the model's base moved by setting its velocity from a body twist (x, y, yaw
// rate), odometry from the world pose. Behaviour per docs/COMPAT-plugins.md.
#pragma once

#include "car_sim/drive.hpp"
#include "car_sim/plugin.hpp"

namespace car_sim {

// World-frame velocity [m/s] of a base at heading yaw [rad] for a body-frame command (vx, vy) [m/s]:
// (vx cos yaw - vy sin yaw, vy cos yaw + vx sin yaw), as upstream.
Eigen::Vector2d planar_world_velocity(double vx, double vy, double yaw);

const PluginKind& planar_move_kind();

}  // namespace car_sim
