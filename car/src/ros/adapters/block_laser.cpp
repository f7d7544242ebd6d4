// libgazebo_ros_block_laser.so on ROS: sensor_msgs/PointCloud on topicName under robotNamespace, in frameName,
// one unnamed channel of intensities (upstream never names it), published only while subscribed.
#include <sensor_msgs/PointCloud.h>

#include "../adapter.hpp"
#include "../conversions.hpp"
#include "block_laser/block_laser.hpp"

namespace car_ros {

namespace {

class BlockLaserAdapter : public Adapter {
 public:
  std::string setup(const car_sim::PluginInfo& p, const car_sim::RobotInfo& robot, NodeContext& node) override {
    frame_ = frame(p.config.text("frameName"));
    pub_ = node.nh().advertise<sensor_msgs::PointCloud>(topic_in(car_sim::plugin_robot_namespace(p.config, robot.name), p.config.text("topicName")), 1);
    return pub_.getTopic();
  }

  bool listened() const override { return pub_.getNumSubscribers() > 0; }

  void publish(const car_sim::Output& out, NodeContext& node) override {
    const auto& o = static_cast<const car_sim::BlockLaserOut&>(out);
    sensor_msgs::PointCloud m;
    m.header.stamp = node.stamp(o.tick);
    m.header.frame_id = frame_;
    const size_t n = o.intensities.size();
    m.points.resize(n);
    for (size_t i = 0; i < n; ++i) {
      m.points[i].x = o.points[3 * i];
      m.points[i].y = o.points[3 * i + 1];
      m.points[i].z = o.points[3 * i + 2];
    }
    m.channels.resize(1);
    m.channels[0].values = o.intensities;
    node.publish(pub_, std::move(m));
  }

 private:
  std::string frame_;
  ros::Publisher pub_;
};

}  // namespace

std::unique_ptr<Adapter> make_block_laser_adapter() { return std::make_unique<BlockLaserAdapter>(); }

}  // namespace car_ros
