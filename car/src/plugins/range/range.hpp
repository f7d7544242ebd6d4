// libgazebo_ros_range.so on a <sensor type="ray"> (or gpu_ray): sonar / IR, the nearest hit of the ray grid.
#pragma once

#include <string>

#include "car_sim/plugin.hpp"

namespace car_sim {

struct RangeOut : Output {
  std::string sensor;
  int radiation = 0;             // sensor_msgs/Range: 0 ULTRASOUND, 1 INFRARED
  float field_of_view = 0;       // [rad], the plug-in's <fov>
  float min_range = 0, max_range = 0;  // [m], the sensor's range.min / range.max
  float range = 0;               // [m], max_range when nothing is in view
  void visit(FieldVisitor& v) const override;
};

const PluginKind& range_kind();

}  // namespace car_sim
