// libgazebo_ros_skid_steer_drive.so on ROS (cmd_vel, linear.x and angular.z, through the kind's input port): odometry out at updateRate with
// covariance_x/_y/_yaw on pose and twist; TF odometryFrame -> robotBaseFrame only with broadcastTF.
#include <nav_msgs/Odometry.h>

#include "../adapter.hpp"
#include "../conversions.hpp"
#include "skid_steer_drive/skid_steer_drive.hpp"

namespace car_ros {

namespace {

class SkidSteerAdapter : public Adapter {
 public:
  std::string setup(const car_sim::PluginInfo& p, const car_sim::RobotInfo& robot, NodeContext& node) override {
    const std::string ns = car_sim::plugin_robot_namespace(p.config, robot.name);
    // tf::resolve(tf::getPrefixParam) as upstream: tf_prefix from the plug-in's namespace (docs/COMPAT-spawn.md 4)
    const std::string prefix = tf_prefix_param(ns);
    odom_frame_ = resolve_tf(prefix, p.config.text("odometryFrame"));
    base_frame_ = resolve_tf(prefix, p.config.text("robotBaseFrame"));
    broadcast_tf_ = p.config.flag("broadcastTF");
    cov_[0] = p.config.number("covariance_x");
    cov_[1] = p.config.number("covariance_y");
    cov_[2] = cov_[3] = cov_[4] = 1e12;
    cov_[5] = p.config.number("covariance_yaw");
    const std::string cmd = topic_in(ns, p.config.text("commandTopic"));
    const std::string odom = topic_in(ns, p.config.text("odometryTopic"));
    odom_ = node.nh().advertise<nav_msgs::Odometry>(odom, 1);
    return "command " + cmd + ", odometry " + odom + " (" + odom_frame_ + " -> " + base_frame_ + ") at " +
           p.config.text("updateRate") + " Hz, separation " + p.config.text("wheelSeparation") + " m, diameter " +
           p.config.text("wheelDiameter") + " m, torque " + p.config.text("torque") + " N m" +
           (broadcast_tf_ ? ", TF" : "");
  }

  void publish(const car_sim::Output& out, NodeContext& node) override {
    const auto& o = static_cast<const car_sim::OdometryOut&>(out);
    nav_msgs::Odometry m;
    m.header.stamp = node.stamp(o.tick);
    m.header.frame_id = odom_frame_;
    m.child_frame_id = base_frame_;
    m.pose.pose = to_pose(o.pose);
    m.twist.twist = to_twist(o.linear, o.angular);
    for (int i = 0; i < 6; ++i) m.pose.covariance[i * 7] = m.twist.covariance[i * 7] = cov_[i];
    if (broadcast_tf_) {
      geometry_msgs::TransformStamped t;
      t.header = m.header;
      t.child_frame_id = base_frame_;
      t.transform = to_transform(o.pose);
      node.send_tf(std::move(t));
    }
    node.publish(odom_, std::move(m));
  }

 private:
  std::string odom_frame_, base_frame_;
  bool broadcast_tf_ = false;
  double cov_[6] = {0, 0, 0, 0, 0, 0};
  ros::Publisher odom_;
};

}  // namespace

std::unique_ptr<Adapter> make_skid_steer_drive_adapter() { return std::make_unique<SkidSteerAdapter>(); }

}  // namespace car_ros
