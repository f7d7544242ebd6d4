// The simulated world: an SDF world description (const), robots spawned into it with their plug-ins, and a
// Bullet dynamics world stepped in integer ticks of a fixed step. No ROS headers; nothing here reads a clock or
// sleeps. A step has phases: every plug-in's pre_physics, one physics step, then every plug-in's track and (when
// its schedule is due) post_physics.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "car_sim/description.hpp"
#include "car_sim/drive.hpp"
#include "car_sim/model.hpp"
#include "car_sim/plugin.hpp"
#include "car_sim/plugins.hpp"
#include "car_sim/sdf_model.hpp"
#include "car_sim/state.hpp"

namespace car_sim {

struct WorldOptions {
  int solver_iterations = 10;        // at most this many sequential-impulse iterations per step
  double residual_threshold = 1e-9;  // [(m/s)^2] converged: stop iterating early
  uint64_t seed = 0;                 // noise: each plug-in's generator is seeded from (seed, robot/plug-in)
};

// One plug-in instance of a spawned robot, for the skins.
struct PluginInfo {
  std::string robot;
  PluginConfig config;          // kind, names, every resolved key
  const PluginKind* kind = nullptr;
  std::string link;             // the link it is on or measures ("" for the whole model)
  double rate = 0.0;            // [Hz], 0 = every step
  bool lazy = false;            // computed only while active (someone listens)
  std::vector<InputPort> inputs;    // its input ports, topics resolved (the kind's `inputs`)
  std::vector<OutputPort> outputs;  // its output ports, topics and frames resolved (the kind's `outputs`)
  std::vector<ServicePort> services;  // its services, names resolved (the kind's `services`)
  std::string summary;              // what it bound to when configured (Plugin::summary), for the log
};

// What a spawned robot is, for the skins: its model, resolved plug-ins and namespace.
struct RobotInfo {
  std::string name;
  std::string robot_namespace;  // as given at spawn ("" when none)
  RobotModel model;
  ModelConfig config;
  Eigen::Isometry3d spawn_pose = Eigen::Isometry3d::Identity();
};

// ---- the gazebo_ros API's records (World's "gazebo_ros API" section; docs/COMPAT.md) ----------------------------

// A link of a model, found by Gazebo's scoped name "MODEL::LINK" or by its plain name.
struct LinkRef {
  std::string model, link;
  bool robot = false;  // a spawned robot (else a world model)
};

struct LinkProperties {
  double mass = 0.0;                                       // [kg]
  Eigen::Vector3d com = Eigen::Vector3d::Zero();           // [m], link frame
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();       // [kg m^2] about the com, link-frame axes
  bool gravity = true;
};

struct ModelProperties {
  std::vector<std::string> bodies;      // links that are bodies (fixed joints merge a child into its parent)
  std::vector<std::string> geoms;       // collision names, Gazebo's URDF naming: LINK_collision[_N]
  std::vector<std::string> joints;      // Gazebo's Model::GetJoints: moving and fixed (not car's static anchors)
  bool is_static = false;               // the model's <static>
};

struct JointProperties {
  std::string model;
  JointType type = JointType::Revolute;
  double position = 0.0;  // [rad] or [m]; a fixed joint NaN (0 on a static model), as Gazebo's Joint::Position
  double velocity = 0.0;  // [rad/s] or [m/s]; a fixed joint 0
  double damping = 0.0;   // URDF <dynamics damping>
};

class World {
 public:
  explicit World(WorldDescription desc, WorldOptions options = WorldOptions());
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  const WorldDescription& description() const { return desc_; }
  double dt() const { return desc_.step_size; }
  uint64_t tick() const { return tick_; }
  double time() const { return static_cast<double>(tick_) * desc_.step_size; }  // [s]

  // Adds a robot with its plug-ins. Throws std::invalid_argument when the name exists, LoadError for a bad model.
  // A non-empty robot_namespace is added to every plug-in without <robotNamespace>, as gazebo_ros does.
  void spawn(const RobotModel& model, const std::string& name, const Eigen::Isometry3d& pose,
             const std::string& robot_namespace = "");
  // Adds an SDF robot (load_sdf_model_string) the same way: its root link at pose * robot.root_pose (the spawn pose
  // on top of the document's model pose, as gazebo_ros's spawn_sdf_model; docs/COMPAT-sdf.md).
  void spawn_sdf(const SdfRobot& robot, const std::string& name, const Eigen::Isometry3d& pose,
                 const std::string& robot_namespace = "");
  // Adds a robot-level plug-in to a spawned robot (e.g. the ground-truth publisher the ROS node attaches).
  // Throws LoadError for a bad plug-in, std::invalid_argument for an unknown robot or a taken plug-in name.
  void attach_plugin(const std::string& robot, const PluginSpec& spec);
  // Removes a robot or world model. Throws std::invalid_argument when there is none of that name.
  void remove(const std::string& name);

  // Advances n fixed steps.
  void step(uint64_t n = 1);
  // Time to zero, every model back to where it started, plug-ins reset (reset_simulation).
  void reset();
  // Models back to where they started, time goes on (reset_world).
  void reset_poses();
  // Time to zero, nothing else reset: the models, their motors and the plug-ins' state stay; every plug-in's schedule
  // and clock restart from tick 0 (Gazebo's World::ResetTime and its time-reset event). Wrench and effort jobs keep
  // their sim times, as gazebo_ros's do.
  void reset_time();

  std::vector<std::string> model_names() const;  // world models first, then robots in spawn order
  bool has_model(const std::string& name) const;
  ModelState model_state(const std::string& name) const;
  // Pose and twist of the model frame, world frame; its nested models move along. A static model takes the pose
  // and ignores the twist (docs/COMPAT.md set_model_state). Throws for an unknown model or a non-finite state.
  void set_model_state(const std::string& name, const ModelState& s);
  const RobotInfo& robot(const std::string& name) const;
  std::vector<std::string> robot_names() const;
  size_t robot_count() const;  // robot_names().size(), without the copy

  // Every non-fixed joint of a robot, in URDF order.
  std::vector<JointState> joint_states(const std::string& robot) const;
  // Pose of a robot link in the world (fixed-joint children included).
  Eigen::Isometry3d link_pose(const std::string& robot, const std::string& link) const;

  // Every plug-in instance of every robot, in spawn order; lazy ones compute only while active.
  std::vector<PluginInfo> plugins() const;
  // The lazy ones (measurements): what Python's sensors() lists.
  std::vector<PluginInfo> sensors() const;
  void set_plugin_active(const std::string& robot, const std::string& plugin, bool active);
  void set_sensor_active(const std::string& robot, const std::string& plugin, bool active) {
    set_plugin_active(robot, plugin, active);
  }
  // A robot's plug-in instance (for tests and the controller layer); nullptr when none.
  Plugin* plugin(const std::string& robot, const std::string& name);

  // A value for an input port of a plug-in instance (PluginInfo::inputs), between steps: the one way a command
  // enters the core. A value with a non-finite number (of the components a Twist port reads) is not passed on:
  // the result says so, for the skin's one warning. Unknown robots, plug-ins and ports, and a value of another
  // type than the port's, throw std::invalid_argument.
  CommandResult command(const std::string& robot, const std::string& plugin, const std::string& port, Command value);
  // A call to a service of a plug-in instance (PluginInfo::services), between steps. When it changed the
  // instance's ports (ros_control loaded or unloaded a controller) the response says so and plugin_info() lists
  // them anew. Unknown robots, plug-ins and services throw std::invalid_argument.
  CallResponse call(const std::string& robot, const std::string& plugin, const std::string& service,
                    const CallRequest& request);
  // One plug-in instance's record, its ports as they are now; throws std::invalid_argument when there is none.
  const PluginInfo& plugin_info(const std::string& robot, const std::string& plugin) const;

  // Every output produced since the last call, in instance order.
  OutputQueue take_outputs();
  // The outputs of one type only (others stay queued), moved out.
  template <class T>
  std::vector<T> take_outputs() {
    std::vector<T> out;
    for (OutputPtr& o : take_outputs_if([](const Output& x) { return dynamic_cast<const T*>(&x) != nullptr; }))
      out.push_back(std::move(static_cast<T&>(*o)));
    return out;
  }
  OutputQueue take_outputs_if(const std::function<bool(const Output&)>& pick);

  // Commands every Twist input of the robot's plug-ins (its drives): v [m/s] forward, w [rad/s] about z.
  // Non-finite values and unknown robots throw std::invalid_argument; a robot without a drive ignores the command.
  void set_cmd_vel(const std::string& robot, double v, double w);
  void set_cmd_vel(const std::string& robot, const Twist& cmd);
  // Odometry produced since the last call (the drive plug-ins' outputs).
  std::vector<OdometryOut> take_odometry() { return take_outputs<OdometryOut>(); }

  // Contacts of the last step with a positive normal force.
  std::vector<Contact> contacts() const;

  // ---- gazebo_ros API (world.cpp, physics side in src/physics/services.cpp) -------------------------------
  // Errors are std::invalid_argument with the reason; a failed call leaves the world untouched.

  // A link by "MODEL::LINK" or plain "LINK" (the first model in model_names() order that has one).
  LinkRef find_link(const std::string& name) const;
  // A link's pose and twist, world frame (twist of the link frame's origin).
  ModelState link_state(const LinkRef& link) const;
  // Moves the link's whole model rigidly so that the link gets pose and twist (world frame); joint positions and
  // speeds are kept. Throws for an unknown link or a non-finite state.
  void set_link_state(const LinkRef& link, const ModelState& s);
  LinkProperties link_properties(const LinkRef& link) const;
  ModelProperties model_properties(const std::string& model) const;
  // A joint, moving or fixed (not car's anchors of a static model), by "MODEL::JOINT" or plain "JOINT" (the first
  // robot that has one).
  JointProperties joint_properties(const std::string& joint) const;
  // Sets joint positions [rad] or [m] of a robot (their speeds to zero; keep_speeds: the speeds stay, as Gazebo's
  // Joint::SetPosition with _preserveWorldVelocity); the root link stays where it is. Throws for an unknown model or
  // joint or a non-finite position, before changing anything.
  void set_joint_positions(const std::string& model, const std::vector<std::string>& joints,
                           const std::vector<double>& positions, bool keep_speeds = false);
  // Centre of mass [m], world frame, of the body that carries a link.
  Eigen::Vector3d body_com(const LinkRef& link) const;
  // Force [N] and torque [N m], world frame, at the carrying body's com, on every step that starts at a sim time t
  // with start <= t <= start + duration (duration < 0: until cleared); start before now means now.
  void apply_wrench(const LinkRef& link, const Eigen::Vector3d& force, const Eigen::Vector3d& torque, double start,
                    double duration);
  // Effort [N m] or [N] on a moving joint, with the same timing.
  void apply_joint_effort(const std::string& joint, double effort, double start, double duration);
  // Removes every wrench job on a link (by its scoped or plain name) / effort job on a joint; the count removed.
  int clear_wrenches(const std::string& link);
  int clear_joint_efforts(const std::string& joint);
  Eigen::Vector3d gravity() const;  // [m/s^2], world frame
  void set_gravity(const Eigen::Vector3d& g);
  int solver_iterations() const;
  void set_solver_iterations(int n);

  // ---- users' own plug-ins: the calls Gazebo 11's C++ API (src/gazebo/, docs/PLUGINS.md) is built on -------------
  // Errors are std::invalid_argument with the reason (an unknown model, link or joint; a non-finite number).

  // Whether a step integrates the physics (Gazebo's World::PhysicsEnabled; joint_pose_trajectory switches it off).
  bool physics_enabled() const;
  // Switches it (Gazebo's World::SetPhysicsEnabled): off, a step advances time and calls the plug-ins only.
  void set_physics_enabled(bool on);
  // What add_link_wrench and the plug-ins added to a robot's link in the current step (cleared as a step starts):
  // force [N] and torque [N m] about the link's body's centre of mass, world frame (Gazebo's Link::WorldForce,
  // WorldTorque). Throws for an unknown robot or link.
  Wrench link_applied_wrench(const LinkRef& link) const;
  // Per-step hooks, called in the order they were added. BeforePhysics: at the start of every step, before the
  // plug-ins' pre_physics, with the tick the step starts from; AfterPhysics: after the physics step, before the
  // plug-ins' track, with the tick reached. A hook may call the commands below; one added inside a hook is first
  // called at its phase's next call, one removed is not called again. With no hook a step calls nothing.
  enum class StepPhase { BeforePhysics, AfterPhysics };
  using StepHook = std::function<void(uint64_t tick)>;
  // Returns the hook's id (never 0).
  uint64_t add_step_hook(StepPhase phase, StepHook hook);
  // Removes a hook (a step, pause, stop or time-reset hook); an unknown id is nothing.
  void remove_step_hook(uint64_t id);

  // Whether the world is paused (Gazebo's World::IsPaused): a flag for the pacer, which steps only while it is false
  // (the ROS node's pause_physics and unpause_physics set it); step() itself runs whatever it says. set_paused calls
  // the pause hooks, with the new value, only when the flag changes (Gazebo's World::SetPaused and
  // event::Events::pause).
  bool paused() const;
  void set_paused(bool paused);
  uint64_t add_pause_hook(std::function<void(bool paused)> hook);
  // The world stops: the stop hooks run once, at the first stop() or in the destructor, before any plug-in goes
  // (Gazebo's World::Stop and event::Events::stop, at the server's end).
  uint64_t add_stop_hook(std::function<void()> hook);
  void stop();
  // Time went back to 0 (Gazebo's event::Events::timeReset, raised in World::ResetTime only): the time-reset hooks
  // run once in reset_time(), after the plug-ins' schedules restart, and once in reset(), before any plug-in's
  // reset; reset_poses() runs none (gazebo_ros's reset_world leaves time alone). On the calling thread.
  uint64_t add_time_reset_hook(std::function<void()> hook);
  // Work for between steps, in the order given (Gazebo's World::ProcessMessages: models inserted by a plug-in):
  // step() runs it at the end of each step, after every plug-in's post_physics; run_deferred() runs it now (the
  // pacer calls it while paused, as Gazebo processes its messages while paused). Work deferred by deferred work runs
  // at the next call.
  void defer(std::function<void()> work);
  void run_deferred();

  // The world's own <plugin>s (WorldDescription::plugins) that load from libraries, loaded when the World is made,
  // after the world's models (docs/COMPAT-plugins.md "World and system plug-ins"); what loading them found (the
  // messages of a plug-in not found or not loaded), for the skins to log.
  const std::vector<Diagnostic>& world_diagnostics() const;
  // A system plug-in (gzserver's -s FILE): looked for as a model's plug-in file, then loaded with Load(args) and
  // Init(), held until the World goes. Returns what loading it found (empty: it runs).
  std::vector<Diagnostic> load_system_plugin(const std::string& filename, const std::vector<std::string>& args);

  // A force [N] acting at `point` [m] and a torque [N m] on a robot's link for the coming step only (Gazebo's
  // Link::AddForce family). Frame::World: force and torque in world axes, point a world position; Frame::Link:
  // in the link's axes, point relative to the link's origin. Called between steps or in a BeforePhysics hook.
  enum class Frame { World, Link };
  void add_link_wrench(const LinkRef& link, const Eigen::Vector3d& force, const Eigen::Vector3d& torque,
                       const Eigen::Vector3d& point, Frame frame);
  // A moving joint's position [rad] or [m] and velocity [rad/s] or [m/s].
  double joint_position(const std::string& robot, const std::string& joint) const;
  double joint_velocity(const std::string& robot, const std::string& joint) const;
  // An effort [N m] or [N] on a moving joint for the coming step only, clamped to its <limit effort> when that is
  // > 0 (Gazebo's Joint::SetForce). Efforts given in one step add up. Returns the effort applied.
  double add_joint_force(const std::string& robot, const std::string& joint, double effort);
  // Sets a moving joint's velocity [rad/s] or [m/s] now (Gazebo's Joint::SetVelocity); its position stays.
  void set_joint_velocity(const std::string& robot, const std::string& joint, double velocity);
  // Sets a link's velocity now: `linear` [m/s] of its centre of mass and `angular` [rad/s], world frame (Gazebo's
  // Link::SetLinearVel / SetAngularVel). The link's whole model takes that rigid motion; joint speeds are kept.
  void set_link_velocity(const LinkRef& link, const Eigen::Vector3d& linear, const Eigen::Vector3d& angular);
  // A velocity motor on a moving joint, as ODE's joint motor (Gazebo's Joint::SetParam "vel", "fmax", "friction";
  // docs/PLUGINS.md): every step it drives the joint's rate to `velocity` [rad/s] or [m/s] with at most
  // `max_effort` [N m] or [N], so it reaches the target within the step when that effort suffices. max_effort 0: off.
  // Not capped by the joint's <limit effort> or <limit velocity> (ODE's motor is not). Kept until changed, over
  // resets too. Throws for an unknown robot or joint, a non-finite number or max_effort < 0.
  struct JointMotor {
    double velocity = 0.0;    // [rad/s] or [m/s]
    double max_effort = 0.0;  // [N m] or [N]
  };
  void set_joint_motor(const std::string& robot, const std::string& joint, const JointMotor& motor);
  // The motor's setting; {0, 0} before any set_joint_motor.
  JointMotor joint_motor(const std::string& robot, const std::string& joint) const;
  // Gazebo's Link::SetGravityMode: with `on` false, gravity no longer acts on the link's mass (at its centre of mass;
  // a body's top link carries the links merged into it by fixed joints, as Gazebo lumps them), from the coming step
  // on. Kept over resets. Throws for an unknown robot or link.
  void set_link_gravity(const LinkRef& link, bool on);
  bool link_gravity(const LinkRef& link) const;

 private:
  struct Impl;
  const WorldDescription desc_;
  WorldOptions options_;
  uint64_t tick_ = 0;
  std::set<std::string> removed_;  // world models deleted at run time (a reset does not bring them back)
  std::unique_ptr<Impl> impl_;
};

// Advances every world n steps, the worlds on car's thread pool (include/car_sim/parallel.hpp), one world per item;
// inside each, the world's own parallel loops run serially on its thread (the pool's nested-loop rule). The worlds
// must be distinct (std::invalid_argument otherwise, before any is stepped). Every world is stepped even when one
// throws; then the exception of the first failing world in list order is rethrown. The result is the same bit for
// bit as stepping each world alone, in any order, on any number of threads.
void step_worlds(const std::vector<World*>& worlds, uint64_t n = 1);

// ---- the numbers the gazebo_ros API takes (docs/COMPAT.md "Every service") ---------------------------------------
// World's methods run these checks before they look up any name; a skin that answers a bad number before its own
// look-ups (the ROS services: a reference frame) calls the same check first. Each throws std::invalid_argument
// with the reason, to which the ROS services put their name in front ("SetModelState: pose and twist ...").

// Every number of a pose and twist: "pose and twist must be finite numbers".
void check_state(const ModelState& s);
// A joint effort [N m] or [N]: "effort must be a finite number".
void check_effort(double effort);
// gazebo_msgs/SetPhysicsProperties' numbers: gravity [m/s^2], time_step [s] and max_update_rate [Hz] finite, and the
// rate >= 0 (steps per wall second, 0 = as fast as possible: the skin's pace, which no World holds):
// "gravity, time_step and max_update_rate must be finite (max_update_rate >= 0)".
void check_physics_properties(const Eigen::Vector3d& gravity, double time_step, double max_update_rate);
// Steps of dt [s] from sim time now [s] to the first step at or after sim time t [s]: where a skin stops a run
// (the ROS node's ~pause_at). nullopt unless t is a finite time after now.
std::optional<uint64_t> steps_until(double now, double t, double dt);

}  // namespace car_sim
