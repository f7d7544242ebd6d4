// libgazebo_ros_joint_pose_trajectory.so on ROS: trajectory_msgs/JointTrajectory on topicName under robotNamespace
// (queue 100). header.stamp is the start (earlier: now); header.frame_id "", "world", "map" or a link of this
// model (whose pose is held anyway: car sets joint positions without moving the base); any other frame is refused
// with an error, as upstream. The upstream service is compiled out there, so none is offered here either.
#include <trajectory_msgs/JointTrajectory.h>

#include "../adapter.hpp"
#include "../conversions.hpp"
#include "joint_pose_trajectory/joint_pose_trajectory.hpp"

namespace car_ros {

namespace {

class JointPoseTrajectoryAdapter : public Adapter {
 public:
  std::string setup(const car_sim::PluginInfo& p, const car_sim::RobotInfo& robot, NodeContext& node) override {
    target_ = dynamic_cast<car_sim::TrajectoryCommand*>(node.world().plugin(robot.name, p.config.name));
    model_ = &robot.model;
    name_ = p.config.name;
    const std::string topic = p.config.text("topicName");
    if (topic.empty()) return "no topic";
    sub_ = node.nh().subscribe<trajectory_msgs::JointTrajectory>(
        topic_in(car_sim::plugin_robot_namespace(p.config, robot.name), topic), 100,
        [this](const trajectory_msgs::JointTrajectory::ConstPtr& m) { on_trajectory(*m); });
    return "trajectory " + sub_.getTopic();
  }

  void publish(const car_sim::Output&, NodeContext&) override {}

 private:
  void on_trajectory(const trajectory_msgs::JointTrajectory& m) {
    const std::string ref = frame(m.header.frame_id);
    if (!ref.empty() && ref != "world" && ref != "map" && !model_->find_link(ref)) {
      ROS_ERROR("car: %s: the trajectory's frame_id '%s' is neither world nor a link of the model; ignored",
                name_.c_str(), ref.c_str());
      return;
    }
    car_sim::JointTrajectory t;
    t.joint_names = m.joint_names;
    t.start = m.header.stamp.toSec();
    for (const auto& p : m.points) {
      car_sim::TrajectoryPoint q;
      q.positions = p.positions;
      q.time_from_start = p.time_from_start.toSec();
      if (q.positions.size() != m.joint_names.size())
        ROS_ERROR("car: %s: a point has %zu positions for %zu joint names; it will be skipped", name_.c_str(),
                  q.positions.size(), m.joint_names.size());
      t.points.push_back(std::move(q));
    }
    if (!target_) return;
    for (const auto& n : target_->set_trajectory(t))
      ROS_WARN("car: %s: no joint '%s' in the model; skipped", name_.c_str(), n.c_str());
  }

  car_sim::TrajectoryCommand* target_ = nullptr;
  const car_sim::RobotModel* model_ = nullptr;
  std::string name_;
  ros::Subscriber sub_;
};

}  // namespace

std::unique_ptr<Adapter> make_joint_pose_trajectory_adapter() { return std::make_unique<JointPoseTrajectoryAdapter>(); }

}  // namespace car_ros
