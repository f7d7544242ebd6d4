// libgazebo_ros_planar_move.so on ROS: cmd_vel (x, y, yaw rate) in, odometry + TF odometryFrame -> robotBaseFrame
// out at odometryRate, under robotNamespace ("" = global, as upstream's NodeHandle("")).
#include <geometry_msgs/Twist.h>
#include <nav_msgs/Odometry.h>

#include <chrono>
#include <cmath>

#include "../adapter.hpp"
#include "../conversions.hpp"
#include "planar_move/planar_move.hpp"

namespace car_ros {

namespace {

class PlanarMoveAdapter : public Adapter {
 public:
  std::string setup(const car_sim::PluginInfo& p, const car_sim::RobotInfo& robot, NodeContext& node) override {
    robot_ = robot.name;
    drive_ = dynamic_cast<car_sim::TwistDrive*>(node.world().plugin(robot.name, p.config.name));
    const std::string ns = car_sim::plugin_robot_namespace(p.config, robot.name);
    // tf::resolve(tf::getPrefixParam) as upstream: tf_prefix from the plug-in's namespace (docs/COMPAT-spawn.md 4)
    const std::string prefix = tf_prefix_param(ns);
    odom_frame_ = resolve_tf(prefix, p.config.text("odometryFrame"));
    base_frame_ = resolve_tf(prefix, p.config.text("robotBaseFrame"));
    const std::string cmd = topic_in(ns, p.config.text("commandTopic"));
    const std::string odom = topic_in(ns, p.config.text("odometryTopic"));
    cmd_vel_ = node.nh().subscribe<geometry_msgs::Twist>(
        cmd, 1, [this](const geometry_msgs::Twist::ConstPtr& m) { on_cmd_vel(*m); });
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
  void on_cmd_vel(const geometry_msgs::Twist& m) {
    if (!std::isfinite(m.linear.x) || !std::isfinite(m.linear.y) || !std::isfinite(m.angular.z)) {
      // throttled in wall time: sim time stands still while paused
      const auto now = std::chrono::steady_clock::now();
      if (last_warning_.time_since_epoch().count() == 0 || now - last_warning_ > std::chrono::seconds(1)) {
        ROS_WARN("car: %s: rejected a cmd_vel with a non-finite value", robot_.c_str());
        last_warning_ = now;
      }
      return;
    }
    car_sim::Twist t;
    t.linear = Eigen::Vector3d(m.linear.x, m.linear.y, 0.0);
    t.angular.z() = m.angular.z;
    if (drive_) drive_->set_twist(t);
  }

  std::string robot_, odom_frame_, base_frame_;
  car_sim::TwistDrive* drive_ = nullptr;
  ros::Subscriber cmd_vel_;
  ros::Publisher odom_;
  std::chrono::steady_clock::time_point last_warning_;
};

}  // namespace

std::unique_ptr<Adapter> make_planar_move_adapter() { return std::make_unique<PlanarMoveAdapter>(); }

}  // namespace car_ros
