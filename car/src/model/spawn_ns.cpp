// The namespace rule of gazebo_ros's spawn service, applied to a loaded model before its plug-ins resolve.
// Rules and sources: docs/COMPAT-spawn.md.
#include "car_sim/model.hpp"

#include "car_sim/plugins.hpp"

namespace car_sim {

namespace {

bool has_namespace(const PluginSpec& p) {
  for (const auto& kv : p.params)
    if (kv.first == "robotNamespace") return true;
  return false;
}

}  // namespace

void apply_robot_namespace(RobotModel* model, const std::string& robot_namespace) {
  // walkChildAddRobotNamespace runs only for a non-empty namespace and only adds where none is written.
  if (!robot_namespace.empty()) {
    for (auto& p : model->plugins)
      if (!has_namespace(p)) p.params.emplace_back("robotNamespace", robot_namespace);
    for (auto& s : model->sensors)
      for (auto& p : s.plugins)
        if (!has_namespace(p)) p.params.emplace_back("robotNamespace", robot_namespace);
  }
  // An empty <robotNamespace> stays empty: each plug-in file reads it by its own rule (plugin_robot_namespace).
}

}  // namespace car_sim
