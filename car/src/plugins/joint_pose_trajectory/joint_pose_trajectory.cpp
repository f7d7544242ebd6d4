// libgazebo_ros_joint_pose_trajectory.so (gazebo_plugins, Noetic): from the trajectory's start, each world update
// at or after the next point's time sets its joint positions (velocity 0), then the next time is this time + the
// point's time_from_start; the world's physics is off while a trajectory plays (disable_physics_updates_).
// updateRate is read and never used upstream. Per docs/COMPAT-plugins.md.
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

  // fix: car drops the trajectory at a reset (upstream has no Reset and plays on), and puts physics back as it was
  void reset() override { finish(); }

  // header.frame_id "world", "map", "/map" or a link of this model (whose pose is held anyway: car sets joint
  // positions without moving the base); anything else, "" included, names no link upstream: refused with its error.
  void command(const std::string&, const Command& value, CommandResult* result) override {
    const JointTrajectory& t = std::get<JointTrajectory>(value);
    const std::string& ref = t.frame_id;
    if (ref != "world" && ref != "map" && ref != "/map" && !(robot_ && robot_->model().find_link(ref))) {
      result->notes.push_back(
          {true, "ros_joint_trajectory plugin needs a reference link [" + ref + "] as frame_id, aborting."});
      return;
    }
    for (const auto& p : t.points)
      if (p.positions.size() < t.joint_names.size())
        result->notes.push_back({true, "a point has " + std::to_string(p.positions.size()) + " positions for " +
                                           std::to_string(t.joint_names.size()) + " joint names; it will be skipped"});
    for (const auto& n : set_trajectory(t)) result->notes.push_back({false, "no joint '" + n + "' in the model; skipped"});
    // the world's physics stops while it plays (its state kept for the end; fix: a trajectory that replaces a
    // playing one keeps the state from before the first, where upstream saves "off" and never turns physics on)
    if (robot_) {
      if (!frozen_) physics_before_ = robot_->physics_enabled();
      frozen_ = true;
      robot_->set_physics_enabled(false);
    }
  }

  // UpdateStates at WorldUpdateBegin, where the sim time already counts the coming step: (tick + 1) dt
  void pre_physics(const StepContext& ctx, RobotHandle& robot) override {
    if (!active_) return;
    if (next_ < 0) next_ = std::max(traj_.start, ctx.time());
    const double now = static_cast<double>(ctx.tick + 1) * ctx.dt;
    if (now + 1e-9 < next_) return;
    if (index_ >= traj_.points.size()) {
      finish();
      return;
    }
    const TrajectoryPoint& p = traj_.points[index_];
    // upstream resizes each point to the joint names: extra positions are not played; a point with fewer (read
    // past its end upstream) is skipped
    if (p.positions.size() >= joints_.size())
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
  bool frozen_ = false, physics_before_ = true;  // physics stopped by this plug-in, and its state before

  // the trajectory ends: physics back as it was
  void finish() {
    active_ = false;
    if (frozen_ && robot_) robot_->set_physics_enabled(physics_before_);
    frozen_ = false;
  }
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
