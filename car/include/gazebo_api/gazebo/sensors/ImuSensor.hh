// car's Gazebo 11 API (docs/PLUGINS.md "Sensors"): gazebo::sensors::ImuSensor, the sample of car's IMU
// (libgazebo_ros_imu_sensor.so's kind) for a <sensor type="imu">, its <noise> included.
#pragma once

#include <ignition/math/Quaternion.hh>
#include <ignition/math/Vector3.hh>

#include "gazebo/sensors/Sensor.hh"

namespace gazebo {
namespace sensors {

class ImuSensor : public Sensor {
 public:
  using Sensor::Sensor;
  // The sensor frame in the world (identity before the first measurement).
  ignition::math::Quaterniond Orientation() const;
  // [rad/s], sensor frame
  ignition::math::Vector3d AngularVelocity() const;
  // [m/s^2], sensor frame: the acceleration less gravity (+g up at rest)
  ignition::math::Vector3d LinearAcceleration() const;

 protected:
  void CarMeasure(const car_sim::Output* _sample) override;

 private:
  ignition::math::Quaterniond orientation;
  ignition::math::Vector3d angularVelocity, linearAcceleration;
};

}  // namespace sensors
}  // namespace gazebo
