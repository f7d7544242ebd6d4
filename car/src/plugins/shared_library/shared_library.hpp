// The plug-in table's entry for plug-ins from shared libraries (users' own Gazebo plug-ins; docs/PLUGINS.md): a
// robot-level <plugin filename> that no kind of car's serves and that is found on the search path
// (car_sim/shared_plugin.hpp). Its instance dlopens the file once the robot is in the world and hands the library's
// RegisterPlugin to the skin that runs it (car_gazebo).
#pragma once

#include "car_sim/plugin.hpp"

namespace car_sim {

const PluginKind& shared_library_kind();

// The <plugin> keys car's kind for a sensor type is resolved with when it measures for Gazebo's sensors API, so
// that it measures as the bare sensor (imu: every measurement, the orientation from the sensor's own at load as
// Gazebo's ImuSensor::Orientation; a frame name, which gazebo_ros's plug-in requires). Diagnostics at these keys
// are car's, not the user's: they are not reported.
ParamList sensor_feed_params(const SensorSpec& sensor);

}  // namespace car_sim
