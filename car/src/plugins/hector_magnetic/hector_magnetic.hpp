// hector_gazebo_plugins' libhector_gazebo_ros_magnetic.so (a robot-level plug-in): the earth's magnetic field in
// a link's frame, through hector's SensorModel.
#pragma once

#include <string>

#include "car_sim/plugin.hpp"

namespace car_sim {

struct MagneticOut : Output {
  Eigen::Vector3d field = Eigen::Vector3d::Zero();  // the body frame (magnitude's unit, default 1)
  void visit(FieldVisitor& v) const override;
  // a Vector3 (or, served by it, a MagneticField) port's
  void samples(SampleList& list) const override { list.add(Vector3Sample{field}); }
};

const PluginKind& hector_magnetic_kind();

}  // namespace car_sim
