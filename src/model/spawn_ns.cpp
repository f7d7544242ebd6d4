// The namespace rule of gazebo_ros's spawn service, applied to a loaded model before its plug-ins resolve.
// Rules and sources: docs/COMPAT-spawn.md.
#include "car_sim/model.hpp"

namespace car_sim {

namespace {

bool has_namespace(const PluginSpec& p) {
  for (const auto& kv : p.params)
    if (kv.first == "robotNamespace") return true;
  return false;
}

}  // namespace

void apply_robot_namespace(RobotModel* model, const std::string& robot_namespace, const std::string& model_name) {
  // walkChildAddRobotNamespace runs only for a non-empty namespace and only adds where none is written.
  if (!robot_namespace.empty()) {
    for (auto& p : model->plugins)
      if (!has_namespace(p)) p.params.emplace_back("robotNamespace", robot_namespace);
    for (auto& s : model->sensors)
      for (auto& p : s.plugins)
        if (!has_namespace(p)) p.params.emplace_back("robotNamespace", robot_namespace);
  }
  // GetRobotNamespace (sensor plug-ins): a present but empty <robotNamespace> is the model's name.
  for (auto& s : model->sensors)
    for (auto& p : s.plugins)
      for (auto& kv : p.params)
        if (kv.first == "robotNamespace" && kv.second.empty()) kv.second = model_name;
}

}  // namespace car_sim
