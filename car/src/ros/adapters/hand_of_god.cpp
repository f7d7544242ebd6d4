// libgazebo_ros_hand_of_god.so on ROS: the target is TF world -> <frameId>_desired (latest, looked up every step;
// a failed lookup is logged once until it succeeds again, and the link keeps its last target); TF world ->
// <frameId>_actual with the link's pose every step.
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <memory>

#include "../adapter.hpp"
#include "../conversions.hpp"
#include "hand_of_god/hand_of_god.hpp"

namespace car_ros {

namespace {

class HandOfGodAdapter : public Adapter {
 public:
  std::string setup(const car_sim::PluginInfo& p, const car_sim::RobotInfo& robot, NodeContext& node) override {
    target_ = dynamic_cast<car_sim::PoseTarget*>(node.world().plugin(robot.name, p.config.name));
    frame_id_ = frame(p.config.text("frameId"));
    buffer_ = std::make_unique<tf2_ros::Buffer>();
    listener_ = std::make_unique<tf2_ros::TransformListener>(*buffer_);
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
    try {
      const geometry_msgs::TransformStamped d = buffer_->lookupTransform("world", frame_id_ + "_desired", ros::Time(0));
      geometry_msgs::Pose p;
      p.position.x = d.transform.translation.x;
      p.position.y = d.transform.translation.y;
      p.position.z = d.transform.translation.z;
      p.orientation = d.transform.rotation;
      if (target_) target_->set_target(from_pose(p));
      errored_ = false;
    } catch (const tf2::TransformException& e) {
      if (!errored_) ROS_ERROR("car: hand_of_god: %s", e.what());
      errored_ = true;
    }
  }

 private:
  car_sim::PoseTarget* target_ = nullptr;
  std::string frame_id_;
  std::unique_ptr<tf2_ros::Buffer> buffer_;
  std::unique_ptr<tf2_ros::TransformListener> listener_;
  bool errored_ = false;
};

}  // namespace

std::unique_ptr<Adapter> make_hand_of_god_adapter() { return std::make_unique<HandOfGodAdapter>(); }

}  // namespace car_ros
