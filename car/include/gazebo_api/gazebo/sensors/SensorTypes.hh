// car's Gazebo 11 API (docs/PLUGINS.md "Sensors"): the sensor classes' pointer types, std::shared_ptr as in
// Gazebo 11's gazebo/sensors/SensorTypes.hh.
#pragma once

#include <memory>
#include <vector>

namespace gazebo {
namespace sensors {

class Sensor;
class RaySensor;
class ContactSensor;
class ImuSensor;
class CameraSensor;
class DepthCameraSensor;

typedef std::shared_ptr<Sensor> SensorPtr;
typedef std::shared_ptr<RaySensor> RaySensorPtr;
typedef std::shared_ptr<ContactSensor> ContactSensorPtr;
typedef std::shared_ptr<ImuSensor> ImuSensorPtr;
typedef std::shared_ptr<CameraSensor> CameraSensorPtr;
typedef std::shared_ptr<DepthCameraSensor> DepthCameraSensorPtr;
typedef std::vector<SensorPtr> Sensor_V;
}  // namespace sensors
}  // namespace gazebo

// Gazebo 11's: lets a plug-in write dynamic_pointer_cast<sensors::RaySensor>(_parent) unqualified
#define GAZEBO_SENSORS_USING_DYNAMIC_POINTER_CAST using std::dynamic_pointer_cast

namespace gazebo {
namespace sensors {

}  // namespace sensors
}  // namespace gazebo
