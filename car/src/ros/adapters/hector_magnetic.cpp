// libhector_gazebo_ros_magnetic.so on ROS: geometry_msgs/Vector3Stamped, or sensor_msgs/MagneticField with
// useMagneticFieldMsgs, on topicName (default "magnetic") under robotNamespace, in frameId.
#include <geometry_msgs/Vector3Stamped.h>
#include <sensor_msgs/MagneticField.h>

#include "../adapter.hpp"
#include "../conversions.hpp"
#include "hector_magnetic/hector_magnetic.hpp"

namespace car_ros {

namespace {

class HectorMagneticAdapter : public Adapter {
 public:
  std::string setup(const car_sim::PluginInfo& p, const car_sim::RobotInfo& robot, NodeContext& node) override {
    frame_ = frame(p.config.text("frameId"));
    field_msgs_ = p.config.flag("useMagneticFieldMsgs");
    const std::string topic = topic_in(car_sim::plugin_robot_namespace(p.config, robot.name), p.config.text("topicName"));
    pub_ = field_msgs_ ? node.nh().advertise<sensor_msgs::MagneticField>(topic, 1)
                       : node.nh().advertise<geometry_msgs::Vector3Stamped>(topic, 1);
    return pub_.getTopic();
  }

  bool listened() const override { return pub_.getNumSubscribers() > 0; }

  void publish(const car_sim::Output& out, NodeContext& node) override {
    const auto& o = static_cast<const car_sim::MagneticOut&>(out);
    std_msgs::Header h;
    h.stamp = node.stamp(o.tick);
    h.frame_id = frame_;
    if (field_msgs_) {
      sensor_msgs::MagneticField m;
      m.header = h;
      m.magnetic_field.x = o.field.x();
      m.magnetic_field.y = o.field.y();
      m.magnetic_field.z = o.field.z();
      node.publish(pub_, std::move(m));
    } else {
      geometry_msgs::Vector3Stamped m;
      m.header = h;
      m.vector.x = o.field.x();
      m.vector.y = o.field.y();
      m.vector.z = o.field.z();
      node.publish(pub_, std::move(m));
    }
  }

 private:
  std::string frame_;
  bool field_msgs_ = false;
  ros::Publisher pub_;
};

}  // namespace

std::unique_ptr<Adapter> make_hector_magnetic_adapter() { return std::make_unique<HectorMagneticAdapter>(); }

}  // namespace car_ros
