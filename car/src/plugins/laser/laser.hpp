// libgazebo_ros_laser.so (and gpu_laser) on a <sensor type="ray"> (or gpu_ray): a planar scan.
#pragma once

#include <string>
#include <vector>

#include "car_sim/plugin.hpp"
#include "../common/ray_sensor.hpp"

namespace car_sim {

struct LaserScanOut : Output, LaserScanSample {
  std::string sensor;
  void visit(FieldVisitor& v) const override;
  void samples(SampleList& list) const override { list.add(static_cast<const LaserScanSample*>(this)); }
};

const PluginKind& laser_kind();

// The <ray> sensor keys every ray-sensor kind reads (SDF 1.6 defaults), vertical scan included.


}  // namespace car_sim
