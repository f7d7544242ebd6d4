// The calls half of the ROS bridge: one service factory per call type (controller_manager_msgs' LoadController,
// UnloadController, SwitchController, ListControllers, ListControllerTypes, ReloadControllerLibraries), and one
// call at set-up with the parameters a SetParameters port names. Every request becomes a car_sim::CallRequest and
// enters the core through World::call; its log lines are the core's.
// Names no plug-in kind.
#pragma once

#include <ros/ros.h>

#include <functional>
#include <string>
#include <vector>

#include "context.hpp"

namespace car_ros {

class ServicePorts {
 public:
  // Called after a call that changed the instance's ports, to read them again.
  using PortsChanged = std::function<void()>;
  // Services for every ServicePort of one plug-in instance; returns the services' namespace for the log line.
  std::string setup(const car_sim::PluginInfo& plugin, NodeContext& node, PortsChanged changed);

 private:
  std::vector<ros::ServiceServer> servers_;
};

}  // namespace car_ros
