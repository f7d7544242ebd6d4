// car's Gazebo 11 API (docs/PLUGINS.md "Sensors"): gazebo::sensors::get_sensor.
#pragma once

#include <string>

#include "gazebo/sensors/SensorTypes.hh"

namespace gazebo {
namespace sensors {

// SensorManager::Instance()->GetSensor(_name).
SensorPtr get_sensor(const std::string& _name);

}  // namespace sensors
}  // namespace gazebo
