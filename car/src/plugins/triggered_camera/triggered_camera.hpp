// libgazebo_ros_triggered_camera.so on a <sensor type="camera">: the ray-cast camera, rendering one frame per
// trigger (docs/COMPAT-sensors.md "libgazebo_ros_triggered_camera.so").
#pragma once

#include "car_sim/plugin.hpp"

namespace car_sim {

// What the node calls on a trigger message (between steps).
class CameraTrigger {
 public:
  virtual ~CameraTrigger() = default;
  // One more frame to render: in the first step after this call, each further pending one in the steps after.
  virtual void trigger() = 0;
};

const PluginKind& triggered_camera_kind();

}  // namespace car_sim
