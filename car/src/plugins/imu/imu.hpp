// libgazebo_ros_imu_sensor.so on a <sensor type="imu">, and the robot-level libgazebo_ros_imu.so.
#pragma once

#include <string>

#include "car_sim/plugin.hpp"

namespace car_sim {

struct ImuOut : Output {
  std::string sensor;
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // sensor frame in the world
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();       // [rad/s], sensor frame
  Eigen::Vector3d linear_acceleration = Eigen::Vector3d::Zero();    // [m/s^2], sensor frame, gravity included
  void visit(FieldVisitor& v) const override;
};

const PluginKind& imu_kind();

}  // namespace car_sim
