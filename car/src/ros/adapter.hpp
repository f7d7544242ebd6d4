// ROS adapters, for the kinds whose outputs have no port type yet (src/ros/adapters/<kind>.cpp), registered in
// src/ros/adapters/registry.cpp. An adapter turns one plug-in instance's configuration into publishers, and its
// outputs into messages; inputs go through inputs.cpp, ported outputs through outputs.cpp. The node owns pacing,
// /clock, the /gazebo services and the loop that feeds the adapters. NodeContext is what all of them may use.
#pragma once

#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

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

  // Publishes msg on pub (a ros::Publisher or image_transport::Publisher) from the node's publishing thread:
  // the message is moved there, serialised and sent while the physics steps on; messages go out in the order
  // they were posted (src/ros/publish_queue.hpp).
  template <class P, class M>
  void publish(const P& pub, M msg) {
    // lockstep (docs/COMPAT-dropins.md): which topics a step published, and to how many
    if (watch_published_) published(pub.getTopic(), pub.getNumSubscribers());
    const size_t bytes = ros::serialization::serializationLength(msg);
    post([pub, m = std::move(msg)] { pub.publish(m); }, bytes);
  }
  // Transforms on /tf, the same way (the broadcaster is made on the first call, as tf()).
  void send_tf(geometry_msgs::TransformStamped t) { send_tf(std::vector<geometry_msgs::TransformStamped>{std::move(t)}); }
  void send_tf(std::vector<geometry_msgs::TransformStamped> ts) {
    tf2_ros::TransformBroadcaster* b = &tf();
    const size_t bytes = ts.size() * 128;
    post([b, v = std::move(ts)] { b->sendTransform(v); }, bytes);
  }

  // Returns once everything published so far has been sent (before an answer that must come after them,
  // e.g. an action's result after the controller's last state).
  virtual void flush_published() = 0;

 protected:
  // A job for the publishing thread, with its size [bytes] for the queue's bound.
  virtual void post(std::function<void()> job, size_t bytes) = 0;
  // A message was posted on topic while it had `subscribers` subscribers (only while watch_published_).
  virtual void published(const std::string& topic, uint32_t subscribers) {}
  bool watch_published_ = false;
};

class Adapter {
 public:
  virtual ~Adapter() = default;
  // Publishers and subscribers of one plug-in instance; returns what it offers, for the node's log line
  // ("topics ..."), or "" to stay silent.
  virtual std::string setup(const car_sim::PluginInfo& plugin, const car_sim::RobotInfo& robot, NodeContext& node) = 0;
  // Someone listens to one of its topics: a lazy plug-in computes only then.
  virtual bool listened() const { return false; }
  // The parts of its plug-in's outputs its subscribers take (Plugin::set_parts; all bits: everything).
  virtual uint32_t parts() const { return ~0u; }
  // One output of its plug-in instance, as messages.
  virtual void publish(const car_sim::Output& out, NodeContext& node) = 0;
  // The same, with the output's ownership: an adapter whose messages are serialised straight from the output's
  // arrays on the publishing thread (the cameras) keeps it until they are sent.
  virtual void publish_owned(std::shared_ptr<const car_sim::Output> out, NodeContext& node) { publish(*out, node); }
};

struct AdapterKind {
  const char* kind;                      // the plug-in kind's registry name
  std::unique_ptr<Adapter> (*make)();
};

// The adapter of a kind; nullptr when the kind has none (its outputs are not published).
const AdapterKind* find_adapter(const std::string& kind);

// The tf_prefix parameter as gazebo_plugins' drives read it (tf::getPrefixParam on a node handle in the plug-in's
// namespace: searchParam upwards from /NS); "" when none is set (docs/COMPAT-spawn.md rule 4).
std::string tf_prefix_param(const std::string& ns);

}  // namespace car_ros
