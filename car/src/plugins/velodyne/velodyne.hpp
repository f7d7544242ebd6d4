// velodyne_simulator's libgazebo_ros_velodyne_laser.so / libgazebo_ros_velodyne_gpu_laser.so on a
// <sensor type="ray"> (or gpu_ray): the rays of the grid inside the range band as points with intensity and ring.
#pragma once

#include <string>
#include <vector>

#include "car_sim/plugin.hpp"

namespace car_sim {

struct VelodyneOut : Output {
  std::string sensor;
  std::vector<float> points;       // x y z per kept ray [m], sensor frame; horizontal index outer, ring inner
  std::vector<float> intensities;  // laser_retro of the hit surface
  std::vector<uint16_t> rings;     // vertical index j, 0 = the lowest beam
  void visit(FieldVisitor& v) const override;
};

const PluginKind& velodyne_kind();

}  // namespace car_sim
