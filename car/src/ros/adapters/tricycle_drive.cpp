// libgazebo_ros_tricycle_drive.so on ROS (cmd_vel, linear.x speed and angular.z steering angle, through the kind's
// input port): odometry and TF
// odometryFrame -> robotBaseFrame out at updateRate; wheel joint states and wheel TF when asked. robotNamespace
// absent or empty means the model's name (upstream's GazeboRos helper).
#include <nav_msgs/Odometry.h>
#include <sensor_msgs/JointState.h>

#include "../adapter.hpp"
#include "../conversions.hpp"
#include "tricycle_drive/tricycle_drive.hpp"

namespace car_ros {

namespace {

class TricycleAdapter : public Adapter {
 public:
  std::string setup(const car_sim::PluginInfo& p, const car_sim::RobotInfo& robot, NodeContext& node) override {
    model_ = &robot.model;
    const std::string ns = car_sim::plugin_robot_namespace(p.config, robot.name);
    // tf::resolve(tf::getPrefixParam) as upstream: tf_prefix from the plug-in's namespace (docs/COMPAT-spawn.md 4)
    prefix_ = tf_prefix_param(ns);
    odom_frame_ = resolve_tf(prefix_, p.config.text("odometryFrame"));
    base_frame_ = resolve_tf(prefix_, p.config.text("robotBaseFrame"));
    wheel_tf_ = p.config.flag("publishWheelTF");
    const std::string cmd = topic_in(ns, p.config.text("commandTopic"));
    const std::string odom = topic_in(ns, p.config.text("odometryTopic"));
    odom_ = node.nh().advertise<nav_msgs::Odometry>(odom, 1);
    if (p.config.flag("publishWheelJointState"))
      joint_states_ = node.nh().advertise<sensor_msgs::JointState>(topic_in(ns, "joint_states"), 1000);
    return "command " + cmd + " (angular.z = steering angle), odometry " + odom + " (" + p.config.text("odometrySource") +
           ") " + odom_frame_ + " -> " + base_frame_ + " at " + p.config.text("updateRate") + " Hz";
  }

  void publish(const car_sim::Output& out, NodeContext& node) override {
    const auto& o = static_cast<const car_sim::OdometryOut&>(out);
    const ros::Time stamp = node.stamp(o.tick);
    nav_msgs::Odometry m;
    m.header.stamp = stamp;
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
    if (joint_states_) {
      sensor_msgs::JointState js;
      js.header.stamp = stamp;
      for (const auto& j : o.joints) {
        js.name.push_back(j.name);
        js.position.push_back(j.position);
        js.velocity.push_back(j.velocity);
      }
      node.publish(joint_states_, std::move(js));
    }
    if (wheel_tf_) {
      // fix: the child link's frame relative to its parent link (upstream names the child frame after the joint)
      for (const auto& j : o.joints) {
        const car_sim::Joint* joint = model_->find_joint(j.name);
        geometry_msgs::TransformStamped w;
        w.header.stamp = stamp;
        w.header.frame_id = resolve_tf(prefix_, joint->parent);
        w.child_frame_id = resolve_tf(prefix_, joint->child);
        Eigen::Isometry3d T = joint->origin;
        T.rotate(Eigen::AngleAxisd(j.position, joint->axis));
        w.transform = to_transform(T);
        node.send_tf(std::move(w));
      }
    }
  }

 private:
  const car_sim::RobotModel* model_ = nullptr;
  std::string odom_frame_, base_frame_;
  std::string prefix_;  // tf_prefix ("" = none)
  bool wheel_tf_ = false;
  ros::Publisher odom_, joint_states_;
};

}  // namespace

std::unique_ptr<Adapter> make_tricycle_drive_adapter() { return std::make_unique<TricycleAdapter>(); }

}  // namespace car_ros
