// hector_gazebo_plugins' libhector_gazebo_ros_gps.so (a robot-level plug-in): NavSatFix and a velocity in the
// reference frame (east-north-up when referenceHeading is 90 deg), through hector's SensorModel.
#pragma once

#include <string>

#include "car_sim/plugin.hpp"

namespace car_sim {

struct GpsOut : Output {
  double latitude = 0, longitude = 0, altitude = 0;  // [deg], [deg], [m]
  int status = 0, service = 0;                       // sensor_msgs/NavSatStatus
  Eigen::Vector3d position_variance = Eigen::Vector3d::Zero();  // [m^2] diagonal (drift^2 + noise^2)
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();           // [m/s]
  void visit(FieldVisitor& v) const override;
};

const PluginKind& hector_gps_kind();

}  // namespace car_sim
