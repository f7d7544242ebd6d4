// What every base-drive plug-in kind shares (diff drive, skid steer, planar move, tricycle): it takes a body
// twist command and reports odometry. The world routes set_cmd_vel and take_odometry through these, so neither
// the world nor its skins name a kind. No ROS headers.
#pragma once

#include <Eigen/Geometry>

#include "car_sim/plugin.hpp"
#include "car_sim/state.hpp"

namespace car_sim {

// A plug-in that drives the robot's base from a twist command (cmd_vel).
class TwistDrive {
 public:
  virtual ~TwistDrive() = default;
  // Takes effect at the plug-in's next update; holds until the next command (no timeout, as upstream).
  virtual void set_twist(const Twist& cmd) = 0;
};

// One odometry message of a drive plug-in, produced at its update rate.
struct OdometryOut : Output {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // base frame in the odometry frame
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();        // [m/s], base frame
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();       // [rad/s], base frame
  std::vector<JointState> joints;                          // the driven wheel joints at that time
  std::vector<double> efforts;  // [N m] or [N], one per joint, for a port with_effort; empty: none
  void visit(FieldVisitor& v) const override;
  void samples(SampleList& list) const override {
    list.add(OdometrySample{pose, linear, angular, std::nullopt});
    list.add(JointStatesSample{&joints, efforts.empty() ? nullptr : &efforts});
  }
};

// A drive's odometry port: frames from the schema keys odometryFrame and robotBaseFrame, under the plug-in's
// namespace; pose covariance (x, y, 1e12, 1e12, 1e12, yaw) as the gazebo_ros drives write it.
OutputPort odometry_port(const PluginConfig& c, const std::string& robot, const std::string& topic_key, uint32_t queue,
                         TfOrder tf, double cov_x = 1e-5, double cov_y = 1e-5, double cov_yaw = 1e-3);
// The wheel TF a drive may add (its wheel joint states: joint_states_port, plugin.hpp).
OutputPort wheel_tf_port(const PluginConfig& c, const std::string& robot);

}  // namespace car_sim
