// What every part of the bridge shares.
#include "context.hpp"

namespace car_ros {

std::string tf_prefix_param(const std::string& ns) {
  ros::NodeHandle nh("/" + ns);
  std::string key, value;
  if (nh.searchParam("tf_prefix", key)) nh.getParam(key, value);
  return value;
}

std::string tf_prefix_here(const std::string& ns) {
  std::string value;
  ros::NodeHandle("/" + ns).getParam("tf_prefix", value);
  return value;
}

}  // namespace car_ros
