// How car's ROS node writes a port's frames: gazebo_plugins' tf_prefix rules (car_sim::FrameRule,
// docs/COMPAT-spawn.md rule 4), in this one place.
#pragma once

#include <functional>
#include <string>

#include "car_sim/ports.hpp"

namespace car_ros {

// Noetic tf's tf::resolve(tf_prefix, name), which gazebo_plugins' GazeboRos::resolveTF calls: a name written with a
// leading '/' loses that one '/' and takes no prefix; another gets "PREFIX/" in front when tf_prefix is set (the
// prefix's own leading '/' dropped); with no prefix the name stays as written.
inline std::string resolve_tf(const std::string& prefix, const std::string& name) {
  if (!name.empty() && name[0] == '/') return name.substr(1);
  if (prefix.empty()) return name;
  return (prefix[0] == '/' ? prefix.substr(1) : prefix) + "/" + name;
}

// The tf_prefix parameter of namespace ns ("" when unset): searched upwards from /NS as gazebo_plugins' drives and
// camera_utils read it (tf::getPrefixParam), or in /NS itself as p3d, f3d and ft_sensor do
// (NodeHandle(robotNamespace).getParam("tf_prefix")).
using TfPrefixLookup = std::function<std::string(const std::string& ns, bool searched)>;

// A port's frames as published, and the tf_prefix they took ("" = none or not looked up).
struct PortFrames {
  car_sim::FrameRule rule = car_sim::FrameRule::PrefixSearched;
  std::string prefix;
  std::string frame, child_frame;  // header.frame_id, child_frame_id
  // Another frame the port publishes as a header frame (the wheel TF's links), by the same rule.
  std::string header_frame(const std::string& name) const;
};

// The frames of `port` by its FrameRule, tf_prefix looked up in the port's namespace where the rule reads it.
PortFrames port_frames(const car_sim::OutputPort& port, const TfPrefixLookup& tf_prefix);

// The node's TfPrefixLookup: the parameter server.
std::string tf_prefix_param(const std::string& ns, bool searched);

}  // namespace car_ros
