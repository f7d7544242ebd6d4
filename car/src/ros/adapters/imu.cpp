// libgazebo_ros_imu(_sensor).so on ROS: sensor_msgs/Imu on topicName under robotNamespace, in frameName,
// covariances gaussianNoise^2 on the diagonals.
#include <sensor_msgs/Imu.h>

#include <cmath>

#include "../adapter.hpp"
#include "../conversions.hpp"
#include "imu/imu.hpp"

namespace car_ros {

namespace {

class ImuAdapter : public Adapter {
 public:
  std::string setup(const car_sim::PluginInfo& p, const car_sim::RobotInfo& robot, NodeContext& node) override {
    frame_ = frame(p.config.text("frameName"));
    variance_ = std::pow(p.config.number("gaussianNoise"), 2);
    imu_ = node.nh().advertise<sensor_msgs::Imu>(topic_in(car_sim::plugin_robot_namespace(p.config, robot.name), p.config.text("topicName")), 10);
    return imu_.getTopic();
  }

  bool listened() const override { return imu_.getNumSubscribers() > 0; }

  void publish(const car_sim::Output& out, NodeContext& node) override {
    const auto& o = static_cast<const car_sim::ImuOut&>(out);
    sensor_msgs::Imu m;
    m.header.stamp = node.stamp(o.tick);
    m.header.frame_id = frame_;
    m.orientation.x = o.orientation.x();
    m.orientation.y = o.orientation.y();
    m.orientation.z = o.orientation.z();
    m.orientation.w = o.orientation.w();
    m.angular_velocity.x = o.angular_velocity.x();
    m.angular_velocity.y = o.angular_velocity.y();
    m.angular_velocity.z = o.angular_velocity.z();
    m.linear_acceleration.x = o.linear_acceleration.x();
    m.linear_acceleration.y = o.linear_acceleration.y();
    m.linear_acceleration.z = o.linear_acceleration.z();
    for (int i = 0; i < 3; ++i) {
      m.orientation_covariance[i * 4] = variance_;
      m.angular_velocity_covariance[i * 4] = variance_;
      m.linear_acceleration_covariance[i * 4] = variance_;
    }
    node.publish(imu_, std::move(m));
  }

 private:
  std::string frame_;
  double variance_ = 0.0;
  ros::Publisher imu_;
};

}  // namespace

std::unique_ptr<Adapter> make_imu_adapter() { return std::make_unique<ImuAdapter>(); }

}  // namespace car_ros
