// What the bridge's parts (inputs.cpp, outputs.cpp, calls.cpp) may use of the node: its node handle, the world,
// sim-time stamps, and the publishing thread. The node owns pacing, /clock, the /gazebo services and the loop that
// hands each plug-in instance's outputs to its ports.
#pragma once

#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "car_sim/world.hpp"

namespace car_ros {

// What the bridge may use of the node.
class NodeContext {
 public:
  virtual ~NodeContext() = default;
  virtual ros::NodeHandle& nh() = 0;  // the global namespace
  virtual car_sim::World& world() = 0;
  virtual tf2_ros::TransformBroadcaster& tf() = 0;
  // The sim time of a tick.
  virtual ros::Time stamp(uint64_t tick) const = 0;

  // A port's publisher. Each subscriber's coming and going reaches the node through roscpp's connect callbacks
  // (run by the node's spinOnce between steps), so a lazy plug-in is switched on before the next step, as
  // gazebo_ros's sensors switch on from their connect callbacks.
  template <class M>
  ros::Publisher advertise(const std::string& topic, uint32_t queue) {
    const auto changed = [this](const ros::SingleSubscriberPublisher&) { listeners_changed(); };
    return nh().advertise<M>(topic, queue, changed, changed);
  }

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

  // The action server of the TrajectoryGoal input port on `ns` (inputs.cpp) ends its goals when a GoalResult
  // sample comes for that port's namespace (outputs.cpp). `owner` tells whose sink a drop removes.
  using GoalSink = std::function<void(const car_sim::GoalResultSample&)>;
  void set_goal_sink(const std::string& ns, const void* owner, GoalSink sink) { goal_sinks_[ns] = {owner, std::move(sink)}; }
  void drop_goal_sink(const std::string& ns, const void* owner) {
    const auto it = goal_sinks_.find(ns);
    if (it != goal_sinks_.end() && it->second.first == owner) goal_sinks_.erase(it);
  }
  void finish_goal(const std::string& ns, const car_sim::GoalResultSample& s) {
    const auto it = goal_sinks_.find(ns);
    if (it != goal_sinks_.end()) it->second.second(s);
  }

 protected:
  // A job for the publishing thread, with its size [bytes] for the queue's bound.
  virtual void post(std::function<void()> job, size_t bytes) = 0;
  // A message was posted on topic while it had `subscribers` subscribers (only while watch_published_).
  virtual void published(const std::string& topic, uint32_t subscribers) {}
  // A port's publisher gained or lost a subscriber.
  virtual void listeners_changed() {}
  bool watch_published_ = false;

 private:
  std::map<std::string, std::pair<const void*, GoalSink>> goal_sinks_;
};

}  // namespace car_ros
