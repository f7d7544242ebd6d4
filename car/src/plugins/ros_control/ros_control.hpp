// libgazebo_ros_control.so (gazebo_ros_control, Noetic) and the controllers it runs, per docs/COMPAT-control.md.
// The kind reads the URDF <transmission>s, offers each joint's position / velocity / effort interface, and runs a
// controller manager: controllers are loaded from a key/value configuration (the YAML keys of ros_controllers),
// started and stopped, and updated every control period. No ROS here: controller_manager's services are the
// instance's calls (CallType), each loaded controller's topics and action its dynamic ports; the ROS bridge serves
// them by type like every other port.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "car_sim/plugin.hpp"

namespace car_sim {

const PluginKind& ros_control_kind();

namespace control {

// A controller's configuration: key path ("pid/p", "gains/joint1/p", "joints") -> its values (one for a scalar,
// several for a list), as the parameter server holds them under <ns>/<controller name>/.
using Params = CallParams;

// A configuration or load error a user can act on; what() reads "controller 'NAME': KEY: REASON".
class ControllerError : public std::runtime_error {
 public:
  ControllerError(const std::string& controller, const std::string& key, const std::string& reason);
  const std::string& key() const { return key_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string key_, reason_;
};

// Typed reads of a controller's Params; throw ControllerError naming the controller and the key.
class ParamReader {
 public:
  ParamReader(const std::string& controller, const Params& p) : name_(controller), p_(p) {}
  bool has(const std::string& key) const;
  std::string text(const std::string& key) const;                 // required
  std::string text(const std::string& key, const std::string& def) const;
  double number(const std::string& key) const;                    // required
  double number(const std::string& key, double def) const;
  bool flag(const std::string& key, bool def) const;
  std::vector<std::string> list(const std::string& key) const;    // required; a scalar is a list of one
  std::vector<double> numbers(const std::string& key) const;      // required
  [[noreturn]] void fail(const std::string& key, const std::string& reason) const;
  const std::string& controller() const { return name_; }

 private:
  std::string name_;
  const Params& p_;
};

// control_toolbox::Pid (1.19.0) as the controllers and gazebo_ros_control's pid_gains use it: p, i, d, i_clamp (or
// i_clamp_min/i_clamp_max), antiwindup; docs/COMPAT-control.md "control_toolbox" has the rules.
struct Pid {
  double p = 0, i = 0, d = 0, i_min = 0, i_max = 0;
  bool antiwindup = false;
  double i_error = 0;  // the integral of the error [error s]; without antiwindup it winds up past the clamp
  double p_term = 0, i_term = 0, d_term = 0;
  double d_error = 0;        // the last error_dot [per s]
  double p_error_last = 0;   // the last error of compute(error, dt)
  bool valid_last = false;   // p_error_last holds an error
  // Reads KEY/p, KEY/i, ... (prefix "pid" or "gains/JOINT") as Pid::init: p is required; i_clamp gives
  // [-|c|, |c|]; i_clamp_min and i_clamp_max override one bound each, their signs forced.
  static Pid from(const ParamReader& r, const std::string& prefix);
  // error, its derivative [per s], dt [s] -> command; dt 0 or a non-finite input gives 0 and keeps the integral
  double compute(double error, double error_dot, double dt);
  // error, dt [s] -> command, its derivative (error - last error) / dt: the last derivative (0 at first) until
  // there is a last error, and for dt < 0 (control_toolbox's computeCommand(error, dt))
  double compute(double error, double dt);
  void reset() {
    i_error = p_term = i_term = d_term = d_error = p_error_last = 0;
    valid_last = false;
  }
};

enum class Interface { Position, Velocity, Effort };
const char* to_string(Interface i);  // "hardware_interface/PositionJointInterface", ...

// One joint as ros_control's hardware sees it: state (position, velocity, effort) and one command per interface.
struct JointIo {
  std::string name;
  int index = -1;               // RobotHandle joint index
  std::vector<Interface> interfaces;
  const Joint* joint = nullptr;
  double position = 0.0, velocity = 0.0, effort = 0.0;  // state: [rad|m], [rad/s|m/s], [N m|N] (last command)
  // Commands; `active` tells which interface a running controller claimed.
  double cmd_position = 0.0, cmd_velocity = 0.0, cmd_effort = 0.0;
  bool has(Interface i) const;
};

// What controllers see of the robot: the transmission joints and the robot's links (for odometry frames).
class Hardware {
 public:
  virtual ~Hardware() = default;
  // A joint offering interface i; throws ControllerError (controller, key) naming why not.
  virtual JointIo& claim(const std::string& controller, const std::string& key, const std::string& joint,
                         Interface i) = 0;
  virtual const RobotModel& model() const = 0;
  virtual ModelState root_state() const = 0;
};

// Control-loop time: the tick and its time [s], and the control period [s].
struct ControlTime {
  uint64_t tick = 0;
  double time = 0.0;    // [s] sim time
  double period = 0.0;  // [s] since the last update
};

// A controller's output at a tick (a joint state, an odometry, a controller state), tagged with its name; its
// `port` is the controller's output port it goes out on.
struct ControllerOutput : Output {
  std::string controller;
  std::string type;  // e.g. "joint_state_controller/JointStateController"
};

// A controller, the shape of controller_interface::ControllerBase: configure (init), starting, update, stopping.
class Controller {
 public:
  virtual ~Controller() = default;
  // Reads its keys and claims its joints; throws ControllerError.
  virtual void configure(const ParamReader& p, Hardware& hw) = 0;
  virtual void starting(const ControlTime& t) {}
  virtual void update(const ControlTime& t) = 0;
  virtual void stopping(const ControlTime& t) {}
  // Outputs due at this tick (publish_rate), pushed to out.
  virtual void publish(const ControlTime& t, OutputQueue* out) {}
  // (hardware interface, joints) it claims, for list_controllers and the switch's conflict check.
  virtual std::vector<std::pair<std::string, std::vector<std::string>>> claimed() const = 0;
  // Its ports, as ros_controllers names its topics: each port's name is "<its name>/<leaf>", its topic under
  // `ns` (/<robot namespace>/<its name>), or `robot_ns` for joint_state_controller's joint_states.
  virtual void ports(const std::string& name, const std::string& robot_ns, const std::string& ns,
                     std::vector<InputPort>* in, std::vector<OutputPort>* out) const {}
  // A value for its input port `leaf` (checked finite by the world), at sim time `now` [s]; refusals and log
  // lines go to *r.
  virtual void command(const std::string& leaf, const Command& value, double now, CommandResult* r) {}
};

struct ControllerType {
  std::string name;       // "diff_drive_controller/DiffDriveController"
  std::string base_class; // "controller_interface::ControllerBase"
  std::function<std::unique_ptr<Controller>()> make;
};

// Every controller type, in registration order (src/plugins/ros_control/controllers/registry.cpp).
const std::vector<ControllerType>& controller_types();
const ControllerType* find_controller_type(const std::string& name);

}  // namespace control

// The plug-in's configuration: <robotNamespace>, <controlPeriod> [s] (0: the physics step), <robotSimType>,
// <legacyModeNS>.
struct RosControlConfig {
  std::string plugin_name, robot_namespace, robot_sim_type;
  double control_period = 0.0;  // [s]
  bool legacy_mode_ns = true;
  static RosControlConfig from(const PluginConfig& c);
};

// The controller manager of one robot. Skins drive it between steps, through World::call and World::command.
class RosControl : public Plugin, public control::Hardware {
 public:
  struct Loaded {
    std::string name, type;
    bool running = false;
    // started by a switch, starting() not yet called: it is called at the next control update, after the joints
    // are read (controller_manager's manageSwitch in update()), so a controller started while paused holds the
    // joints where they are when the world plays (spawn_model -J, set_model_configuration)
    bool starting_due = false;
    // commands (not goals) that came while starting was due: given to it right after starting(), so that one sent
    // after the switch answered is not overwritten by starting's hold (upstream's switch returns once started)
    std::vector<std::pair<std::string, Command>> held;
    std::unique_ptr<control::Controller> controller;
  };

  RosControl(const PluginConfig& c, const std::string& robot);
  double update_rate() const override { return 0.0; }
  void configure(RobotHandle& robot) override;
  std::string summary() const override;
  void pre_physics(const StepContext& ctx, RobotHandle& robot) override;
  void post_physics(const StepContext& ctx, const RobotHandle& robot, OutputQueue* out) override;
  void reset() override;
  // The commands of the loaded controllers' input ports ("<controller>/<leaf>").
  void command(const std::string& port, const Command& value, CommandResult* result) override;
  // controller_manager's services (ServicePort names as its kind lists them: load_controller, ...).
  CallResponse call(const std::string& service, const CallRequest& request) override;
  // Every loaded controller's ports, in load order.
  void dynamic_ports(std::vector<InputPort>* inputs, std::vector<OutputPort>* outputs) const override;

  // controller_manager: throws control::ControllerError with the reason.
  void load(const std::string& name, const std::string& type, const control::Params& params);
  void unload(const std::string& name);
  // strict (2): any unknown, already running / stopped controller or a resource conflict fails the whole switch;
  // best effort (1): those are skipped. Returns false (with *why) when strict and refused.
  bool switch_controllers(const std::vector<std::string>& start, const std::vector<std::string>& stop, bool strict,
                          std::string* why);
  const std::vector<Loaded>& loaded() const { return loaded_; }
  control::Controller* controller(const std::string& name);
  const RosControlConfig& config() const { return cfg_; }

  // control::Hardware
  control::JointIo& claim(const std::string& controller, const std::string& key, const std::string& joint,
                          control::Interface i) override;
  const RobotModel& model() const override { return *model_; }
  ModelState root_state() const override { return root_; }

 private:
  void read(const RobotHandle& robot);
  control::ControlTime time_at(uint64_t tick, double dt) const;
  // gazebo_ros_control/pid_gains/JOINT/{p, i, d, ...} (the call "pid_gains"): see pids_
  void set_pid_gains(const control::Params& params, CallResponse* r);
  // joint k's position command clamped to its <limit lower upper> (revolute, prismatic), as joint_limits_interface
  double position_command(size_t k) const;

  RosControlConfig cfg_;
  const RobotModel* model_ = nullptr;
  std::vector<control::JointIo> joints_;
  std::vector<int> motors_;
  std::vector<std::vector<const Link*>> subtree_;  // per joint: the links it moves (its child and below)
  std::vector<int> modes_;  // per joint: the Interface a running controller commands, -1: the first offered
  // per joint: its pid_gains, if any. Then its position and velocity commands are followed by that PID's effort
  // (DefaultRobotHWSim's POSITION_PID, VELOCITY_PID) instead of its motor
  std::vector<std::optional<control::Pid>> pids_;
  std::vector<Loaded> loaded_;
  ModelState root_;
  std::string ns_;   // the robot namespace its topics go under ("" = global), leading '/' dropped
  double now_ = 0;   // [s] sim time of the last step (for commands between steps)
  uint64_t period_ticks_ = 1, last_update_ = 0;
  double dt_ = 0.0;
  bool first_ = true;
};

}  // namespace car_sim
