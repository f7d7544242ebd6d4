// libgazebo_ros_laser.so on ROS: sensor_msgs/LaserScan on topicName under robotNamespace, in frameName.
#include <sensor_msgs/LaserScan.h>

#include "../adapter.hpp"
#include "../conversions.hpp"
#include "laser/laser.hpp"

namespace car_ros {

namespace {

class LaserAdapter : public Adapter {
 public:
  std::string setup(const car_sim::PluginInfo& p, const car_sim::RobotInfo& robot, NodeContext& node) override {
    frame_ = frame(p.config.text("frameName"));
    scan_ = node.nh().advertise<sensor_msgs::LaserScan>(topic_in(car_sim::plugin_robot_namespace(p.config, robot.name), p.config.text("topicName")), 10);
    return scan_.getTopic();
  }

  bool listened() const override { return scan_.getNumSubscribers() > 0; }

  void publish(const car_sim::Output& out, NodeContext& node) override {
    const auto& o = static_cast<const car_sim::LaserScanOut&>(out);
    sensor_msgs::LaserScan m;
    m.header.stamp = node.stamp(o.tick);
    m.header.frame_id = frame_;
    m.angle_min = o.angle_min;
    m.angle_max = o.angle_max;
    m.angle_increment = o.angle_increment;
    m.time_increment = 0.f;
    m.scan_time = 0.f;
    m.range_min = o.range_min;
    m.range_max = o.range_max;
    m.ranges = o.ranges;
    m.intensities = o.intensities;
    node.publish(scan_, std::move(m));
  }

 private:
  std::string frame_;
  ros::Publisher scan_;
};

}  // namespace

std::unique_ptr<Adapter> make_laser_adapter() { return std::make_unique<LaserAdapter>(); }

}  // namespace car_ros
