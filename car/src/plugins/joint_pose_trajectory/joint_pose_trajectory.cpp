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
    k.finish = finish;
    k.make = [](const PluginConfig&, const std::string&, uint64_t) -> std::unique_ptr<Plugin> {
      return std::make_unique<JointPoseTrajectory>();
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
