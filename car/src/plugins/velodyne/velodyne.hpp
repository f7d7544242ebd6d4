// velodyne_simulator's libgazebo_ros_velodyne_laser.so / libgazebo_ros_velodyne_gpu_laser.so on a
// <sensor type="ray"> (or gpu_ray): the rays of the grid inside the range band as points with intensity and ring.
#pragma once

#include <string>
#include <vector>

#include "car_sim/plugin.hpp"

namespace car_sim {

// points: x y z per kept ray [m], sensor frame, horizontal index outer, ring inner; intensities: laser_retro of the
// hit surface; rings: vertical index j, 0 = the lowest beam
struct VelodyneOut : Output, LidarCloudSample {
  std::string sensor;
  void visit(FieldVisitor& v) const override;
  void samples(SampleList& list) const override { list.add(static_cast<const LidarCloudSample*>(this)); }
};

const PluginKind& velodyne_kind();

}  // namespace car_sim
