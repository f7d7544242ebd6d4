// libgazebo_ros_diff_drive.so: configuration, the plain maths of the controller, and the plug-in kind.
#pragma once

#include <string>

#include "car_sim/drive.hpp"
#include "car_sim/plugin.hpp"

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

// Wheel surface speeds [m/s] for a body twist: left = v - w sep/2, right = v + w sep/2.
void wheel_speeds(double v, double w, double separation, double* left, double* right);

// gazebo_ros_diff_drive's wheel ramp (UpdateChild, noetic-devel; docs/COMPAT-plugins.md "the update and the wheel
// ramp"), left and right [m/s] of wheel surface speed. Each update: when the acceleration is 0 or either wheel's
// current speed is within 0.01 m/s of its target, both motors get their targets and the commanded speeds stay as
// they were; otherwise each commanded speed moves by the clamp of (target - current) to +-accel * since, and the
// motors get those. The commanded speeds start at 0.
struct WheelRamp {
  double instr[2] = {0.0, 0.0};  // [m/s] commanded speeds, kept between updates (wheel_speed_instr_)

  // target, current [m/s]; accel [m/s^2]; since [s] seconds_since_last_update. Writes the motors' speeds to out.
  void update(const double target[2], const double current[2], double accel, double since, double out[2]);
};

// The drives' rule for a wheel length key [m] (separation, diameter): 0 is refused (the drive divides by it); a
// negative one is what Gazebo 11 loads too (the wheels turn the other way), so a warning (docs/COMPAT-validation.md).
void check_wheel_length(ResolveContext& ctx, const char* key);

// Planar pose integrated from wheel travel, as the plug-in's encoder odometry does.
struct EncoderOdometry {
  double x = 0.0, y = 0.0, theta = 0.0;  // [m], [m], [rad], odometry frame
  double v = 0.0, w = 0.0;               // [m/s], [rad/s], last step

  // sl, sr: wheel travel [m] during dt [s]. Keeps the sign of v when reversing (fix of upstream's |v|).
  void integrate(double sl, double sr, double separation, double dt);
};

const PluginKind& diff_drive_kind();

}  // namespace car_sim
