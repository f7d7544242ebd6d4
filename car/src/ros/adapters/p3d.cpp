// libgazebo_ros_p3d.so on ROS: nav_msgs/Odometry on topicName under robotNamespace, header frame frameName,
// child frame bodyName, covariances gaussianNoise^2 on the diagonals; published only while subscribed.
#include <nav_msgs/Odometry.h>

#include "../adapter.hpp"
#include "../conversions.hpp"
#include "p3d/p3d.hpp"

namespace car_ros {

namespace {

class P3dAdapter : public Adapter {
 public:
  std::string setup(const car_sim::PluginInfo& p, const car_sim::RobotInfo& robot, NodeContext& node) override {
    frame_ = frame(p.config.text("frameName"));
    body_ = p.config.text("bodyName");
    variance_ = p.config.number("gaussianNoise") * p.config.number("gaussianNoise");
    pub_ = node.nh().advertise<nav_msgs::Odometry>(topic_in(car_sim::plugin_robot_namespace(p.config, robot.name), p.config.text("topicName")), 100);
    return pub_.getTopic();
  }

  bool listened() const override { return pub_.getNumSubscribers() > 0; }

  void publish(const car_sim::Output& out, NodeContext& node) override {
    const auto& o = static_cast<const car_sim::P3dOut&>(out);
    nav_msgs::Odometry m;
    m.header.stamp = node.stamp(o.tick);
    m.header.frame_id = frame_;
    m.child_frame_id = body_;
    m.pose.pose = to_pose(o.pose);
    m.twist.twist = to_twist(o.linear, o.angular);
    for (int i = 0; i < 6; ++i) {
      m.pose.covariance[i * 7] = variance_;
      m.twist.covariance[i * 7] = variance_;
    }
    node.publish(pub_, std::move(m));
  }

 private:
  std::string frame_, body_;
  double variance_ = 0.0;
  ros::Publisher pub_;
};

}  // namespace

std::unique_ptr<Adapter> make_p3d_adapter() { return std::make_unique<P3dAdapter>(); }

}  // namespace car_ros
