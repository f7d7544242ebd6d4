// The controller types car's ros_control layer runs, one line each (docs/COMPAT-control.md). A new type adds its
// ctl_*.cpp (with its ports: Controller::ports) and one line here.
#include "controllers.hpp"

namespace car_sim {
namespace control {

std::unique_ptr<Controller> make_joint_state_controller();
std::unique_ptr<Controller> make_forward_controller(Interface i, bool group);
std::unique_ptr<Controller> make_pid_controller(bool velocity);
std::unique_ptr<Controller> make_diff_drive_controller();
std::unique_ptr<Controller> make_trajectory_controller(Interface i);

const std::vector<ControllerType>& controller_types() {
  using I = Interface;
  static const std::string base = "controller_interface::ControllerBase";
  static const std::vector<ControllerType> types = {
      {"joint_state_controller/JointStateController", base, [] { return make_joint_state_controller(); }},
      {"diff_drive_controller/DiffDriveController", base, [] { return make_diff_drive_controller(); }},
      {"position_controllers/JointPositionController", base, [] { return make_forward_controller(I::Position, false); }},
      {"velocity_controllers/JointVelocityController", base, [] { return make_forward_controller(I::Velocity, false); }},
      {"effort_controllers/JointEffortController", base, [] { return make_forward_controller(I::Effort, false); }},
      {"position_controllers/JointGroupPositionController", base, [] { return make_forward_controller(I::Position, true); }},
      {"velocity_controllers/JointGroupVelocityController", base, [] { return make_forward_controller(I::Velocity, true); }},
      {"effort_controllers/JointGroupEffortController", base, [] { return make_forward_controller(I::Effort, true); }},
      {"effort_controllers/JointPositionController", base, [] { return make_pid_controller(false); }},
      {"effort_controllers/JointVelocityController", base, [] { return make_pid_controller(true); }},
      {"position_controllers/JointTrajectoryController", base, [] { return make_trajectory_controller(I::Position); }},
      {"velocity_controllers/JointTrajectoryController", base, [] { return make_trajectory_controller(I::Velocity); }},
      {"effort_controllers/JointTrajectoryController", base, [] { return make_trajectory_controller(I::Effort); }},
  };
  return types;
}

}  // namespace control
}  // namespace car_sim
