// hector_gazebo_plugins' libhector_gazebo_ros_imu.so (a robot-level plug-in): sensor_msgs/Imu from a link's
// motion through hector's accel, rate and yaw SensorModels, and the current biases.
#pragma once

#include "../common/sensor_outputs.hpp"
#include "car_sim/plugin.hpp"

namespace car_sim {

struct HectorImuOut : ImuOut {
  Eigen::Quaterniond orientation_error = Eigen::Quaterniond::Identity();  // what the biases do to the orientation
  Eigen::Vector3d rate_bias = Eigen::Vector3d::Zero();                     // [rad/s]
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();                    // [m/s^2]
  void visit(FieldVisitor& v) const override;
  // the measurement; for the port "bias", the biases as an Imu sample (orientation_error, rate_bias, accel_bias)
  void samples(SampleList& list) const override {
    ImuOut::samples(list);
    list.add(ImuSample{orientation_error, rate_bias, accel_bias}, "bias");
  }
};

const PluginKind& hector_imu_kind();

}  // namespace car_sim
