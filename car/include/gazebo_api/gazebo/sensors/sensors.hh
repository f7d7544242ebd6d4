// car's Gazebo 11 API (docs/PLUGINS.md "Sensors"): #include <gazebo/sensors/sensors.hh>, the sensors car offers.
#pragma once

#include "gazebo/sensors/CameraSensor.hh"
#include "gazebo/sensors/ContactSensor.hh"
#include "gazebo/sensors/DepthCameraSensor.hh"
#include "gazebo/sensors/ImuSensor.hh"
#include "gazebo/sensors/RaySensor.hh"
#include "gazebo/sensors/Sensor.hh"
#include "gazebo/sensors/SensorManager.hh"
#include "gazebo/sensors/SensorTypes.hh"
#include "gazebo/sensors/SensorsIface.hh"
