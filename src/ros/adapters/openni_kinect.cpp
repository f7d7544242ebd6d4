// libgazebo_ros_openni_kinect.so on ROS: colour image and camera_info, depth image and its camera_info, and the
// organized cloud, under <robotNamespace>/<cameraName>/; each published only while subscribed.
#include "../adapter.hpp"
#include "../conversions.hpp"
#include "camera_msgs.hpp"

namespace car_ros {

namespace {

class KinectAdapter : public Adapter {
 public:
  std::string setup(const car_sim::PluginInfo& p, const car_sim::RobotInfo& robot, NodeContext& node) override {
    std::string topics = topics_.advertise(node.nh(), p.config, robot.name);
    const std::string& base = topics_.base();
    depth_ = node.nh().advertise<sensor_msgs::Image>(topic_in(base, p.config.text("depthImageTopicName")), 2);
    topics_.extra_info =
        node.nh().advertise<sensor_msgs::CameraInfo>(topic_in(base, p.config.text("depthImageCameraInfoTopicName")), 2);
    points_ = node.nh().advertise<sensor_msgs::PointCloud2>(topic_in(base, p.config.text("pointCloudTopicName")), 2);
    millimetres_ = p.config.flag("useDepth16UC1Format");
    return topics + ", " + depth_.getTopic() + ", " + topics_.extra_info.getTopic() + ", " + points_.getTopic();
  }

  bool listened() const override {
    return topics_.listened() || depth_.getNumSubscribers() > 0 || points_.getNumSubscribers() > 0;
  }

  void publish(const car_sim::Output& out, NodeContext& node) override {
    const auto& o = static_cast<const car_sim::CameraOut&>(out);
    const ros::Time stamp = node.stamp(o.tick);
    topics_.publish(o, stamp, node);
    if (depth_.getNumSubscribers() > 0) node.publish(depth_, depth_image(o, millimetres_, topics_.frame_id(), stamp));
    if (points_.getNumSubscribers() > 0) node.publish(points_, point_cloud(o, topics_.frame_id(), stamp));
  }

 private:
  CameraTopics topics_;
  ros::Publisher depth_, points_;
  bool millimetres_ = false;
};

}  // namespace

std::unique_ptr<Adapter> make_openni_kinect_adapter() { return std::make_unique<KinectAdapter>(); }

}  // namespace car_ros
