// libgazebo_ros_camera.so on a <sensor type="camera"> (or a depth sensor's colour image): the shared ray-cast
// camera (common/camera_render.hpp) under the camera kind's record.
#pragma once

#include "../common/camera_render.hpp"

namespace car_sim {

const PluginKind& camera_kind();

}  // namespace car_sim
