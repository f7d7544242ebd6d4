// libgazebo_ros_laser.so (and gpu_laser) on a <sensor type="ray"> (or gpu_ray): a planar scan.
#pragma once

#include <string>
#include <vector>

#include "car_sim/plugin.hpp"

namespace car_sim {

struct LaserScanOut : Output {
  std::string sensor;
  float angle_min = 0, angle_max = 0, angle_increment = 0;  // [rad]
  float range_min = 0, range_max = 0;                       // [m]
  std::vector<float> ranges;       // [m]; +inf: no hit within range_max
  std::vector<float> intensities;  // laser_retro of the hit surface
  void visit(FieldVisitor& v) const override;
};

const PluginKind& laser_kind();

}  // namespace car_sim
