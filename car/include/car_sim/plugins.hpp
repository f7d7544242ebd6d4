// Plug-in configuration: every key a plug-in kind reads, with its default and unit, resolved from the model's
// <gazebo> blocks per gazebo_ros (Noetic) behaviour. The schemas live with their kinds (src/plugins/<kind>/);
// this header is what the loader, the model check and the skins see. No ROS headers.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "car_sim/model.hpp"

namespace car_sim {

// Text: as written. Frame: text with leading '/' removed (tf2 frame names). Number: a finite decimal.
// Integer: a whole number. Flag: true/false/1/0 in any case, stored as "true"/"false".
enum class ParamType { Text, Frame, Number, Integer, Flag };

// One key of a plug-in's schema.
struct ParamDef {
  const char* key;
  ParamType type;
  const char* default_value;
  const char* unit;  // "" when dimensionless
  // [unit] stated limits of a Number or Integer key: a value outside is a load error naming the key and the limit,
  // raised before any instance allocates from it
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
};

// A key with the value it resolved to.
struct ResolvedParam {
  std::string key;
  std::string value;   // normalised text: numbers as written, flags as "true"/"false"
  std::string unit;
  bool from_default = false;
};

// One configured plug-in, robot-level or inside a sensor, with every schema key resolved.
struct PluginConfig {
  std::string kind;        // the kind's registry name, e.g. "diff_drive", "laser"
  std::string name;        // <plugin name>
  std::string filename;    // <plugin filename>
  std::string sensor;      // sensor name, "" for robot-level plug-ins
  std::string sensor_type; // sensor type, "" for robot-level plug-ins
  std::string link;        // the link it measures or acts on ("" when the whole model)
  Eigen::Isometry3d sensor_pose = Eigen::Isometry3d::Identity();  // sensor frame in the link frame
  std::vector<ResolvedParam> params;
  ParamList raw;  // the <plugin>'s elements as written, for a kind that reads its own keys (any_keys)

  const ResolvedParam& param(const std::string& key) const;  // throws std::out_of_range
  bool has(const std::string& key) const;
  const std::string& text(const std::string& key) const;
  double number(const std::string& key) const;
  bool flag(const std::string& key) const;
};

struct ModelConfig {
  std::vector<PluginConfig> plugins;
  std::vector<Diagnostic> diagnostics;  // unknown plug-ins, unknown keys, ignored keys, quirks
};

// Parses "true/false/1/0" in any case. Returns false when the text is none of those.
bool parse_flag(const std::string& text, bool* value);

// Resolves every plug-in of a model through the registry. Throws LoadError naming the plug-in (or sensor) and key
// for bad values: a missing wheel joint, zero samples, min_angle > max_angle, near >= far, an unknown image
// format, ...
ModelConfig resolve_plugins(const RobotModel& model);
// Resolves one robot-level plug-in (e.g. one the ROS node attaches); throws LoadError like resolve_plugins.
PluginConfig resolve_plugin(const RobotModel& model, const PluginSpec& spec, std::vector<Diagnostic>* diagnostics);

// The schema of a plug-in kind (sensor keys first, then the plug-in's own). Empty for unknown kinds.
const std::vector<ParamDef>& plugin_schema(const std::string& kind);

// The kind for a plug-in file name ("libgazebo_ros_diff_drive.so" -> "diff_drive"), "" when unknown.
std::string plugin_kind(const std::string& filename);

// How a plug-in file reads <robotNamespace>, as its upstream Load does (docs/COMPAT-plugins.md "Namespaces"): a
// field of its kind (PluginKind::namespace_rule). The spawn service's injection (apply_robot_namespace) comes
// first; this reads what it left.
enum class NamespaceRule {
  AsWritten,      // HasElement ? value : "": absent or empty -> global
  ModelName,      // GazeboRos (model plug-ins): absent or empty -> the model's name
  EmptyIsModel,   // GetRobotNamespace (sensor plug-ins): absent -> global, empty -> the model's name
  AbsentIsModel,  // gazebo_ros_control, imu_sensor: absent -> the model's name, empty -> global
};
// The rule of a plug-in file, from its kind; false (and AsWritten) for a file no kind serves.
bool namespace_rule(const std::string& filename, NamespaceRule* rule);
// The namespace a plug-in's topics go under, by its file's rule: leading and trailing '/' removed, "" = global
// ("/" is global whatever the rule; "r1", "/r1" and "/r1/" are /r1).
std::string plugin_robot_namespace(const PluginConfig& c, const std::string& model_name);

}  // namespace car_sim
