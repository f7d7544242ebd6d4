// libhector_gazebo_ros_gps.so on ROS: sensor_msgs/NavSatFix on topicName (default "fix") and
// geometry_msgs/Vector3Stamped on velocityTopicName ("fix_velocity") under robotNamespace, both in frameId;
// position covariance diagonal, type DIAGONAL_KNOWN.
#include <geometry_msgs/Vector3Stamped.h>
#include <sensor_msgs/NavSatFix.h>

#include "../adapter.hpp"
#include "../conversions.hpp"
#include "hector_gps/hector_gps.hpp"

namespace car_ros {

namespace {

class HectorGpsAdapter : public Adapter {
 public:
  std::string setup(const car_sim::PluginInfo& p, const car_sim::RobotInfo& robot, NodeContext& node) override {
    frame_ = frame(p.config.text("frameId"));
    const std::string ns = car_sim::plugin_robot_namespace(p.config, robot.name);
    fix_ = node.nh().advertise<sensor_msgs::NavSatFix>(topic_in(ns, p.config.text("topicName")), 10);
    vel_ = node.nh().advertise<geometry_msgs::Vector3Stamped>(topic_in(ns, p.config.text("velocityTopicName")), 10);
    return fix_.getTopic() + ", " + vel_.getTopic();
  }

  bool listened() const override { return fix_.getNumSubscribers() > 0 || vel_.getNumSubscribers() > 0; }

  void publish(const car_sim::Output& out, NodeContext& node) override {
    const auto& o = static_cast<const car_sim::GpsOut&>(out);
    sensor_msgs::NavSatFix f;
    f.header.stamp = node.stamp(o.tick);
    f.header.frame_id = frame_;
    f.status.status = static_cast<int8_t>(o.status);
    f.status.service = static_cast<uint16_t>(o.service);
    f.latitude = o.latitude;
    f.longitude = o.longitude;
    f.altitude = o.altitude;
    f.position_covariance_type = sensor_msgs::NavSatFix::COVARIANCE_TYPE_DIAGONAL_KNOWN;
    f.position_covariance[0] = o.position_variance.x();
    f.position_covariance[4] = o.position_variance.y();
    f.position_covariance[8] = o.position_variance.z();
    node.publish(fix_, f);
    geometry_msgs::Vector3Stamped v;
    v.header = f.header;
    v.vector.x = o.velocity.x();
    v.vector.y = o.velocity.y();
    v.vector.z = o.velocity.z();
    node.publish(vel_, std::move(v));
  }

 private:
  std::string frame_;
  ros::Publisher fix_, vel_;
};

}  // namespace

std::unique_ptr<Adapter> make_hector_gps_adapter() { return std::make_unique<HectorGpsAdapter>(); }

}  // namespace car_ros
