// libgazebo_ros_camera.so on ROS: image and camera_info under <robotNamespace>/<cameraName>/.
#include "../adapter.hpp"
#include "camera_msgs.hpp"

namespace car_ros {

namespace {

class CameraAdapter : public Adapter {
 public:
  std::string setup(const car_sim::PluginInfo& p, const car_sim::RobotInfo& robot, NodeContext& node) override {
    return topics_.advertise(node.nh(), p.config, robot.name);
  }
  bool listened() const override { return topics_.listened(); }
  void publish(const car_sim::Output& out, NodeContext& node) override {
    publish_owned(std::make_shared<car_sim::CameraOut>(static_cast<const car_sim::CameraOut&>(out)), node);
  }
  void publish_owned(std::shared_ptr<const car_sim::Output> out, NodeContext& node) override {
    auto o = std::static_pointer_cast<const car_sim::CameraOut>(out);
    topics_.publish(o, node.stamp(o->tick), node);
  }

 private:
  CameraTopics topics_;
};

}  // namespace

std::unique_ptr<Adapter> make_camera_adapter() { return std::make_unique<CameraAdapter>(); }

}  // namespace car_ros
