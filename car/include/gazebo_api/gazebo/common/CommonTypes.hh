// car's Gazebo 11 API (docs/PLUGINS.md): forward declarations of the plug-in classes, common::Time and the event
// connection, with Gazebo 11's pointer types (gazebo/common/CommonTypes.hh). Gazebo's physics, sensors and plug-in
// headers include it, so a plug-in that includes only <gazebo/common/Plugin.hh> has event::ConnectionPtr.
#pragma once

#include <boost/shared_ptr.hpp>
#include <map>
#include <string>
#include <vector>

namespace gazebo {

class WorldPlugin;
class ModelPlugin;
class SensorPlugin;
class SystemPlugin;
typedef boost::shared_ptr<WorldPlugin> WorldPluginPtr;
typedef boost::shared_ptr<ModelPlugin> ModelPluginPtr;
typedef boost::shared_ptr<SensorPlugin> SensorPluginPtr;
typedef boost::shared_ptr<SystemPlugin> SystemPluginPtr;

namespace common {
class Time;
class PID;
typedef std::map<std::string, std::string> StrStr_M;
}  // namespace common

namespace event {
class Connection;
// Keep it: the callback is connected while a copy lives (Gazebo 11: a boost::shared_ptr).
typedef boost::shared_ptr<Connection> ConnectionPtr;
typedef std::vector<ConnectionPtr> Connection_V;
}  // namespace event

}  // namespace gazebo
