// Plug-ins as parts: what a plug-in kind declares (its Gazebo file names, schema, validation, factory) and what
// an instance does on the world's step (configure, pre_physics, track, post_physics, reset), each on one
// integer-tick schedule. The shape of gz-sim's systems and MuJoCo's plug-in callbacks, in car's words.
// No ROS headers; a kind never sees Bullet: it acts on its robot through RobotHandle.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "car_sim/model.hpp"
#include "car_sim/plugins.hpp"
#include "car_sim/ports.hpp"
#include "car_sim/raycast.hpp"
#include "car_sim/state.hpp"

namespace car_sim {

class World;

// ---- outputs ----------------------------------------------------------------------------------------------

// Lists an output's fields for consumers that do not know its type (the Python module, the batch runner).
class FieldVisitor {
 public:
  virtual ~FieldVisitor() = default;
  virtual void number(const char* key, double v) = 0;
  virtual void integer(const char* key, int64_t v) = 0;
  virtual void text(const char* key, const std::string& v) = 0;
  // A short vector (a position, a quaternion): a list in Python.
  virtual void vector(const char* key, const double* v, size_t n) = 0;
  // Bulk data, row-major with the given shape: a NumPy array in Python.
  virtual void array(const char* key, const float* data, const std::vector<size_t>& shape) = 0;
  virtual void array(const char* key, const uint8_t* data, const std::vector<size_t>& shape) = 0;
};

// A measurement or message one plug-in instance produced at one tick. Each kind has its own type.
struct Output {
  virtual ~Output() = default;
  std::string robot, plugin;  // stamped by the world
  uint64_t tick = 0;          // stamped by the world
  std::string port;           // the one output port it is for ("": every port of its instance)
  virtual void visit(FieldVisitor& v) const = 0;
  // Its samples (include/car_sim/ports.hpp: the table Sample), each once: for every port of its type, or named for
  // one port, or with its frame (SampleList::add). None by default.
  virtual void samples(SampleList& list) const {}
  // The sample of type S a port named `port` reading frame `frame` takes (SampleList::find), for readers other than
  // the ROS bridge (car_gazebo's sensors, tests): a pointer where Sample holds S by pointer, else an optional copy.
  template <class S>
  SampleHandle<S> sample_of(std::string_view port = {}, size_t frame = 0) const {
    SampleList list;
    samples(list);
    const Sample s = list.find(sample_type<S>(), port, frame);
    if constexpr (detail::kByPointer<S>) {
      const auto* p = std::get_if<const S*>(&s);
      return p ? *p : nullptr;
    } else {
      const auto* p = std::get_if<S>(&s);
      return p ? std::optional<S>(*p) : std::nullopt;
    }
  }
};
using OutputPtr = std::unique_ptr<Output>;
using OutputQueue = std::vector<OutputPtr>;

// ---- schedule ---------------------------------------------------------------------------------------------

// The update clock of gazebo_ros's UpdateChild (the diff drive, skid steer and tricycle, the joint state publisher;
// docs/COMPAT-plugins.md "the update and the wheel ramp"): a call at sim time t updates when (t - last).Double() >
// 1 / updateRate (strictly; every call with updateRate <= 0), and then `last_update_time_ +=
// common::Time(update_period_)`; last starts at the load. Gazebo calls a plug-in at the sim time after the step
// whose state it reads, so the call that reads tick k's state is at tick k + 1. Whole nanoseconds, as common::Time.
class UpdateClock {
 public:
  UpdateClock() = default;
  explicit UpdateClock(double rate)
      : period_(rate > 0 ? 1.0 / rate : 0.0), period_ns_(rate > 0 ? common_time_ns(1.0 / rate) : 0) {}
  // last = the sim time of tick (the load's, or a reset's).
  void start(uint64_t tick, double dt) {
    started_ = true;
    last_ns_ = tick_time_ns(tick, dt);
  }
  // start() at the first call after construction or restart(): a plug-in learns the tick in its first pre_physics.
  void begin(uint64_t tick, double dt) {
    if (!started_) start(tick, dt);
  }
  void restart() { started_ = false; }
  // seconds_since_last_update [s] of the call that reads tick's state.
  double seconds(uint64_t tick, double dt) const { return common_time_double(tick_time_ns(tick + 1, dt) - last_ns_); }
  // That call updates.
  bool due(uint64_t tick, double dt) const { return seconds(tick, dt) > period_; }
  // At an update: seconds_since_last_update, and last moves on by the period (never, with updateRate 0: the time
  // since the load, as upstream).
  double since(uint64_t tick, double dt) {
    const double s = seconds(tick, dt);
    last_ns_ += period_ns_;
    return s;
  }

 private:
  double period_ = 0.0;    // [s] update_period_, 1 / updateRate as a double
  int64_t period_ns_ = 0;  // [ns] common::Time(update_period_)
  int64_t last_ns_ = 0;    // [ns] last_update_time_
  bool started_ = false;
};

// Updates at ticks start + ceil(k * num / den), k = 1, 2, ...: a period of num/den ticks, so a rate such as
// 5.5 Hz at 1 ms (2000/11 ticks) stays on its schedule exactly, with integer arithmetic only.
// Schedule::absolute instead keeps hector's UpdateTimer grid of absolute sim time (docs/COMPAT-sensors.md), and
// Schedule::update_clock gazebo_ros's UpdateChild rule (UpdateClock).
class Schedule {
 public:
  Schedule() = default;
  // rate [Hz] at step dt [s]; rate <= 0 means every step.
  Schedule(double rate, double dt, uint64_t start_tick);
  // Due at a tick whose sim time t [ns] has fmod(common::Time(t - offset_ns).Double() + dt / 2, period) in
  // [0, dt), as hector's UpdateTimer::checkUpdate; period [s] 0: every step. Neither the start nor a restart
  // moves the grid.
  static Schedule absolute(double period, int64_t offset_ns, double dt);
  // Due by UpdateClock(rate)'s rule, the clock started at start_tick and again at each restart.
  static Schedule update_clock(double rate, double dt, uint64_t start_tick);
  // The rate control of gazebo_ros's p3d, imu (model plug-in) and ft_sensor: the call at tick k's sim time t
  // publishes unless (t - last).Double() < 1.0 / rate, and then last = t. last starts at start_tick's time, or at 0
  // (from_zero: ft_sensor's default-constructed last_time_); a restart sets it the same way. rate <= 0: every step.
  // At 30 Hz and 1 ms that is every 34 ms (29.4 Hz), as upstream.
  static Schedule since_last(double rate, double dt, uint64_t start_tick, bool from_zero);
  bool due(uint64_t tick) const {
    switch (mode_) {
      case Mode::Absolute: return absolute_due(tick);
      case Mode::Clock: return clock_.due(tick, dt_);
      case Mode::SinceLast:
        return !(period_ > 0.0) || !(common_time_double(tick_time_ns(tick, dt_) - last_ns_) < period_);
      default: return tick >= next_;
    }
  }
  // After a due tick: the next one (never in the past, so a pause in activity gives no burst).
  void advance(uint64_t tick);
  void restart(uint64_t start_tick);

 private:
  bool absolute_due(uint64_t tick) const;
  enum class Mode { Count, Absolute, Clock, SinceLast };
  Mode mode_ = Mode::Count;
  uint64_t num_ = 1, den_ = 1;  // period [ticks] = num / den
  uint64_t start_ = 0, k_ = 0;
  uint64_t next_ = 1;
  double period_ = 0.0, dt_ = 0.0;  // [s]; SinceLast: 1.0 / rate
  int64_t offset_ns_ = 0;           // [ns] Absolute: the grid's offset
  int64_t last_ns_ = 0;             // [ns] SinceLast: the last publication's time
  bool from_zero_ = false;
  UpdateClock clock_;
};

// ---- what a plug-in may read and do -----------------------------------------------------------------------

// A plug-in's robot. Read access any time; actuation (motors, efforts) in configure and pre_physics only.
class RobotHandle {
 public:
  virtual ~RobotHandle() = default;
  virtual const std::string& name() const = 0;
  virtual const RobotModel& model() const = 0;
  virtual const Eigen::Isometry3d& spawn_pose() const = 0;

  // A non-fixed joint's index, -1 when the robot has none of that name.
  virtual int joint(const std::string& name) const = 0;
  virtual double joint_position(int joint) const = 0;  // [rad] or [m]
  virtual double joint_velocity(int joint) const = 0;  // [rad/s] or [m/s]
  // A motor on a joint with an effort cap [N m] or [N]; returns its id. In configure only.
  virtual int add_motor(int joint, double max_effort) = 0;
  virtual void set_motor(int motor, const MotorTarget& target) = 0;

  // A link's frame in the world (fixed-joint children included); throws for an unknown link.
  virtual Eigen::Isometry3d link_pose(const std::string& link) const = 0;
  // A link's frame with the velocity of its origin, world frame; throws for an unknown link.
  virtual ModelState link_state(const std::string& link) const = 0;
  // The model frame (Gazebo's Model::WorldPose: the root link's frame for a URDF robot; an SDF model's own frame),
  // with the velocity of the root link's origin (Model::WorldLinearVel), world frame.
  virtual ModelState root_state() const = 0;

  // ---- motion and contact (issue 11) ----
  // Adds a force [N] and a torque [N m] on a link for the coming step only, the force acting at `point` [m].
  // in_link_frame: force, torque and point in the link's frame (point relative to its origin); else world frame
  // (point a world position). In pre_physics only. Throws for an unknown link.
  virtual void apply_wrench(const std::string& link, const Wrench& w, const Eigen::Vector3d& point,
                            bool in_link_frame) = 0;
  // The sum of what apply_wrench added to a link for the last step: force [N] and torque [N m] about the link's
  // centre of mass, world frame (zero when nothing was applied). Throws for an unknown link.
  virtual Wrench applied_wrench(const std::string& link) const = 0;
  // Sets the root's velocity, world frame: linear [m/s] of the root frame's origin, angular [rad/s]. The pose stays.
  virtual void set_root_velocity(const Eigen::Vector3d& linear, const Eigen::Vector3d& angular) = 0;
  // Sets a joint's position [rad] or [m] and its velocity to 0.
  virtual void set_joint_position(int joint, double position) = 0;
  // The world's physics switch (Gazebo's World::SetPhysicsEnabled): while off, each step advances sim time and
  // integrates nothing; only what plug-ins set (joint positions) moves. Velocities are kept for when it is back on.
  virtual bool physics_enabled() const = 0;
  virtual void set_physics_enabled(bool on) = 0;
  // Measure the joint's reaction wrench from now on (in configure). Throws for a joint that is not moving.
  virtual void enable_joint_wrench(int joint) = 0;
  // The wrench the joint exerted on its child link during the last step: force [N] and torque [N m] about the child
  // link's origin, in the child link's frame. Needs enable_joint_wrench.
  virtual Wrench joint_wrench(int joint) const = 0;
  // Contacts of a link's body (the rigid body it was merged into) during the last step, with a positive force.
  virtual std::vector<LinkContact> link_contacts(const std::string& link) const = 0;

  // ---- ros_control (docs/COMPAT-control.md) ----
  // Adds an effort [N m] or [N] on a joint for the coming step only (clamped to its <limit effort> when > 0).
  // In pre_physics only.
  virtual void add_joint_effort(int joint, double effort) = 0;
};

// What a plug-in may read of the world at a step.
class WorldAccess {
 public:
  virtual ~WorldAccess() = default;
  virtual const Environment& environment() const = 0;
  // The ray scene with every body where it is at this tick (built on first use in a step).
  virtual const RayScene& rays() const = 0;
  // Contacts of the last step with a positive normal force.
  virtual std::vector<Contact> contacts() const = 0;
};

struct StepContext {
  uint64_t tick = 0;   // the tick the step starts from (pre_physics) or has reached (track, post_physics)
  double dt = 0.0;     // [s] physics step
  const WorldAccess* world = nullptr;
  double time() const { return static_cast<double>(tick) * dt; }  // [s]
};

// ---- instances --------------------------------------------------------------------------------------------

class Plugin {
 public:
  virtual ~Plugin() = default;
  // [Hz] of post_physics; 0 = every step.
  virtual double update_rate() const = 0;
  // When post_physics is due, for a plug-in configured at start_tick with step dt [s]: whole periods of
  // update_rate() from start_tick unless the kind keeps upstream's own clock (Schedule::absolute, update_clock,
  // since_last).
  virtual Schedule schedule(double dt, uint64_t start_tick) const { return Schedule(update_rate(), dt, start_tick); }
  // Joints this plug-in drives. Asked before the robot's physics is built (a driven caster keeps its friction).
  virtual std::vector<std::string> driven_joints() const { return {}; }
  // Binds to the robot: looks its joints and links up, adds motors. Once, after the robot's bodies exist.
  virtual void configure(RobotHandle& robot) {}
  // What configure found, for the log line that says what loaded ("2 transmissions, 2 joints"); "" for nothing
  // beyond the ports.
  virtual std::string summary() const { return ""; }
  // Every step, before physics: motor targets, forces.
  virtual void pre_physics(const StepContext& ctx, RobotHandle& robot) {}
  // Every step after physics, read-only: integrators between updates. A lazy plug-in only while active.
  virtual void track(const StepContext& ctx, const RobotHandle& robot) {}
  // When the schedule is due (a lazy plug-in: and active), read-only: measure, push outputs.
  virtual void post_physics(const StepContext& ctx, const RobotHandle& robot, OutputQueue* out) {}
  // Whether post_physics may run on a thread beside other robots' plug-ins: it reads only its robot and the world's
  // ray scene and writes only its own members and queue. The due ones of a step then share the threads (a fleet's
  // lidars, all due at the same tick), each queue's outputs the same as one by one.
  virtual bool concurrent() const { return false; }
  // When the schedule is due while a lazy plug-in is off, read-only: the state upstream's sensor keeps between
  // measurements whether or not anyone subscribes (an IMU's last velocity). No outputs, no noise drawn.
  virtual void idle(const StepContext& ctx, const RobotHandle& robot) {}
  // Sim time starts at `tick` for this plug-in: at its load (after configure), and at 0 when time goes back
  // (reset_simulation: Gazebo's time-reset event). Its schedule restarts there too.
  virtual void start_clock(uint64_t tick) {}
  // Once its robot is in the world, after every plug-in of the robot is configured: a plug-in from a shared library
  // (src/plugins/shared_library/) loads here, with World's public API, which is what it runs on. What goes wrong
  // goes to *diagnostics (the robot's), and the robot stays. No kind of car's own needs it.
  virtual void loaded(World& world, std::vector<Diagnostic>* diagnostics) {}
  // Back to the state right after configure (a world reset put the robot back at its spawn pose).
  virtual void reset() {}
  // Whether a reset that keeps time (reset_world) restarts its schedule at the reset's tick, as upstream's Reset
  // of gazebo_ros_diff_drive does (last_update_time_ = now). Gazebo's sensors and the plug-ins without such a Reset
  // keep their phase: no time-reset event fires. A reset that takes time back (reset_simulation) restarts every
  // schedule.
  virtual bool restarts_schedule_on_reset_world() const { return false; }
  // A lazy plug-in was switched on or off.
  virtual void set_active(bool active) {}
  // Which parts of its outputs anyone takes, a bit per part as its kind defines them (all bits: everything, the
  // default). A plug-in may leave the other parts out of the outputs it makes from then on; a kind without parts
  // ignores this.
  virtual void set_parts(uint32_t parts) {}
  // A value for one of its input ports (World::command has checked that it fits the port and is finite); notes
  // for the log go to *result. Between steps only.
  virtual void command(const std::string& port, const Command& value, CommandResult* result) {}
  // A call to one of its services (PluginInfo::services), between steps.
  virtual CallResponse call(const std::string& service, const CallRequest& request) {
    CallResponse r;
    r.ok = false;
    r.errors.push_back("no service '" + service + "'");
    return r;
  }
  // Ports that come and go at run time (ros_control's controllers), after its kind's own; asked again after every
  // call whose response says ports_changed.
  virtual void dynamic_ports(std::vector<InputPort>* inputs, std::vector<OutputPort>* outputs) const {}
};

// What the resolver hands a kind's finish(): the plug-in being resolved, its model and where to report.
class ResolveContext {
 public:
  ResolveContext(const RobotModel& model, const PluginSpec& spec, const SensorSpec* sensor, PluginConfig* config,
                 std::vector<Diagnostic>* diagnostics);
  const RobotModel& model() const { return model_; }
  const PluginSpec& spec() const { return spec_; }
  const SensorSpec* sensor() const { return sensor_; }
  PluginConfig& config() { return *config_; }
  // A plug-in key's element path ("gazebo/plugin[NAME]/KEY" or "sensor[S]/plugin[NAME]/KEY").
  std::string where(const std::string& key) const;
  // Load errors at a plug-in key, or at a sensor key ("sensor[S]/KEY").
  [[noreturn]] void fail(const std::string& key, const std::string& reason) const;
  [[noreturn]] void fail_sensor(const std::string& key, const std::string& reason) const;
  // The plug-in does not load and the model loads without it, as where upstream's Load logs a ROS_FATAL and
  // returns: a warning "plugin-not-loaded" at the key (a plug-in the node attaches alone: a LoadError).
  [[noreturn]] void drop(const std::string& key, const std::string& reason) const;
  void warn(Severity severity, const std::string& code, const std::string& key, const std::string& message);
  void set(const std::string& key, const std::string& value);  // replaces a resolved value

 private:
  const RobotModel& model_;
  const PluginSpec& spec_;
  const SensorSpec* sensor_;
  PluginConfig* config_;
  std::vector<Diagnostic>* diagnostics_;
};

// A rate key [Hz] below 0: gazebo_ros's and hector's plug-ins then take a period of 0 and update every step, so
// car warns and does the same (a refusal would be stricter than Gazebo).
void warn_negative_rate(ResolveContext& ctx, const std::string& key);

// xyzOffset and rpyOffset (p3d, the two IMUs): each three numbers, else a load error naming the key.
void check_offsets(ResolveContext& ctx);
// rpyOffset "r p y" [rad] as a rotation, ignition's Quaterniond(Vector3d): roll about x, then pitch about y, then
// yaw about z. For a configuration check_offsets passed.
Eigen::Matrix3d rpy_offset(const PluginConfig& c);

// A plug-in kind, registered once in src/plugins/registry.cpp.
struct PluginKind {
  std::string name;                         // registry name, e.g. "diff_drive"
  std::vector<std::string> filenames;       // Gazebo plug-in file names it serves
  // How its files read <robotNamespace>, as their upstream Load does (docs/COMPAT-plugins.md "Namespaces"), and
  // the files of the kind that read it otherwise.
  NamespaceRule namespace_rule = NamespaceRule::AsWritten;
  std::map<std::string, NamespaceRule> file_namespace_rules;
  bool model_level = true;                  // may stand in a robot-level <gazebo><plugin>
  std::vector<std::string> sensor_types;    // <sensor type>s it may sit in; empty: not a sensor plug-in
  // the files of the kind that each take only some of those (the laser's and velodyne's CPU and GPU files)
  std::map<std::string, std::vector<std::string>> file_sensor_types;
  std::vector<ParamDef> sensor_schema;      // keys of its <sensor> (flattened paths, update_rate included)
  std::vector<ParamDef> schema;             // keys of its <plugin>
  std::map<std::string, std::string> ignored;  // keys upstream accepts and ignores -> a note ("" = silent)
  bool any_keys = false;                    // reads keys of its own: none is unknown (a plug-in from a library)
  bool lazy = false;                        // a measurement: computed only while someone listens
  std::string output_group;                 // key of its outputs in Python's take_sensor_outputs(), e.g. "scans"
  // Checks resolved values against the model and fills derived defaults (ctx.fail for errors).
  std::function<void(ResolveContext&)> finish;
  // Its input ports for a resolved configuration on a robot, topics resolved (none: no inputs).
  std::function<std::vector<InputPort>(const PluginConfig& config, const std::string& robot)> inputs;
  // Its output ports for a resolved configuration on a robot in a world (env: its gravity when the instance is
  // made), topics, frames and covariances resolved (none: its outputs have a ROS adapter instead).
  std::function<std::vector<OutputPort>(const PluginConfig& config, const std::string& robot, const Environment& env)>
      outputs;
  // Its services for a resolved configuration on a robot, names resolved (none: no services).
  std::function<std::vector<ServicePort>(const PluginConfig& config, const std::string& robot)> services;
  // An instance for a resolved configuration. seed: the world's noise seed.
  std::function<std::unique_ptr<Plugin>(const PluginConfig& config, const std::string& robot, uint64_t seed)> make;
};

// A kind's `inputs` for one port of `type` on the topic its schema key `topic_key` names, under the plug-in's
// namespace (plugin_robot_namespace); the port has no topic while the key is empty.
std::function<std::vector<InputPort>(const PluginConfig&, const std::string&)> topic_input(
    const std::string& port, InputType type, const std::string& topic_key, uint32_t queue, uint32_t axes = kAllAxes);

// An output port of joint states on <the plug-in's namespace>/joint_states.
OutputPort joint_states_port(const PluginConfig& c, const std::string& robot, uint32_t queue);

// ---- sensors: laser, range, imu, gps, magnetic, wrench, contacts, pose ----
// A sensor's output port: `type` on the topic its schema key `topic_key` names under the plug-in's namespace, the
// header frame `frame` with its leading '/'s dropped (FrameRule::NoPrefix; a kind may set another), the
// publisher's queue as upstream.
OutputPort sensor_port(const PluginConfig& c, const std::string& robot, const std::string& name, SampleType type,
                       const std::string& topic_key, const std::string& frame, uint32_t queue);

// Every registered kind, in registration order.
const std::vector<const PluginKind*>& plugin_kinds();
const PluginKind* find_plugin_kind(const std::string& name);
const PluginKind* plugin_kind_for_file(const std::string& filename);

// The generator of one measuring plug-in: the same seed and names give the same noise, whatever else runs.
std::mt19937_64 plugin_rng(uint64_t seed, const std::string& robot, const std::string& name);

}  // namespace car_sim
