// libgazebo_ros_range.so on ROS: sensor_msgs/Range on topicName under robotNamespace, in frameName, at most
// updateRate per second of sim time (0 = every sensor update), published only while subscribed.
#include <sensor_msgs/Range.h>

#include "../adapter.hpp"
#include "../conversions.hpp"
#include "range/range.hpp"

namespace car_ros {

namespace {

class RangeAdapter : public Adapter {
 public:
  std::string setup(const car_sim::PluginInfo& p, const car_sim::RobotInfo& robot, NodeContext& node) override {
    frame_ = frame(p.config.text("frameName"));
    const double r = p.config.number("updateRate");
    period_ = r > 0 ? 1.0 / r : 0.0;
    pub_ = node.nh().advertise<sensor_msgs::Range>(topic_in(car_sim::plugin_robot_namespace(p.config, robot.name), p.config.text("topicName")), 1);
    return pub_.getTopic();
  }

  bool listened() const override { return pub_.getNumSubscribers() > 0; }

  void publish(const car_sim::Output& out, NodeContext& node) override {
    const auto& o = static_cast<const car_sim::RangeOut&>(out);
    const ros::Time stamp = node.stamp(o.tick);
    // upstream: publish when (now - last) >= 1 / updateRate, a time going backwards restarts the throttle
    if (period_ > 0 && stamp >= last_ && !last_.isZero() && (stamp - last_).toSec() < period_ - 1e-9) return;
    last_ = stamp;
    sensor_msgs::Range m;
    m.header.stamp = stamp;
    m.header.frame_id = frame_;
    m.radiation_type = static_cast<uint8_t>(o.radiation);
    m.field_of_view = o.field_of_view;
    m.min_range = o.min_range;
    m.max_range = o.max_range;
    m.range = o.range;
    node.publish(pub_, std::move(m));
  }

 private:
  std::string frame_;
  double period_ = 0.0;  // [s]
  ros::Time last_;
  ros::Publisher pub_;
};

}  // namespace

std::unique_ptr<Adapter> make_range_adapter() { return std::make_unique<RangeAdapter>(); }

}  // namespace car_ros
