// libhector_gazebo_ros_sonar.so on ROS: sensor_msgs/Range on topicName (default "sonar") under robotNamespace,
// in frameId, at the plug-in's own rate; published only while subscribed.
#include <sensor_msgs/Range.h>

#include "../adapter.hpp"
#include "../conversions.hpp"
#include "range/range.hpp"

namespace car_ros {

namespace {

class HectorSonarAdapter : public Adapter {
 public:
  std::string setup(const car_sim::PluginInfo& p, const car_sim::RobotInfo& robot, NodeContext& node) override {
    frame_ = frame(p.config.text("frameId"));
    pub_ = node.nh().advertise<sensor_msgs::Range>(topic_in(car_sim::plugin_robot_namespace(p.config, robot.name), p.config.text("topicName")), 1);
    return pub_.getTopic();
  }

  bool listened() const override { return pub_.getNumSubscribers() > 0; }

  void publish(const car_sim::Output& out, NodeContext& node) override {
    const auto& o = static_cast<const car_sim::RangeOut&>(out);
    sensor_msgs::Range m;
    m.header.stamp = node.stamp(o.tick);
    m.header.frame_id = frame_;
    m.radiation_type = sensor_msgs::Range::ULTRASOUND;
    m.field_of_view = o.field_of_view;
    m.min_range = o.min_range;
    m.max_range = o.max_range;
    m.range = o.range;
    node.publish(pub_, std::move(m));
  }

 private:
  std::string frame_;
  ros::Publisher pub_;
};

}  // namespace

std::unique_ptr<Adapter> make_hector_sonar_adapter() { return std::make_unique<HectorSonarAdapter>(); }

}  // namespace car_ros
