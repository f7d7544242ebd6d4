// The wheel drives' plain maths, shared by diff_drive, skid_steer_drive and tricycle_drive: wheel speeds for a
// twist, gazebo_ros_diff_drive's wheel ramp, the wheel length rule and encoder odometry. Not a kind: shared code.
#pragma once

#include "car_sim/plugin.hpp"

namespace car_sim {

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

}  // namespace car_sim
