// libgazebo_ros_diff_drive.so: configuration and the plug-in kind (the drives' maths: common/drive.hpp).
#pragma once

#include <string>

#include "car_sim/drive.hpp"
#include "car_sim/plugin.hpp"
#include "../common/drive.hpp"

namespace car_sim {

struct DiffDriveConfig {
  std::string plugin_name;
  std::string robot_namespace;   // resolved: "" = global names, else "ns" (no leading slash)
  std::string command_topic = "cmd_vel";
  std::string odometry_topic = "odom";
  std::string odometry_frame = "odom";
  std::string robot_base_frame = "base_footprint";
  double wheel_separation = 0.34;   // [m]
  double wheel_diameter = 0.15;     // [m]
  double wheel_torque = 5.0;        // [N m] motor cap
  double wheel_acceleration = 0.0;  // [m/s^2] of wheel surface speed; 0 = unlimited
  double update_rate = 100.0;       // [Hz]; 0 = every step
  bool encoder_odometry = false;    // odometrySource encoder (else world)
  bool publish_tf = true;           // false: no /odom at all (upstream quirk)
  bool publish_odom_tf = true;
  bool publish_wheel_tf = false;
  bool publish_wheel_joint_state = false;
  std::string left_joint = "left_joint";
  std::string right_joint = "right_joint";
  std::string ros_debug_level = "na";

  // From a resolved plug-in; model_name fills an absent or empty robotNamespace, "/" means global.
  static DiffDriveConfig from(const PluginConfig& c, const std::string& model_name);
};

const PluginKind& diff_drive_kind();

}  // namespace car_sim
