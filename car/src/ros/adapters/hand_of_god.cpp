// libgazebo_ros_hand_of_god.so on ROS: TF world -> <frameId>_actual with the link's pose every step. The target,
// TF world -> <frameId>_desired, is the kind's Pose input port, read from TF after each of these (inputs.cpp).

#include "../adapter.hpp"
#include "../conversions.hpp"
#include "hand_of_god/hand_of_god.hpp"

namespace car_ros {

namespace {

class HandOfGodAdapter : public Adapter {
 public:
  std::string setup(const car_sim::PluginInfo& p, const car_sim::RobotInfo& robot, NodeContext& node) override {
    frame_id_ = frame(p.config.text("frameId"));
    return "target TF world -> " + frame_id_ + "_desired, actual world -> " + frame_id_ + "_actual, link " +
           p.config.text("linkName") + ", kl " + p.config.text("kl") + ", ka " + p.config.text("ka");
  }

  // TF has no subscriber count: the actual pose always goes out (and the target is looked up) every step
  bool listened() const override { return true; }

  void publish(const car_sim::Output& out, NodeContext& node) override {
    const auto& o = static_cast<const car_sim::PoseOut&>(out);
    geometry_msgs::TransformStamped t;
    t.header.frame_id = "world";
    t.header.stamp = node.stamp(o.tick);
    t.child_frame_id = frame_id_ + "_actual";
    t.transform = to_transform(o.pose);
    node.send_tf(std::move(t));
  }

 private:
  std::string frame_id_;
};

}  // namespace

std::unique_ptr<Adapter> make_hand_of_god_adapter() { return std::make_unique<HandOfGodAdapter>(); }

}  // namespace car_ros
