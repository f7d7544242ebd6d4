// The controller types of car's ros_control layer (docs/COMPAT-control.md): what their ports take and
// the outputs each publishes. One file per type family: ctl_joint_state.cpp, ctl_joint.cpp (forward and PID
// joint controllers, joint groups), ctl_diff_drive.cpp, ctl_trajectory.cpp; the type table in ctl_registry.cpp.
#pragma once

#include <optional>

#include "ros_control.hpp"

namespace car_sim {
namespace control {

// A port of controller `name`: named "<name>/<leaf>", on `topic` (absolute).
InputPort controller_input(const std::string& name, const std::string& leaf, InputType type, const std::string& topic,
                           uint32_t queue);
OutputPort controller_output(const std::string& name, const std::string& leaf, SampleType type,
                             const std::string& topic, uint32_t queue);

// joint_states of joint_state_controller: every transmission joint (and extra_joints), with its effort.
struct JointStatesOutput : ControllerOutput {
  std::vector<JointState> joints;
  std::vector<double> effort;  // [N m] or [N], one per joint
  void samples(SampleList& list) const override { list.add(JointStatesSample{&joints, &effort}); }
  void visit(FieldVisitor& v) const override;
};

// control_msgs/JointControllerState of the PID joint controllers.
struct JointControllerStateOutput : ControllerOutput, ControllerStateSample {
  void samples(SampleList& list) const override { list.add(static_cast<const ControllerStateSample*>(this)); }
  void visit(FieldVisitor& v) const override;
};

// diff_drive_controller's odometry: pose and twist of base_frame_id in odom_frame_id (the port's frames).
struct DiffDriveOdometryOutput : ControllerOutput {
  double x = 0, y = 0, heading = 0;   // [m], [rad], odom frame
  double linear = 0, angular = 0;     // [m/s], [rad/s], base frame
  // the pose from x, y and heading, its orientation the controller's quaternion from the yaw
  void samples(SampleList& list) const override;
  void visit(FieldVisitor& v) const override;
};

// joint_trajectory_controller's state: desired, actual and error per joint.
struct TrajectoryStateOutput : ControllerOutput, TrajectoryStateSample {
  void samples(SampleList& list) const override { list.add(static_cast<const TrajectoryStateSample*>(this)); }
  void visit(FieldVisitor& v) const override;
};

// A FollowJointTrajectory goal's end, for the action server. error_code -6 (car's own: canceled) ends it as
// canceled with code 0, 0 as succeeded, any other as aborted (the sample says which).
struct TrajectoryResultOutput : ControllerOutput {
  uint64_t goal = 0;
  int error_code = 0;  // control_msgs/FollowJointTrajectoryResult codes
  std::string error_string;
  GoalResultSample sample;  // filled by finish()
  void samples(SampleList& list) const override { list.add(&sample); }
  void finish();
  void visit(FieldVisitor& v) const override;
};

// Controllers that take a command: std_msgs/Float64 on <ns>/command (one joint), or Float64MultiArray (a group).
class CommandController : public Controller {
 public:
  // One value per joint, in `joints()` order.
  virtual bool set_command(const std::vector<double>& values, std::string* why) = 0;
  virtual std::vector<std::string> joints() const = 0;
  // The command port, Float64 or Float64Array as the type is a group or not.
  virtual bool group() const { return false; }
  void ports(const std::string& name, const std::string& robot_ns, const std::string& ns, std::vector<InputPort>* in,
             std::vector<OutputPort>* out) const override;
  void command(const std::string& leaf, const Command& value, double now, CommandResult* r) override;
};

class DiffDriveController : public Controller {
 public:
  // geometry_msgs/Twist: linear.x [m/s], angular.z [rad/s], received at sim time `time` [s].
  virtual void set_twist(double linear, double angular, double time) = 0;
  void command(const std::string& leaf, const Command& value, double now, CommandResult* r) override {
    const Twist& t = std::get<Twist>(value);
    set_twist(t.linear.x(), t.angular.z(), now);
  }
};

// One trajectory point as trajectory_msgs/JointTrajectoryPoint has it (empty vectors: not given).
struct TrajPoint {
  std::vector<double> positions, velocities, accelerations;
  double time_from_start = 0;  // [s]
};

struct TrajGoal {
  std::vector<std::string> joint_names;
  std::vector<TrajPoint> points;
  double start_time = 0;  // [s] sim time (header.stamp; 0 = now)
  // FollowJointTrajectory tolerances by joint name: position (0: unchecked; < 0: none)
  std::map<std::string, double> path_position, goal_position;
  std::optional<double> goal_time_tolerance;  // [s]
};

class TrajectoryController : public Controller {
 public:
  // A new trajectory replaces the current one from its start (`command` topic: goal_id 0). Returns false with
  // the reason (control_msgs INVALID_GOAL / INVALID_JOINTS code in *code) when refused.
  virtual bool set_trajectory(const TrajGoal& goal, uint64_t goal_id, double now, std::string* why, int* code) = 0;
  // Cancel an action goal: stop (hold the current position, ramping over stop_trajectory_duration).
  virtual void cancel(uint64_t goal_id, double now) = 0;
  virtual std::vector<std::string> joints() const = 0;
  // state, command (JointTrajectory) and follow_joint_trajectory (TrajectoryGoal in, GoalResult out)
  void ports(const std::string& name, const std::string& robot_ns, const std::string& ns, std::vector<InputPort>* in,
             std::vector<OutputPort>* out) const override;
  void command(const std::string& leaf, const Command& value, double now, CommandResult* r) override;
};

}  // namespace control
}  // namespace car_sim
