// libgazebo_ros_range.so on a <sensor type="ray"> (or gpu_ray): sonar / IR, the nearest hit of the ray grid.
#pragma once

#include <string>

#include "car_sim/plugin.hpp"

namespace car_sim {

// radiation: 0 ULTRASOUND, 1 INFRARED; field_of_view: the plug-in's <fov>; min_range / max_range: the sensor's
// range.min / range.max; range: max_range when nothing is in view. Also hector_sonar's output.
struct RangeOut : Output, RangeSample {
  std::string sensor;
  void visit(FieldVisitor& v) const override;
  const RangeSample* range_sample() const override { return this; }
};

const PluginKind& range_kind();

}  // namespace car_sim
