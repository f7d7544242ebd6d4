#include "car_sim/diff_drive.hpp"

#include <algorithm>
#include <cmath>

namespace car_sim {

DiffDriveConfig DiffDriveConfig::from(const PluginConfig& c, const std::string& model_name) {
  DiffDriveConfig d;
  d.plugin_name = c.name;
  const ResolvedParam& ns = c.param("robotNamespace");
  if (ns.from_default || ns.value.empty()) {
    d.robot_namespace = model_name;
  } else {
    std::string s = ns.value;
    while (!s.empty() && s.front() == '/') s.erase(s.begin());
    while (!s.empty() && s.back() == '/') s.pop_back();
    d.robot_namespace = s;  // "/" -> "" (global)
  }
  d.command_topic = c.text("commandTopic");
  d.odometry_topic = c.text("odometryTopic");
  d.odometry_frame = c.text("odometryFrame");
  d.robot_base_frame = c.text("robotBaseFrame");
  d.wheel_separation = c.number("wheelSeparation");
  d.wheel_diameter = c.number("wheelDiameter");
  d.wheel_torque = c.number("wheelTorque");
  d.wheel_acceleration = c.number("wheelAcceleration");
  d.update_rate = c.number("updateRate");
  d.encoder_odometry = c.text("odometrySource") == "encoder";
  d.publish_tf = c.flag("publishTf");
  d.publish_odom_tf = c.flag("publishOdomTF");
  d.publish_wheel_tf = c.flag("publishWheelTF");
  d.publish_wheel_joint_state = c.flag("publishWheelJointState");
  d.left_joint = c.text("leftJoint");
  d.right_joint = c.text("rightJoint");
  d.ros_debug_level = c.text("rosDebugLevel");
  return d;
}

void wheel_speeds(double v, double w, double separation, double* left, double* right) {
  *left = v - w * separation / 2.0;
  *right = v + w * separation / 2.0;
}

double rate_limit(double current, double target, double max_step) {
  if (max_step <= 0.0) return target;
  return current + std::clamp(target - current, -max_step, max_step);
}

void EncoderOdometry::integrate(double sl, double sr, double separation, double dt) {
  const double ssum = sl + sr;
  const double sdiff = sr - sl;
  // midpoint heading over the step (Siegwart, Autonomous Mobile Robots, 2011, p. 337)
  const double heading = theta + sdiff / (2.0 * separation);
  x += ssum / 2.0 * std::cos(heading);
  y += ssum / 2.0 * std::sin(heading);
  theta += sdiff / separation;
  if (dt > 0.0) {
    v = ssum / 2.0 / dt;
    w = sdiff / separation / dt;
  }
}

}  // namespace car_sim
