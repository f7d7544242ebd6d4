// car's Gazebo 11 API (docs/PLUGINS.md "Sensors"): gazebo::sensors::SensorManager, the sensors car offers to
// Gazebo's API in every world of the process.
#pragma once

#include <string>

#include "gazebo/sensors/SensorTypes.hh"

namespace gazebo {
namespace sensors {

class SensorManager {
 public:
  static SensorManager* Instance();
  // By scoped name "world::model::link::sensor", else by <sensor name> when exactly one sensor has it (several:
  // Gazebo's error, and none); nullptr when none.
  SensorPtr GetSensor(const std::string& _name) const;
  Sensor_V GetSensors() const;

  // car: a sensor comes and goes with its model.
  void CarAdd(const SensorPtr& _sensor);
  void CarRemove(const SensorPtr& _sensor);

 private:
  SensorManager() = default;
  Sensor_V sensors;
};

}  // namespace sensors
}  // namespace gazebo
