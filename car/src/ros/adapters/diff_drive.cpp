// libgazebo_ros_diff_drive.so on ROS (cmd_vel comes in through the kind's input port, inputs.cpp): odom + TF odom -> base out, wheel joint states and wheel TF
// when asked; rosDebugLevel sets the node's logger level, as upstream.
#include <nav_msgs/Odometry.h>
#include <sensor_msgs/JointState.h>

#include <map>

#include "../adapter.hpp"
#include "../conversions.hpp"
#include "diff_drive/diff_drive.hpp"

namespace car_ros {

namespace {

class DiffDriveAdapter : public Adapter {
 public:
  std::string setup(const car_sim::PluginInfo& p, const car_sim::RobotInfo& robot, NodeContext& node) override {
    cfg_ = car_sim::DiffDriveConfig::from(p.config, robot.name);
    model_ = &robot.model;
    // GazeboRos::resolveTF: tf_prefix from the plug-in's namespace (docs/COMPAT-spawn.md rule 4)
    prefix_ = tf_prefix_param(car_sim::plugin_robot_namespace(p.config, robot.name));
    odom_frame_ = resolve_tf(prefix_, cfg_.odometry_frame);
    base_frame_ = resolve_tf(prefix_, cfg_.robot_base_frame);
    const std::string cmd = topic_in(cfg_.robot_namespace, cfg_.command_topic);
    const std::string odom = topic_in(cfg_.robot_namespace, cfg_.odometry_topic);
    if (cfg_.publish_tf)
      odom_ = node.nh().advertise<nav_msgs::Odometry>(odom, 100);
    else
      ROS_WARN("car: %s: publishTf is false, so (like gazebo_ros) no %s is published at all", cfg_.plugin_name.c_str(),
               odom.c_str());
    if (cfg_.publish_wheel_joint_state)
      wheel_joint_states_ = node.nh().advertise<sensor_msgs::JointState>(topic_in(cfg_.robot_namespace, "joint_states"), 10);
    set_debug_level();
    char line[1024];
    std::snprintf(line, sizeof line,
                  "command %s, odometry %s (%s) %s -> %s at %g Hz, wheels %s/%s, separation %g m, diameter %g m, "
                  "torque %g N m, acceleration %g m/s^2%s%s%s",
                  cmd.c_str(), odom.c_str(), cfg_.encoder_odometry ? "encoder" : "world",
                  odom_frame_.c_str(), base_frame_.c_str(), cfg_.update_rate,
                  cfg_.left_joint.c_str(), cfg_.right_joint.c_str(), cfg_.wheel_separation, cfg_.wheel_diameter,
                  cfg_.wheel_torque, cfg_.wheel_acceleration, cfg_.publish_odom_tf ? ", odom TF" : "",
                  cfg_.publish_wheel_tf ? ", wheel TF" : "", cfg_.publish_wheel_joint_state ? ", wheel joint states" : "");
    return line;
  }

  void publish(const car_sim::Output& out, NodeContext& node) override {
    const auto& o = static_cast<const car_sim::OdometryOut&>(out);
    const ros::Time stamp = node.stamp(o.tick);
    nav_msgs::Odometry msg;
    msg.header.stamp = stamp;
    msg.header.frame_id = odom_frame_;
    msg.child_frame_id = base_frame_;
    msg.pose.pose = to_pose(o.pose);
    const double cov[6] = {1e-5, 1e-5, 1e12, 1e12, 1e12, 1e-3};
    for (int i = 0; i < 6; ++i) msg.pose.covariance[i * 7] = cov[i];
    msg.twist.twist = to_twist(o.linear, o.angular);
    // the transform is made before the odometry is moved to the publishing thread; both leave in that order
    geometry_msgs::TransformStamped t;
    if (cfg_.publish_odom_tf) {
      t.header = msg.header;
      t.child_frame_id = msg.child_frame_id;
      t.transform = to_transform(o.pose);
    }
    node.publish(odom_, std::move(msg));
    if (cfg_.publish_odom_tf) node.send_tf(std::move(t));
    if (cfg_.publish_wheel_joint_state) {
      sensor_msgs::JointState js;
      js.header.stamp = stamp;
      js.name.reserve(o.joints.size());
      js.position.reserve(o.joints.size());
      js.velocity.reserve(o.joints.size());
      for (const auto& j : o.joints) {
        js.name.push_back(j.name);
        js.position.push_back(j.position);
        js.velocity.push_back(j.velocity);
      }
      node.publish(wheel_joint_states_, std::move(js));
    }
    if (cfg_.publish_wheel_tf) {
      // fix: each wheel relative to its parent link (upstream publishes it relative to the odometry frame)
      for (const auto& j : o.joints) {
        const car_sim::Joint* joint = model_->find_joint(j.name);
        geometry_msgs::TransformStamped t;
        t.header.stamp = stamp;
        t.header.frame_id = resolve_tf(prefix_, joint->parent);
        t.child_frame_id = resolve_tf(prefix_, joint->child);
        Eigen::Isometry3d T = joint->origin;
        T.rotate(Eigen::AngleAxisd(j.position, joint->axis));
        t.transform = to_transform(T);
        node.send_tf(std::move(t));
      }
    }
  }

 private:
  // rosDebugLevel (Debug, Info, Warn, Error, Fatal; "na" leaves it) sets this node's logger level, as upstream.
  void set_debug_level() {
    static const std::map<std::string, ros::console::levels::Level> levels = {
        {"debug", ros::console::levels::Debug}, {"info", ros::console::levels::Info},
        {"warn", ros::console::levels::Warn},   {"error", ros::console::levels::Error},
        {"fatal", ros::console::levels::Fatal}};
    std::string l = cfg_.ros_debug_level;
    for (auto& c : l) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const auto it = levels.find(l);
    if (it == levels.end()) return;
    if (ros::console::set_logger_level(ROSCONSOLE_DEFAULT_NAME, it->second)) ros::console::notifyLoggerLevelsChanged();
  }

  car_sim::DiffDriveConfig cfg_;
  std::string odom_frame_, base_frame_;  // the odometry's frame_id and child_frame_id, as published
  std::string prefix_;                   // tf_prefix ("" = none)
  const car_sim::RobotModel* model_ = nullptr;
  ros::Publisher odom_, wheel_joint_states_;
};

}  // namespace

std::unique_ptr<Adapter> make_diff_drive_adapter() { return std::make_unique<DiffDriveAdapter>(); }

}  // namespace car_ros
