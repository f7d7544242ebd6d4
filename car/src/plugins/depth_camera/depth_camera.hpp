// libgazebo_ros_depth_camera.so on a <sensor type="depth">: colour, depth image, organized cloud, camera_info.
#pragma once

#include "car_sim/plugin.hpp"

namespace car_sim {

const PluginKind& depth_camera_kind();

}  // namespace car_sim
