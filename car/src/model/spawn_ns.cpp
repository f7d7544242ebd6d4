// The namespace rule of gazebo_ros's spawn service, applied to a loaded model before its plug-ins resolve.
// Rules and sources: docs/COMPAT-spawn.md.
#include "car_sim/model.hpp"

#include <map>

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

bool namespace_rule(const std::string& filename, NamespaceRule* rule) {
  using R = NamespaceRule;
  // Each file's Load in gazebo_ros_pkgs noetic-devel, velodyne_simulator, hector_gazebo (docs/COMPAT-plugins.md).
  static const std::map<std::string, R> kRules = {
      {"libgazebo_ros_diff_drive.so", R::ModelName},
      {"libgazebo_ros_tricycle_drive.so", R::ModelName},
      {"libgazebo_ros_joint_state_publisher.so", R::ModelName},
      {"libgazebo_ros_laser.so", R::EmptyIsModel},
      {"libgazebo_ros_gpu_laser.so", R::EmptyIsModel},
      {"libgazebo_ros_camera.so", R::EmptyIsModel},
      {"libgazebo_ros_triggered_camera.so", R::EmptyIsModel},
      {"libgazebo_ros_depth_camera.so", R::EmptyIsModel},
      {"libgazebo_ros_openni_kinect.so", R::EmptyIsModel},
      {"libgazebo_ros_multicamera.so", R::EmptyIsModel},
      {"libgazebo_ros_control.so", R::AbsentIsModel},
      {"libgazebo_ros_imu_sensor.so", R::AbsentIsModel},
      {"libgazebo_ros_imu.so", R::AsWritten},
      {"libgazebo_ros_p3d.so", R::AsWritten},
      {"libgazebo_ros_f3d.so", R::AsWritten},
      {"libgazebo_ros_force.so", R::AsWritten},
      {"libgazebo_ros_ft_sensor.so", R::AsWritten},
      {"libgazebo_ros_joint_pose_trajectory.so", R::AsWritten},
      {"libgazebo_ros_skid_steer_drive.so", R::AsWritten},
      {"libgazebo_ros_planar_move.so", R::AsWritten},
      {"libgazebo_ros_hand_of_god.so", R::AsWritten},  // read and not used: TF only
      {"libgazebo_ros_range.so", R::AsWritten},
      {"libgazebo_ros_bumper.so", R::AsWritten},
      {"libgazebo_ros_block_laser.so", R::AsWritten},
      {"libgazebo_ros_velodyne_laser.so", R::AsWritten},      // absent: "/"; empty: NodeHandle("")
      {"libgazebo_ros_velodyne_gpu_laser.so", R::AsWritten},
      {"libhector_gazebo_ros_gps.so", R::AsWritten},
      {"libhector_gazebo_ros_imu.so", R::AsWritten},
      {"libhector_gazebo_ros_magnetic.so", R::AsWritten},
      {"libhector_gazebo_ros_sonar.so", R::AsWritten},
  };
  const auto it = kRules.find(filename);
  *rule = it == kRules.end() ? R::AsWritten : it->second;
  return it != kRules.end();
}

std::string plugin_robot_namespace(const PluginConfig& c, const std::string& model_name) {
  NamespaceRule rule;
  namespace_rule(c.filename, &rule);
  const bool present = c.has("robotNamespace") && !c.param("robotNamespace").from_default;
  std::string ns = present ? c.text("robotNamespace") : "";
  const bool to_model = present ? ns.empty() && (rule == NamespaceRule::ModelName || rule == NamespaceRule::EmptyIsModel)
                                : (rule == NamespaceRule::ModelName || rule == NamespaceRule::AbsentIsModel);
  if (to_model) ns = model_name;
  // "/" and "" are the global namespace; "r1/" is what NodeHandle("r1" + "/") names
  while (!ns.empty() && ns.front() == '/') ns.erase(ns.begin());
  while (!ns.empty() && ns.back() == '/') ns.pop_back();
  return ns;
}

}  // namespace car_sim
