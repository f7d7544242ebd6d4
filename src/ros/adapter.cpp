// What every adapter shares.
#include "adapter.hpp"

namespace car_ros {

std::string plugin_namespace(const car_sim::PluginConfig& c) {
  std::string ns = c.has("robotNamespace") ? c.text("robotNamespace") : "";
  while (!ns.empty() && ns.front() == '/') ns.erase(ns.begin());
  while (!ns.empty() && ns.back() == '/') ns.pop_back();
  return ns;
}

}  // namespace car_ros
