// The simulated world: an SDF world description (const), robots spawned into it, and a Bullet dynamics
// world stepped in integer ticks of a fixed step. No ROS headers; nothing here reads a clock or sleeps.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "car_sim/diff_drive.hpp"
#include "car_sim/model.hpp"
#include "car_sim/plugins.hpp"
#include "car_sim/sensors.hpp"

namespace car_sim {

// ---- world description (from SDF) -------------------------------------------------------------------

struct SurfaceFriction {
  double mu = 1.0;   // [-] Gazebo's default when a surface sets nothing
  double mu2 = 1.0;  // [-] kept for listing; Bullet uses one isotropic coefficient (mu)
};

struct WorldCollision {
  std::string name;
  Shape shape;  // shape.origin: collision frame in the link frame
  SurfaceFriction friction;
};

struct WorldVisual {
  std::string name;
  Shape shape;                // shape.origin: visual frame in the link frame
  Material material;          // rgba from <diffuse> (else <ambient>) when given
  std::string script_name;    // e.g. "Gazebo/Bricks", "" when none
  Eigen::Vector4d ambient = Eigen::Vector4d::Zero();
  bool has_ambient = false;
};

struct WorldLink {
  std::string name;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // link frame in the model frame
  std::optional<Inertial> inertial;
  std::vector<WorldCollision> collisions;
  std::vector<WorldVisual> visuals;
};

struct WorldModelDesc {
  std::string name;
  bool is_static = false;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // model frame in the world, after <state>
  std::vector<WorldLink> links;
};

struct WorldDescription {
  std::string name = "default";
  std::string source;                                    // file name or "<string>"
  Eigen::Vector3d gravity = Eigen::Vector3d(0, 0, -9.8);  // [m/s^2], world frame
  double step_size = 0.001;                              // [s] <max_step_size>
  double real_time_factor = 1.0;                         // <real_time_factor>, a pacing hint for the node
  Eigen::Vector3d sun_direction = Eigen::Vector3d(-0.5, 0.1, -0.9).normalized();  // light travels along it
  double ambient = 0.4;                                                          // <scene><ambient> (grey level)
  Eigen::Vector3d background = Eigen::Vector3d(0.7, 0.7, 0.7);                  // <scene><background>
  std::vector<WorldModelDesc> models;
  std::vector<Diagnostic> diagnostics;

  const WorldModelDesc* find_model(const std::string& name) const;
};

// Loads an SDF world (SDF 1.4-1.9 through sdformat). Throws LoadError naming file, element and reason.
WorldDescription load_world_file(const std::string& path);
WorldDescription load_world_string(const std::string& xml, const std::string& source_name = "<string>");
// The include rule (the same as python/car/world_tools.py): model://NAME through GAZEBO_MODEL_PATH, then car's
// models/ folder; package://PKG through ROS_PACKAGE_PATH; file:// and plain paths as they are. "" when not found.
std::vector<std::string> model_path();
std::string resolve_uri(const std::string& uri);
std::string resolve_uri(const std::string& uri, const std::string& base_dir);  // relative paths against base_dir

// Gazebo's empty world: a ground plane (mu 100, mu2 50) and a sun, 1 ms step.
WorldDescription empty_world();

// ---- runtime ------------------------------------------------------------------------------------------

struct WorldOptions {
  int solver_iterations = 10;        // at most this many sequential-impulse iterations per step
  double residual_threshold = 1e-9;  // [(m/s)^2] converged: stop iterating early
  uint64_t seed = 0;                 // sensor noise: each sensor's generator is seeded from (seed, robot/sensor)
};

// Pose and twist of a model's root frame, world frame.
struct ModelState {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();   // [m/s], world frame
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();  // [rad/s], world frame
};

struct JointState {
  std::string name;
  double position = 0.0;  // [rad] or [m]
  double velocity = 0.0;  // [rad/s] or [m/s]
};

// One odometry message of a diff-drive plug-in, produced at its update rate.
struct OdometrySample {
  std::string model;
  size_t drive = 0;         // index into RobotInfo::drives
  uint64_t tick = 0;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // base frame in the odometry frame
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();        // [m/s], base frame
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();       // [rad/s], base frame (z only for encoder)
  JointState left, right;   // the wheel joints at that time
};

// A contact between two bodies during the last step.
struct Contact {
  std::string a, b;          // "model/link" (robots: the body's top link)
  Eigen::Vector3d position;  // [m], world frame, on b
  double normal_force = 0.0; // [N]
};

// A sensor of a spawned robot, for the ROS skin.
struct SensorInfo {
  std::string robot;
  PluginConfig config;   // kind, names, every resolved key
  std::string link;      // the link it is on
  double rate = 0.0;     // [Hz], 0 = every step
};

// What a spawned robot is, for the ROS skin: its model, resolved plug-ins and namespace.
struct RobotInfo {
  std::string name;
  std::string robot_namespace;  // as given at spawn ("" when none)
  RobotModel model;
  ModelConfig config;
  std::vector<DiffDriveConfig> drives;  // resolved namespaces
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

  // Adds a robot. Throws std::invalid_argument when the name exists, LoadError for a bad model.
  // A non-empty robot_namespace overrides every plug-in's <robotNamespace>, as gazebo_ros does.
  void spawn(const RobotModel& model, const std::string& name, const Eigen::Isometry3d& pose,
             const std::string& robot_namespace = "");
  // Removes a robot or world model. Throws std::invalid_argument when there is none of that name.
  void remove(const std::string& name);

  // Advances n fixed steps: plug-ins apply commands, physics, then plug-ins sample outputs.
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

  // Commands the robot's diff drive(s): v [m/s] forward, w [rad/s] about z. Non-finite values throw.
  void set_cmd_vel(const std::string& robot, double v, double w);

  // Sensors: every sensor plug-in of every robot. A sensor computes only while active (someone listens).
  std::vector<SensorInfo> sensors() const;
  void set_sensor_active(const std::string& robot, const std::string& plugin, bool active);
  // Measurements made since the last call.
  SensorOutputs take_sensor_outputs();

  // Contacts of the last step with a positive normal force.
  std::vector<Contact> contacts() const;

  // Odometry produced since the last call.
  std::vector<OdometrySample> take_odometry();

 private:
  void update_sensors();

  struct Impl;
  WorldDescription desc_;
  WorldOptions options_;
  uint64_t tick_ = 0;
  std::unique_ptr<Impl> impl_;
};

}  // namespace car_sim
