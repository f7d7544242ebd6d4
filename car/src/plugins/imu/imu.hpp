// libgazebo_ros_imu_sensor.so on a <sensor type="imu">, and the robot-level libgazebo_ros_imu.so.
#pragma once

#include <string>

#include "car_sim/plugin.hpp"

namespace car_sim {

// The sensor frame's orientation in the world, its angular velocity [rad/s] and its linear acceleration [m/s^2],
// gravity included, both in the sensor frame.
struct ImuOut : Output, ImuSample {
  std::string sensor;
  void visit(FieldVisitor& v) const override;
  bool imu_sample(const std::string& port, ImuSample* s) const override {
    *s = *this;
    return true;
  }
};

const PluginKind& imu_kind();

}  // namespace car_sim
