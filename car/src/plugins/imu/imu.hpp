// The robot-level libgazebo_ros_imu.so (gazebo_ros_imu.cpp), and the IMU sample every IMU kind publishes.
#pragma once

#include <string>

#include "car_sim/plugin.hpp"

namespace car_sim {

// The orientation, angular velocity [rad/s] and linear acceleration [m/s^2] of an IMU message, as its kind
// defines them (docs/COMPAT-sensors.md "The two IMU plug-ins", hector's IMU).
struct ImuOut : Output, ImuSample {
  std::string sensor;
  void visit(FieldVisitor& v) const override;
  bool imu_sample(const std::string& port, ImuSample* s) const override {
    *s = *this;
    return true;
  }
};

// Both gazebo_ros IMU plug-ins' port: sensor_msgs/Imu on topicName in frameName, queue 1 (as their advertise),
// gaussianNoise^2 on the three covariances' diagonals.
std::vector<OutputPort> imu_ports(const PluginConfig& c, const std::string& robot, const Environment& env);

const PluginKind& imu_kind();

}  // namespace car_sim
