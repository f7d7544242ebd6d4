// The input half of the ROS bridge: one subscriber factory per input sample type (Twist, Wrench, JointTrajectory,
// Trigger, Float64, Float64Array; a Pose read from TF; a TrajectoryGoal through a FollowJointTrajectory action
// server). Every message becomes a car_sim::Command and enters the core through World::command, which checks it; a
// rejected value gets one warning per port, throttled. Names no plug-in kind.
#pragma once

#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "context.hpp"

namespace car_ros {

class InputPorts {
 public:
  // Subscribers (or a TF reader, an action server) for every input port of one plug-in instance; returns the
  // topics for the log. Called again when the instance's ports change: a port of the same name, type and topic
  // keeps its subscriber, the others go.
  std::string setup(const car_sim::PluginInfo& plugin, NodeContext& node);
  // Reads the TF-fed ports and hands their values to the world (after each output of the plug-in is published,
  // as gazebo_ros's hand of god looks its target up on each update).
  void poll();
  bool polled() const { return polled_; }

  struct Port;  // one port and its subscriber (inputs.cpp)

 private:
  std::vector<std::shared_ptr<Port>> ports_;
  bool polled_ = false;  // some port is read from TF
};

}  // namespace car_ros
