// libgazebo_ros_openni_kinect.so on a <sensor type="depth">: colour, depth image, organized cloud, camera_info.
#pragma once

#include "car_sim/plugin.hpp"

namespace car_sim {

const PluginKind& openni_kinect_kind();

}  // namespace car_sim
