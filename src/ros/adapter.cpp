// What every adapter shares.
#include "adapter.hpp"

namespace car_ros {

std::string plugin_namespace(const car_sim::PluginConfig& c, const std::string& model_name) {
  return car_sim::plugin_robot_namespace(c, model_name);
}

}  // namespace car_ros
