// libgazebo_ros_force.so on ROS: geometry_msgs/Wrench on topicName under robotNamespace (queue 1); a message with a
// non-finite value is dropped with a warning.
#include <geometry_msgs/Wrench.h>

#include <cmath>

#include "../adapter.hpp"
#include "../conversions.hpp"
#include "force/force.hpp"

namespace car_ros {

namespace {

class ForceAdapter : public Adapter {
 public:
  std::string setup(const car_sim::PluginInfo& p, const car_sim::RobotInfo& robot, NodeContext& node) override {
    name_ = p.config.name;
    target_ = dynamic_cast<car_sim::WrenchCommand*>(node.world().plugin(robot.name, p.config.name));
    const std::string topic = topic_in(car_sim::plugin_robot_namespace(p.config, robot.name), p.config.text("topicName"));
    sub_ = node.nh().subscribe<geometry_msgs::Wrench>(topic, 1, [this](const geometry_msgs::Wrench::ConstPtr& m) {
      car_sim::Wrench w;
      w.force = Eigen::Vector3d(m->force.x, m->force.y, m->force.z);
      w.torque = Eigen::Vector3d(m->torque.x, m->torque.y, m->torque.z);
      if (!w.force.allFinite() || !w.torque.allFinite()) {
        ROS_WARN_THROTTLE(1.0, "car: %s: dropped a wrench with a non-finite value", name_.c_str());
        return;
      }
      if (target_) target_->set_wrench(w);
    });
    return "wrench " + sub_.getTopic() + " on " + p.config.text("bodyName");
  }

  void publish(const car_sim::Output&, NodeContext&) override {}

 private:
  std::string name_;
  car_sim::WrenchCommand* target_ = nullptr;
  ros::Subscriber sub_;
};

}  // namespace

std::unique_ptr<Adapter> make_force_adapter() { return std::make_unique<ForceAdapter>(); }

}  // namespace car_ros
