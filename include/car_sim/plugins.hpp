// Plug-in and sensor configuration: every key the simulator reads, with its default and unit, resolved from
// the URDF's <gazebo> blocks per gazebo_ros (Noetic) behaviour. No ROS headers.
#pragma once

#include <string>
#include <vector>

#include "car_sim/model.hpp"

namespace car_sim {

enum class ParamType { Text, Number, Integer, Flag };

// One key of a plug-in's schema.
struct ParamDef {
  const char* key;
  ParamType type;
  const char* default_value;
  const char* unit;  // "" when dimensionless
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
  std::string kind;        // "diff_drive", "laser", "openni_kinect", "camera", "imu"
  std::string name;        // <plugin name>
  std::string filename;    // <plugin filename>
  std::string sensor;      // sensor name, "" for robot-level plug-ins
  std::string sensor_type; // sensor type, "" for robot-level plug-ins
  std::string link;        // sensor's link, or the imu body
  std::vector<ResolvedParam> params;

  const ResolvedParam& param(const std::string& key) const;  // throws std::out_of_range
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

// Resolves every plug-in of a model. Throws LoadError naming the plug-in (or sensor) and key for bad values:
// a missing wheel joint, zero samples, min_angle > max_angle, near >= far, an unknown image format, ...
ModelConfig resolve_plugins(const RobotModel& model);

// The schema of a plug-in kind (sensor keys first, then the plug-in's own). Empty for unknown kinds.
const std::vector<ParamDef>& plugin_schema(const std::string& kind);

// The kind for a plug-in file name ("libgazebo_ros_diff_drive.so" -> "diff_drive"), "" when unknown.
std::string plugin_kind(const std::string& filename);

}  // namespace car_sim
