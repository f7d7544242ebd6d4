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
  // the frame's parts by topic; camera_info alone needs no pixels: depth, the cheapest part
  uint32_t parts() const override {
    uint32_t p = 0;
    if (topics_.image_listened()) p |= car_sim::kCameraImage;
    if (depth_.getNumSubscribers() > 0) p |= car_sim::kCameraDepth;
    if (points_.getNumSubscribers() > 0) p |= car_sim::kCameraCloud;
    return p ? p : car_sim::kCameraDepth;
  }

  void publish(const car_sim::Output& out, NodeContext& node) override {
    publish_owned(std::make_shared<car_sim::CameraOut>(static_cast<const car_sim::CameraOut&>(out)), node);
  }
  void publish_owned(std::shared_ptr<const car_sim::Output> out, NodeContext& node) override {
    auto o = std::static_pointer_cast<const car_sim::CameraOut>(out);
    const ros::Time stamp = node.stamp(o->tick);
    topics_.publish(o, stamp, node);
    // depth image and cloud: serialised by roscpp straight from the frame's arrays (camera_msgs.hpp)
    // a part nobody took as the frame was made is not in it (a subscriber that came since gets the next frame)
    if (depth_.getNumSubscribers() > 0 && !o->depth.empty()) {
      DepthView v;
      v.out = o;
      v.frame = topics_.frame_id();
      v.stamp = stamp;
      v.millimetres = millimetres_;
      node.publish(depth_, std::move(v));
    }
    if (points_.getNumSubscribers() > 0 && !o->points.empty()) {
      CloudView v;
      v.out = o;
      v.frame = topics_.frame_id();
      v.stamp = stamp;
      node.publish(points_, std::move(v));
    }
  }

 private:
  CameraTopics topics_;
  ros::Publisher depth_, points_;
  bool millimetres_ = false;
};

}  // namespace

std::unique_ptr<Adapter> make_openni_kinect_adapter() { return std::make_unique<KinectAdapter>(); }

}  // namespace car_ros
