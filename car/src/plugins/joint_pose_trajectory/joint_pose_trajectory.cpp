// libgazebo_ros_joint_pose_trajectory.so (gazebo_plugins, Noetic): from the trajectory's start, each step at or
// after the next point's time sets its joint positions (velocity 0; physics keeps running), then the next time is
// this time + the point's time_from_start. updateRate is read and never used upstream. Per
// docs/COMPAT-plugins.md.
#include "joint_pose_trajectory.hpp"

#include <algorithm>

namespace car_sim {

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType N = ParamType::Number;

class JointPoseTrajectory : public Plugin, public TrajectoryCommand {
 public:
  double update_rate() const override { return 0.0; }

  void configure(RobotHandle& robot) override { robot_ = &robot; }

  std::vector<std::string> set_trajectory(const JointTrajectory& t) override {
    std::vector<std::string> unknown;
    traj_ = t;
    joints_.clear();
    for (const auto& n : t.joint_names) {
      const int j = robot_ ? robot_->joint(n) : -1;
      if (j < 0) unknown.push_back(n);
      joints_.push_back(j);
    }
    next_ = -1.0;  // set from the start at the next step
    index_ = 0;
    active_ = true;
    return unknown;
  }

  void reset() override { active_ = false; }

  // header.frame_id "", "world", "map" or a link of this model (whose pose is held anyway: car sets joint
  // positions without moving the base); any other frame is refused with an error, as upstream.
  void command(const std::string&, const Command& value, CommandResult* result) override {
    const JointTrajectory& t = std::get<JointTrajectory>(value);
    std::string ref = t.frame_id;
    while (!ref.empty() && ref.front() == '/') ref.erase(ref.begin());
    if (!ref.empty() && ref != "world" && ref != "map" && !(robot_ && robot_->model().find_link(ref))) {
      result->notes.push_back(
          {true, "the trajectory's frame_id '" + ref + "' is neither world nor a link of the model; ignored"});
      return;
    }
    for (const auto& p : t.points)
      if (p.positions.size() != t.joint_names.size())
        result->notes.push_back({true, "a point has " + std::to_string(p.positions.size()) + " positions for " +
                                           std::to_string(t.joint_names.size()) + " joint names; it will be skipped"});
    for (const auto& n : set_trajectory(t)) result->notes.push_back({false, "no joint '" + n + "' in the model; skipped"});
  }

  void pre_physics(const StepContext& ctx, RobotHandle& robot) override {
    if (!active_) return;
    const double now = ctx.time();
    if (next_ < 0) next_ = std::max(traj_.start, now);
    if (now + 1e-9 < next_) return;
    if (index_ >= traj_.points.size()) {
      active_ = false;
      return;
    }
    const TrajectoryPoint& p = traj_.points[index_];
    // a point with the wrong number of positions is skipped (upstream logs it)
    if (p.positions.size() == joints_.size())
      for (size_t i = 0; i < joints_.size(); ++i)
        if (joints_[i] >= 0) robot.set_joint_position(joints_[i], p.positions[i]);
    next_ += p.time_from_start;
    ++index_;
  }

 private:
  RobotHandle* robot_ = nullptr;
  JointTrajectory traj_;
  std::vector<int> joints_;
  double next_ = -1.0;  // [s] sim time of the next point
  size_t index_ = 0;
  bool active_ = false;
};

void finish(ResolveContext&) {}

}  // namespace

const PluginKind& joint_pose_trajectory_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "joint_pose_trajectory";
    k.filenames = {"libgazebo_ros_joint_pose_trajectory.so"};
    k.schema = {
        {"robotNamespace", T, "", ""},
        {"topicName", T, "set_joint_trajectory", ""},
        {"serviceName", T, "set_joint_trajectory", ""},
        {"updateRate", N, "0", "Hz"},
    };
    k.ignored = {{"alwaysOn", ""}};
    k.inputs = topic_input("trajectory", InputType::JointTrajectory, "topicName", 100);
    k.finish = finish;
    k.make = [](const PluginConfig&, const std::string&, uint64_t) -> std::unique_ptr<Plugin> {
      return std::make_unique<JointPoseTrajectory>();
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
