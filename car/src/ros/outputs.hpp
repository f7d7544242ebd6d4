// The output half of the ROS bridge for the kinds whose outputs have ports: one converter per sample type
// (Odometry -> nav_msgs/Odometry and its TF, JointStates -> sensor_msgs/JointState, JointTransforms -> TF; the
// sensors' LaserScan, PointCloud, LidarCloud -> PointCloud2, Range, Imu, NavSatFix, Vector3 -> Vector3Stamped,
// MagneticField, Wrench -> WrenchStamped, Contacts -> gazebo_msgs/ContactsState, Transform -> TF; ControllerState
// -> control_msgs/JointControllerState, TrajectoryState -> JointTrajectoryControllerState, GoalResult -> the action
// server of inputs.cpp; the camera types in outputs_image.cpp). Frames get the tf_prefix of the port's namespace
// (gazebo_ros resolveTF) where the port asks for it. Names no plug-in kind.
#pragma once

#include <ros/ros.h>
#include <std_msgs/Header.h>

#include <memory>
#include <string>
#include <vector>

#include "context.hpp"

namespace car_ros {

class OutputPorts {
 public:
  // Publishers for every output port of one plug-in instance; returns what it offers, for the log line. Called
  // again when the instance's ports change: a port of the same name, type and topic keeps its publisher.
  std::string setup(const car_sim::PluginInfo& plugin, const car_sim::RobotInfo& robot, NodeContext& node);
  bool empty() const { return ports_.empty(); }
  // Someone listens to one of its topics.
  bool listened() const;
  // The parts of the output its subscribed ports take (Plugin::set_parts; all bits: every part).
  uint32_t parts() const;
  // One output of the instance, on every port (or the one its `port` names), in the ports' order; its ownership, for the messages serialised
  // straight from its arrays on the publishing thread (the camera types), which keep it until they are sent.
  void publish(std::shared_ptr<const car_sim::Output> out, NodeContext& node);

 private:
  struct Port {
    car_sim::OutputPort port;
    ros::Publisher pub;
    std::string prefix;              // tf_prefix of the port's namespace ("" = none)
    std::string frame, child_frame;  // as published
    // a port with a min_period (range's throttle) or a CameraInfo port's period: when its next message is due
    car_sim::PeriodGate gate;
    // ---- cameras
  };
  // A message with the port's header, on its publisher.
  template <class M>
  static void publish(const Port& p, M msg, const std_msgs::Header& header, NodeContext& node) {
    msg.header = header;
    node.publish(p.pub, std::move(msg));
  }
  // ---- cameras (outputs_image.cpp): the publisher of a port of a camera sample type, with the log's words; one
  // frame's message on it
  std::string setup_image(Port& p, NodeContext& node);
  void publish_image(Port& p, const std::shared_ptr<const car_sim::Output>& out, const ros::Time& stamp,
                     NodeContext& node);
  std::vector<Port> ports_;
  const car_sim::RobotModel* model_ = nullptr;
};

}  // namespace car_ros
