// libgazebo_ros_joint_pose_trajectory.so: a joint trajectory played by setting joint positions, one point per step.
#pragma once

#include <string>
#include <vector>

#include "car_sim/plugin.hpp"

namespace car_sim {

// A plug-in that takes a trajectory command (through its input port).
class TrajectoryCommand {
 public:
  virtual ~TrajectoryCommand() = default;
  // Replaces any trajectory in progress. Returns what was skipped (unknown joint names), for the log.
  virtual std::vector<std::string> set_trajectory(const JointTrajectory& t) = 0;
};

const PluginKind& joint_pose_trajectory_kind();

}  // namespace car_sim
