// libhector_gazebo_ros_imu.so on ROS: sensor_msgs/Imu on topicName (default "imu") and the biases as
// sensor_msgs/Imu on biasTopicName (topicName + "/bias"), under robotNamespace, in frameId. Covariances as
// upstream: rate and accel noise squared; orientation roll/pitch accel noise^2 / g^2, yaw the yaw noise squared.
#include <sensor_msgs/Imu.h>

#include <cmath>
#include <sstream>

#include "../adapter.hpp"
#include "../conversions.hpp"
#include "hector_imu/hector_imu.hpp"

namespace car_ros {

namespace {

// A key that is one number or "x y z"; the components, or zeros when unreadable (as upstream keeps its default).
Eigen::Vector3d vec3(const car_sim::PluginConfig& c, const std::string& key) {
  std::istringstream ss(c.text(key));
  Eigen::Vector3d v;
  if (ss >> v.x() >> v.y() >> v.z()) return v;
  return Eigen::Vector3d::Zero();
}

void fill(sensor_msgs::Imu* m, const Eigen::Quaterniond& q, const Eigen::Vector3d& w, const Eigen::Vector3d& a) {
  m->orientation.x = q.x();
  m->orientation.y = q.y();
  m->orientation.z = q.z();
  m->orientation.w = q.w();
  m->angular_velocity.x = w.x();
  m->angular_velocity.y = w.y();
  m->angular_velocity.z = w.z();
  m->linear_acceleration.x = a.x();
  m->linear_acceleration.y = a.y();
  m->linear_acceleration.z = a.z();
}

class HectorImuAdapter : public Adapter {
 public:
  std::string setup(const car_sim::PluginInfo& p, const car_sim::RobotInfo& robot, NodeContext& node) override {
    const car_sim::PluginConfig& c = p.config;
    frame_ = frame(c.text("frameId"));
    const std::string ns = car_sim::plugin_robot_namespace(c, robot.name);
    // [per axis] the models' noise; a non-zero gaussianNoise replaces both
    Eigen::Vector3d rate = vec3(c, "rateGaussianNoise"), accel = vec3(c, "accelGaussianNoise");
    if (c.number("gaussianNoise") != 0.0) rate = accel = Eigen::Vector3d::Constant(c.number("gaussianNoise"));
    std::istringstream ys(c.text("yawGaussianNoise"));
    double yaw = 0;
    ys >> yaw;
    const double g = node.world().description().gravity.norm();
    for (int i = 0; i < 3; ++i) {
      cov_.angular_velocity_covariance[4 * i] = rate[i] * rate[i];
      cov_.linear_acceleration_covariance[4 * i] = accel[i] * accel[i];
    }
    cov_.orientation_covariance[8] = yaw * yaw;
    cov_.orientation_covariance[0] = g > 0 ? accel.x() * accel.x() / (g * g) : -1;
    cov_.orientation_covariance[4] = g > 0 ? accel.y() * accel.y() / (g * g) : -1;
    std::string topics;
    if (!c.text("topicName").empty()) {
      imu_ = node.nh().advertise<sensor_msgs::Imu>(topic_in(ns, c.text("topicName")), 10);
      topics = imu_.getTopic();
    }
    if (!c.text("biasTopicName").empty()) {
      bias_ = node.nh().advertise<sensor_msgs::Imu>(topic_in(ns, c.text("biasTopicName")), 10);
      topics += (topics.empty() ? "" : ", ") + bias_.getTopic();
    }
    return topics;
  }

  bool listened() const override {
    return (imu_ && imu_.getNumSubscribers() > 0) || (bias_ && bias_.getNumSubscribers() > 0);
  }

  void publish(const car_sim::Output& out, NodeContext& node) override {
    const auto& o = static_cast<const car_sim::HectorImuOut&>(out);
    sensor_msgs::Imu m = cov_;
    m.header.stamp = node.stamp(o.tick);
    m.header.frame_id = frame_;
    if (imu_) {
      fill(&m, o.orientation, o.angular_velocity, o.linear_acceleration);
      node.publish(imu_, m);
    }
    if (bias_) {
      sensor_msgs::Imu b;
      b.header = m.header;
      fill(&b, o.orientation_error, o.rate_bias, o.accel_bias);
      node.publish(bias_, std::move(b));
    }
  }

 private:
  std::string frame_;
  sensor_msgs::Imu cov_;  // the covariances every message carries
  ros::Publisher imu_, bias_;
};

}  // namespace

std::unique_ptr<Adapter> make_hector_imu_adapter() { return std::make_unique<HectorImuAdapter>(); }

}  // namespace car_ros
