// hector_gazebo_plugins' libhector_gazebo_ros_gps.so (a robot-level plug-in): NavSatFix and a velocity in the
// reference frame (east-north-up when referenceHeading is 90 deg), through hector's SensorModel.
#pragma once

#include <string>

#include "car_sim/plugin.hpp"

namespace car_sim {

// The fix (position_variance: drift^2 + noise^2) and the velocity.
struct GpsOut : Output, NavSatFixSample {
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // [m/s]
  void visit(FieldVisitor& v) const override;
  // the fix; the velocity
  void samples(SampleList& list) const override {
    list.add(static_cast<const NavSatFixSample*>(this));
    list.add(Vector3Sample{velocity});
  }
};

const PluginKind& hector_gps_kind();

}  // namespace car_sim
