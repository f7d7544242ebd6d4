// libgazebo_ros_triggered_camera.so on ROS: the camera's image and camera_info under <robotNamespace>/<cameraName>/;
// its trigger topic there (std_msgs/Empty, queue 1) is the kind's Trigger input port (inputs.cpp): each message
// renders one frame in the next step.

#include "../adapter.hpp"
#include "../conversions.hpp"
#include "camera_msgs.hpp"
#include "triggered_camera/triggered_camera.hpp"

namespace car_ros {

namespace {

class TriggeredCameraAdapter : public Adapter {
 public:
  std::string setup(const car_sim::PluginInfo& p, const car_sim::RobotInfo& robot, NodeContext& node) override {
    std::string topics = topics_.advertise(node.nh(), p.config, robot.name);
    for (const auto& in : p.inputs) topics += ", trigger " + in.topic;
    return topics;
  }
  bool listened() const override { return topics_.listened(); }
  void publish(const car_sim::Output& out, NodeContext& node) override {
    publish_owned(std::make_shared<car_sim::CameraOut>(static_cast<const car_sim::CameraOut&>(out)), node);
  }
  // upstream publishes image and camera_info only while the image topic has subscribers
  void publish_owned(std::shared_ptr<const car_sim::Output> out, NodeContext& node) override {
    if (!topics_.image_listened()) return;
    auto o = std::static_pointer_cast<const car_sim::CameraOut>(out);
    topics_.publish(o, node.stamp(o->tick), node);
  }

 private:
  CameraTopics topics_;
};

}  // namespace

std::unique_ptr<Adapter> make_triggered_camera_adapter() { return std::make_unique<TriggeredCameraAdapter>(); }

}  // namespace car_ros
