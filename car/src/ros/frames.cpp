// gazebo_plugins' tf_prefix rules for the frames of a port (docs/COMPAT-spawn.md rule 4).
#include "frames.hpp"

#include <ros/ros.h>

namespace car_ros {

std::string PortFrames::header_frame(const std::string& name) const {
  switch (rule) {
    case car_sim::FrameRule::PrefixSearched:
    case car_sim::FrameRule::PrefixHere: return resolve_tf(prefix, name);
    case car_sim::FrameRule::NoPrefix: return car_sim::strip_frame(name);
    case car_sim::FrameRule::AsWritten: return name;
  }
  return name;
}

PortFrames port_frames(const car_sim::OutputPort& port, const TfPrefixLookup& tf_prefix) {
  PortFrames f;
  f.rule = port.frame_rule;
  switch (port.frame_rule) {
    // GazeboRos::resolveTF with tf::getPrefixParam: both frames
    case car_sim::FrameRule::PrefixSearched:
      f.prefix = tf_prefix(port.ns, true);
      f.child_frame = resolve_tf(f.prefix, port.child_frame);
      break;
    // frame_name_ = tf::resolve(getParam("tf_prefix"), frameName): the header frame only
    case car_sim::FrameRule::PrefixHere:
      f.prefix = tf_prefix(port.ns, false);
      f.child_frame = port.child_frame;
      break;
    case car_sim::FrameRule::NoPrefix:
    case car_sim::FrameRule::AsWritten: f.child_frame = port.child_frame; break;
  }
  f.frame = f.header_frame(port.frame);
  return f;
}

std::string tf_prefix_param(const std::string& ns, bool searched) {
  ros::NodeHandle nh("/" + ns);
  std::string key = "tf_prefix", value;
  if (searched && !nh.searchParam("tf_prefix", key)) return value;
  nh.getParam(key, value);
  return value;
}

}  // namespace car_ros
