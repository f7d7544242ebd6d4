// libgazebo_ros_block_laser.so on a <sensor type="ray"> (or gpu_ray): every ray of the horizontal x vertical
// grid as a point (sensor_msgs/PointCloud), multi-layer lidars' plug-in.
#pragma once

#include <string>
#include <vector>

#include "car_sim/plugin.hpp"

namespace car_sim {

// points: x y z per ray [m], sensor frame; intensities: the channel, laser_retro of the hit surface (+ noise)
struct BlockLaserOut : Output, PointCloudSample {
  std::string sensor;
  int rows = 0, cols = 0;          // vertical x horizontal samples; point (row j, col i) at index i + j cols
  void visit(FieldVisitor& v) const override;
  void samples(SampleList& list) const override { list.add(static_cast<const PointCloudSample*>(this)); }
};

const PluginKind& block_laser_kind();

}  // namespace car_sim
