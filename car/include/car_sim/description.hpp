// The world description of the car_sim core: an SDF world as read through sdformat (models, links, shapes,
// surfaces, materials, light, gravity, step size), fixed after loading, and the URI rule for includes and meshes.
// No ROS headers.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "car_sim/model.hpp"
#include "car_sim/sdf_model.hpp"

namespace car_sim {

struct SurfaceFriction {
  double mu = 1.0;   // [-] Gazebo's default when a surface sets nothing
  double mu2 = 1.0;  // [-] kept for listing; Bullet uses one isotropic coefficient (mu)
};

struct WorldCollision {
  std::string name;
  Shape shape;  // shape.origin: collision frame in the link frame
  SurfaceFriction friction;
  std::optional<double> laser_retro;  // <laser_retro>: the intensity ray sensors read off it
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
  bool gravity = true;                                     // <gravity>: false = the link feels no gravity
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

// Whether world model `model` is nested (at any depth) in `parent`: hoisted nested models are named
// "parent::child" (docs/COMPAT-sdf.md 16a).
inline bool nested_in(const std::string& model, const std::string& parent) {
  return model.size() > parent.size() + 2 && model.compare(0, parent.size(), parent) == 0 &&
         model.compare(parent.size(), 2, "::") == 0;
}

// A world model with plug-ins, sensors or joints: spawned as a robot when the World starts (docs/COMPAT-sdf.md 16).
struct WorldRobotDesc {
  std::string name;
  SdfRobot robot;
  // where to spawn it: World::spawn_sdf(robot, name, pose) puts the root link at pose * robot.root_pose
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
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
  std::vector<WorldRobotDesc> robots;  // world models simulated as robots (plug-ins, sensors, joints)
  // The world's own <plugin>s (directly in <world>), in document order: Gazebo's world plug-ins (docs/PLUGINS.md)
  std::vector<PluginSpec> plugins;
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

// A world file as one self-contained SDF document (world_tool flatten, docs/TOOLS.md): every <include> replaced
// by what it names, with its <name>, <pose> and <static> (URIs by resolve_uri, relative ones against the including
// file's folder; a model folder by its model.config; mesh URIs made absolute), at most 32 includes deep; nested
// models hoisted to top-level models "parent::child" with composed poses (static when the parent is); the <state>
// block's model poses applied and the block dropped. Throws LoadError naming file, element and reason. With
// warnings, an <include> that names nothing or resolves nowhere is left out with a warning "include-missing", as
// the simulator leaves it out (docs/COMPAT-validation.md); without, it is an error.
std::string flatten_world_file(const std::string& path, std::vector<Diagnostic>* warnings = nullptr);

// world_tool check's reading of a world file, in one call (docs/COMPAT-validation.md "world_tool check"): the file
// flattened as flatten_world_file does (an include that resolves nowhere: the warning "include-missing"; a file it
// cannot flatten: the error "world-unreadable" with its reason), the flattened world held to the check's rules
// (pose-malformed, geometry-empty, geometry-unknown, uri-missing, geometry-unsimulated), then, when none of those is
// an error, the flattened text read by the loader as load_world_string reads it (its refusal: the error "world-load",
// "ELEMENT: REASON"; its warnings appended). Throws nothing for a bad world.
struct WorldCheck {
  std::vector<Diagnostic> findings;              // in the order found
  std::shared_ptr<const WorldDescription> world;  // the loaded world; null when an error came first
};
WorldCheck check_world_file(const std::string& path);

// world_tool map's and plot's reading of a world file, in one call: flattened as flatten_world_file does (warnings as
// there), the text in UTF-8 as check_world_file reads it, then loaded by load_world_string. Throws LoadError (a
// byte that is not text: "not UTF-8 text (byte 0x..; ...)", as check_world_file's finding).
WorldDescription load_flattened_world(const std::string& path, std::vector<Diagnostic>* warnings = nullptr);

// Gazebo's empty world: a ground plane (mu 100, mu2 50) and a sun, 1 ms step.
WorldDescription empty_world();

}  // namespace car_sim
