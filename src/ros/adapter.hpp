// ROS adapters: one per plug-in kind (src/ros/adapters/<kind>.cpp), registered in src/ros/adapters/registry.cpp.
// An adapter turns one plug-in instance's configuration into publishers and subscribers, and its outputs into
// messages. The node owns pacing, /clock, the /gazebo services and the loop that feeds the adapters.
#pragma once

#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>

#include <memory>
#include <string>

#include "car_sim/world.hpp"

namespace car_ros {

// What an adapter may use of the node.
class NodeContext {
 public:
  virtual ~NodeContext() = default;
  virtual ros::NodeHandle& nh() = 0;  // the global namespace
  virtual car_sim::World& world() = 0;
  virtual tf2_ros::TransformBroadcaster& tf() = 0;
  // The sim time of a tick.
  virtual ros::Time stamp(uint64_t tick) const = 0;
};

class Adapter {
 public:
  virtual ~Adapter() = default;
  // Publishers and subscribers of one plug-in instance; returns what it offers, for the node's log line
  // ("topics ..."), or "" to stay silent.
  virtual std::string setup(const car_sim::PluginInfo& plugin, const car_sim::RobotInfo& robot, NodeContext& node) = 0;
  // Someone listens to one of its topics: a lazy plug-in computes only then.
  virtual bool listened() const { return false; }
  // One output of its plug-in instance, as messages.
  virtual void publish(const car_sim::Output& out, NodeContext& node) = 0;
};

struct AdapterKind {
  const char* kind;                      // the plug-in kind's registry name
  std::unique_ptr<Adapter> (*make)();
};

// The adapter of a kind; nullptr when the kind has none (its outputs are not published).
const AdapterKind* find_adapter(const std::string& kind);

// A plug-in's namespace by its file's <robotNamespace> rule (absent, empty, explicit: docs/COMPAT-plugins.md
// "Namespaces"): leading and trailing '/' removed ("" = global).
std::string plugin_namespace(const car_sim::PluginConfig& c, const std::string& model_name);

}  // namespace car_ros
