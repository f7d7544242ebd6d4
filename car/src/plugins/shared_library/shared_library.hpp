// The plug-in table's entry for plug-ins from shared libraries (users' own Gazebo plug-ins; docs/PLUGINS.md): a
// robot-level <plugin filename> that no kind of car's serves and that is found on the search path
// (car_sim/shared_plugin.hpp). Its instance dlopens the file once the robot is in the world and hands the library's
// RegisterPlugin to the skin that runs it (car_gazebo).
#pragma once

#include "car_sim/plugin.hpp"

namespace car_sim {

const PluginKind& shared_library_kind();

}  // namespace car_sim
