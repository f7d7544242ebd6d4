// The output half of the ROS bridge: each plug-in instance's output ports, published by sample type through one
// converter per type (converters.hpp; outputs.cpp, the camera types in outputs_image.cpp). Frames by the port's
// FrameRule (frames.hpp). Names no plug-in kind.
#pragma once

#include <ros/ros.h>

#include <memory>
#include <string>
#include <vector>

#include "context.hpp"
#include "converters.hpp"

namespace car_ros {

class OutputPorts {
 public:
  // Publishers for every output port of one plug-in instance; returns what it offers, for the log line. Called
  // again when the instance's ports change: a port of the same name, type and topic keeps its publisher.
  std::string setup(const car_sim::PluginInfo& plugin, const car_sim::RobotInfo& robot, NodeContext& node);
  bool empty() const { return ports_.empty(); }
  // Someone listens to one of its topics.
  bool listened() const;
  // The parts of the output its subscribed ports take (Plugin::set_parts; all bits: every part).
  uint32_t parts() const;
  // One output of the instance, on every port (or the one its `port` names), in the ports' order; its ownership,
  // for the messages serialised straight from its arrays on the publishing thread (the camera types), which keep
  // it until they are sent.
  void publish(std::shared_ptr<const car_sim::Output> out, NodeContext& node);

 private:
  std::vector<OutPort> ports_;
  const car_sim::RobotModel* model_ = nullptr;
  car_sim::SampleList samples_;  // the output being published's
};

}  // namespace car_ros
