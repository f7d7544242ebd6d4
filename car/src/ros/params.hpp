// The node's number parameters that must be finite (~rtf, ~lockstep_timeout): one reader, one rule.
#pragma once

#include <ros/node_handle.h>

#include <cmath>
#include <string>

namespace car_ros {

// Reads a number parameter into value, fallback when it is unset (NodeHandle::param). False when the value is not
// finite (NaN, inf): the caller then refuses it or falls back, in its own words, and can print what was read.
inline bool finite_param(const ros::NodeHandle& nh, const std::string& name, double fallback, double& value) {
  nh.param(name, value, fallback);
  return std::isfinite(value);
}

}  // namespace car_ros
