// libgazebo_ros_multicamera.so on ROS: per side, image and camera_info under
// <robotNamespace>/<cameraName>/left and .../right (the right camera's P carries -f hackBaseline), every frame of
// a pair with the same stamp.
#include <deque>

#include "../adapter.hpp"
#include "camera_msgs.hpp"
#include "multicamera/multicamera.hpp"

namespace car_ros {

namespace {

void set_param(car_sim::PluginConfig* c, const std::string& key, const std::string& value) {
  for (auto& p : c->params)
    if (p.key == key) p.value = value;
}

class MultiCameraAdapter : public Adapter {
 public:
  std::string setup(const car_sim::PluginInfo& p, const car_sim::RobotInfo& robot, NodeContext& node) override {
    std::string topics;
    for (const char* side : {"left", "right"}) {
      if (p.config.text(std::string("camera[") + side + "]/@name").empty()) continue;
      car_sim::PluginConfig c = p.config;
      set_param(&c, "cameraName", c.text("cameraName") + "/" + side);
      if (std::string(side) == "left") set_param(&c, "hackBaseline", "0");
      sides_.push_back(side);
      topics_.emplace_back();
      topics += (topics.empty() ? "" : ", ") + topics_.back().advertise(node.nh(), c, robot.name);
    }
    return topics;
  }

  bool listened() const override {
    for (const auto& t : topics_)
      if (t.listened()) return true;
    return false;
  }

  void publish(const car_sim::Output& out, NodeContext& node) override {
    publish_owned(std::make_shared<car_sim::MultiCameraOut>(static_cast<const car_sim::MultiCameraOut&>(out)), node);
  }
  void publish_owned(std::shared_ptr<const car_sim::Output> out, NodeContext& node) override {
    const auto& o = static_cast<const car_sim::MultiCameraOut&>(*out);
    const ros::Time stamp = node.stamp(o.tick);
    for (size_t i = 0; i < o.frames.size(); ++i)
      for (size_t k = 0; k < sides_.size(); ++k)
        if (sides_[k] == o.sides[i])
          // a frame of the pair, owned with the whole output
          topics_[k].publish(std::shared_ptr<const car_sim::CameraOut>(out, &o.frames[i]), stamp, node);
  }

 private:
  std::vector<std::string> sides_;
  std::deque<CameraTopics> topics_;
};

}  // namespace

std::unique_ptr<Adapter> make_multicamera_adapter() { return std::make_unique<MultiCameraAdapter>(); }

}  // namespace car_ros
