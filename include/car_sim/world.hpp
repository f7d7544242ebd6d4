// The simulated world: an SDF world description (const), robots spawned into it with their plug-ins, and a
// Bullet dynamics world stepped in integer ticks of a fixed step. No ROS headers; nothing here reads a clock or
// sleeps. A step has phases: every plug-in's pre_physics, one physics step, then every plug-in's track and (when
// its schedule is due) post_physics.
#pragma once

#include <cstdint>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "car_sim/description.hpp"
#include "car_sim/drive.hpp"
#include "car_sim/model.hpp"
#include "car_sim/plugin.hpp"
#include "car_sim/plugins.hpp"
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
};
using SensorInfo = PluginInfo;

// What a spawned robot is, for the skins: its model, resolved plug-ins and namespace.
struct RobotInfo {
  std::string name;
  std::string robot_namespace;  // as given at spawn ("" when none)
  RobotModel model;
  ModelConfig config;
  Eigen::Isometry3d spawn_pose = Eigen::Isometry3d::Identity();
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

  std::vector<std::string> model_names() const;  // world models first, then robots in spawn order
  bool has_model(const std::string& name) const;
  ModelState model_state(const std::string& name) const;
  void set_model_state(const std::string& name, const ModelState& s);
  const RobotInfo& robot(const std::string& name) const;
  std::vector<std::string> robot_names() const;

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
  // A robot's plug-in instance (for a skin to command it, e.g. through TwistDrive); nullptr when none.
  Plugin* plugin(const std::string& robot, const std::string& name);

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

  // Commands every drive plug-in of the robot (TwistDrive): v [m/s] forward, w [rad/s] about z. Non-finite
  // values and unknown robots throw std::invalid_argument; a robot without a drive ignores the command.
  void set_cmd_vel(const std::string& robot, double v, double w);
  void set_cmd_vel(const std::string& robot, const Twist& cmd);
  // Odometry produced since the last call (the drive plug-ins' outputs).
  std::vector<OdometryOut> take_odometry() { return take_outputs<OdometryOut>(); }

  // Contacts of the last step with a positive normal force.
  std::vector<Contact> contacts() const;

 private:
  struct Impl;
  const WorldDescription desc_;
  WorldOptions options_;
  uint64_t tick_ = 0;
  std::set<std::string> removed_;  // world models deleted at run time (a reset does not bring them back)
  std::unique_ptr<Impl> impl_;
};

}  // namespace car_sim
