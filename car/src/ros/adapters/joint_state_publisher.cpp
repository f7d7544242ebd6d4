// libgazebo_ros_joint_state_publisher.so on ROS: sensor_msgs/JointState on <robotNamespace>/joint_states, where an
// absent or empty robotNamespace means the model's name (upstream), effort left empty.
#include <sensor_msgs/JointState.h>

#include "../adapter.hpp"
#include "../conversions.hpp"
#include "joint_state_publisher/joint_state_publisher.hpp"

namespace car_ros {

namespace {

class JointStatePublisherAdapter : public Adapter {
 public:
  std::string setup(const car_sim::PluginInfo& p, const car_sim::RobotInfo& robot, NodeContext& node) override {
    const std::string ns = car_sim::plugin_robot_namespace(p.config, robot.name);
    pub_ = node.nh().advertise<sensor_msgs::JointState>(topic_in(ns, "joint_states"), 1000);
    return pub_.getTopic() + " (" + p.config.text("jointName") + ") at " + p.config.text("updateRate") + " Hz";
  }

  bool listened() const override { return pub_.getNumSubscribers() > 0; }

  void publish(const car_sim::Output& out, NodeContext& node) override {
    const auto& o = static_cast<const car_sim::JointStatesOut&>(out);
    sensor_msgs::JointState m;
    m.header.stamp = node.stamp(o.tick);
    for (const auto& j : o.joints) {
      m.name.push_back(j.name);
      m.position.push_back(j.position);
      m.velocity.push_back(j.velocity);
    }
    node.publish(pub_, std::move(m));
  }

 private:
  ros::Publisher pub_;
};

}  // namespace

std::unique_ptr<Adapter> make_joint_state_publisher_adapter() { return std::make_unique<JointStatePublisherAdapter>(); }

}  // namespace car_ros
