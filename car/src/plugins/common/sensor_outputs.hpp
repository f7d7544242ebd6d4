// Outputs more than one kind publishes: the IMU sample (imu, imu_sensor, hector_imu) and the range sample (range,
// hector_sonar). Not a kind: shared code.
#pragma once

#include <string>
#include <vector>

#include "car_sim/plugin.hpp"

namespace car_sim {

// The orientation, angular velocity [rad/s] and linear acceleration [m/s^2] of an IMU message, as its kind
// defines them (docs/COMPAT-sensors.md "The two IMU plug-ins", hector's IMU).
struct ImuOut : Output, ImuSample {
  std::string sensor;
  void visit(FieldVisitor& v) const override;
  void samples(SampleList& list) const override { list.add(static_cast<const ImuSample&>(*this)); }
};

// Both gazebo_ros IMU plug-ins' port: sensor_msgs/Imu on topicName in frameName, queue 1 (as their advertise),
// gaussianNoise^2 on the three covariances' diagonals.
std::vector<OutputPort> imu_ports(const PluginConfig& c, const std::string& robot, const Environment& env);

// radiation: 0 ULTRASOUND, 1 INFRARED; field_of_view: the plug-in's <fov>; min_range / max_range: the sensor's
// range.min / range.max; range: max_range when nothing is in view. Also hector_sonar's output.
struct RangeOut : Output, RangeSample {
  std::string sensor;
  void visit(FieldVisitor& v) const override;
  void samples(SampleList& list) const override { list.add(static_cast<const RangeSample*>(this)); }
};

}  // namespace car_sim
