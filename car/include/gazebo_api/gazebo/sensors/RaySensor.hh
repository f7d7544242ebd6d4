// car's Gazebo 11 API (docs/PLUGINS.md "Sensors"): gazebo::sensors::RaySensor, the ranges of car's laser for a
// <sensor type="ray"> (or gpu_ray).
#pragma once

#include <ignition/math/Angle.hh>
#include <vector>

#include "gazebo/sensors/Sensor.hh"

namespace gazebo {
namespace sensors {

class RaySensor : public Sensor {
 public:
  using Sensor::Sensor;
  // [rad] <ray><scan><horizontal> min_angle, max_angle; the angle between two ranges
  ignition::math::Angle AngleMin() const;
  ignition::math::Angle AngleMax() const;
  double AngleResolution() const;
  // [m] <ray><range>
  double RangeMin() const;
  double RangeMax() const;
  double RangeResolution() const;
  // <horizontal><samples>; times <resolution>
  int RayCount() const;
  int RangeCount() const;
  int VerticalRayCount() const;
  int VerticalRangeCount() const;
  ignition::math::Angle VerticalAngleMin() const;
  ignition::math::Angle VerticalAngleMax() const;
  double VerticalAngleResolution() const;
  // [m] of the last scan, row after row (index row * RangeCount() + i); +inf where nothing is hit within RangeMax
  // (car's laser: docs/COMPAT-sensors.md). 0 with an error for an index out of range or before the first scan.
  double Range(const unsigned int _index) const;
  void Ranges(std::vector<double>& _ranges) const;
  // The hit surface's <laser_retro> (car's laser intensities).
  double Retro(const unsigned int _index) const;
  // Gazebo's transport topic of its scans (msgs::LaserScanStamped): "~/MODEL/LINK/SENSOR/scan" ("::" as "/"); each
  // measurement is published there while it has a subscriber.
  std::string Topic() const;
  // Active while SetActive(true) holds, or while its topic has a subscriber, as Gazebo 11's RaySensor.
  bool IsActive() const override;

 protected:
  void CarMeasure(const car_sim::Output* _sample) override;

 private:
  const std::string& ScanTopic() const;
  std::vector<double> ranges, retros;
  // car: Topic() decoded as transport::Node does ("/gazebo/WORLD/..."), made once (IsActive asks every step)
  mutable std::string decodedTopic;
};

}  // namespace sensors
}  // namespace gazebo
