// libgazebo_ros_planar_move.so on ROS (cmd_vel, x, y and yaw rate, through the kind's input port): odometry + TF odometryFrame -> robotBaseFrame
// out at odometryRate, under robotNamespace ("" = global, as upstream's NodeHandle("")).
#include <nav_msgs/Odometry.h>

#include "../adapter.hpp"
#include "../conversions.hpp"
#include "planar_move/planar_move.hpp"

namespace car_ros {

namespace {

class PlanarMoveAdapter : public Adapter {
 public:
  std::string setup(const car_sim::PluginInfo& p, const car_sim::RobotInfo& robot, NodeContext& node) override {
    const std::string ns = car_sim::plugin_robot_namespace(p.config, robot.name);
    // tf::resolve(tf::getPrefixParam) as upstream: tf_prefix from the plug-in's namespace (docs/COMPAT-spawn.md 4)
    const std::string prefix = tf_prefix_param(ns);
    odom_frame_ = resolve_tf(prefix, p.config.text("odometryFrame"));
    base_frame_ = resolve_tf(prefix, p.config.text("robotBaseFrame"));
    const std::string cmd = topic_in(ns, p.config.text("commandTopic"));
    const std::string odom = topic_in(ns, p.config.text("odometryTopic"));
    odom_ = node.nh().advertise<nav_msgs::Odometry>(odom, 1);
    return "command " + cmd + ", odometry " + odom + " (" + odom_frame_ + " -> " + base_frame_ + ") at " +
           p.config.text("odometryRate") + " Hz, cmdTimeout " + p.config.text("cmdTimeout") + " s";
  }

  void publish(const car_sim::Output& out, NodeContext& node) override {
    const auto& o = static_cast<const car_sim::OdometryOut&>(out);
    nav_msgs::Odometry m;
    m.header.stamp = node.stamp(o.tick);
    m.header.frame_id = odom_frame_;
    m.child_frame_id = base_frame_;
    m.pose.pose = to_pose(o.pose);
    const double cov[6] = {1e-5, 1e-5, 1e12, 1e12, 1e12, 1e-3};
    for (int i = 0; i < 6; ++i) m.pose.covariance[i * 7] = cov[i];
    m.twist.twist = to_twist(o.linear, o.angular);
    geometry_msgs::TransformStamped t;
    t.header = m.header;
    t.child_frame_id = base_frame_;
    t.transform = to_transform(o.pose);
    node.send_tf(std::move(t));
    node.publish(odom_, std::move(m));
  }

 private:
  std::string odom_frame_, base_frame_;
  ros::Publisher odom_;
};

}  // namespace

std::unique_ptr<Adapter> make_planar_move_adapter() { return std::make_unique<PlanarMoveAdapter>(); }

}  // namespace car_ros
