// libgazebo_ros_ft_sensor.so on ROS: geometry_msgs/WrenchStamped on topicName under robotNamespace, header frame
// the joint's child link, while subscribed.
#include <geometry_msgs/WrenchStamped.h>

#include "../adapter.hpp"
#include "../conversions.hpp"
#include "ft_sensor/ft_sensor.hpp"

namespace car_ros {

namespace {

class FtSensorAdapter : public Adapter {
 public:
  std::string setup(const car_sim::PluginInfo& p, const car_sim::RobotInfo& robot, NodeContext& node) override {
    frame_ = frame(p.config.link);
    pub_ = node.nh().advertise<geometry_msgs::WrenchStamped>(
        topic_in(car_sim::plugin_robot_namespace(p.config, robot.name), p.config.text("topicName")), 1);
    return pub_.getTopic() + " (joint " + p.config.text("jointName") + ", frame " + frame_ + ")";
  }

  bool listened() const override { return pub_.getNumSubscribers() > 0; }

  void publish(const car_sim::Output& out, NodeContext& node) override {
    const auto& o = static_cast<const car_sim::WrenchOut&>(out);
    geometry_msgs::WrenchStamped m;
    m.header.stamp = node.stamp(o.tick);
    m.header.frame_id = frame_;
    m.wrench.force.x = o.wrench.force.x();
    m.wrench.force.y = o.wrench.force.y();
    m.wrench.force.z = o.wrench.force.z();
    m.wrench.torque.x = o.wrench.torque.x();
    m.wrench.torque.y = o.wrench.torque.y();
    m.wrench.torque.z = o.wrench.torque.z();
    node.publish(pub_, std::move(m));
  }

 private:
  std::string frame_;
  ros::Publisher pub_;
};

}  // namespace

std::unique_ptr<Adapter> make_ft_sensor_adapter() { return std::make_unique<FtSensorAdapter>(); }

}  // namespace car_ros
