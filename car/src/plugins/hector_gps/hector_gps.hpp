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
  const NavSatFixSample* nav_sat_fix_sample() const override { return this; }
  bool vector3_sample(Eigen::Vector3d* v) const override {
    *v = velocity;
    return true;
  }
};

const PluginKind& hector_gps_kind();

}  // namespace car_sim
