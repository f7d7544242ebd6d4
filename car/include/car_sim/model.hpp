// The robot model of the car_sim core: what a URDF (with its <gazebo> extensions) says, fixed after loading.
// No ROS headers. Units are SI throughout: metres, kilograms, seconds, radians.
#pragma once

#include <Eigen/Geometry>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "car_sim/diagnostics.hpp"

namespace car_sim {

// An ordered list of (key, text) pairs, as written in the XML. Nested elements are flattened with '/',
// e.g. "ray/scan/horizontal/samples" -> "360".
using ParamList = std::vector<std::pair<std::string, std::string>>;

// Looks a key up in a ParamList; the last occurrence wins, as with repeated XML elements.
const std::string* find_param(const ParamList& params, const std::string& key);

enum class ShapeType { Box, Cylinder, Sphere, Mesh, Plane };
const char* to_string(ShapeType t);

// The triangles of a mesh file, in the file's frame and units (a shape's mesh_scale applies on top).
struct TriMesh {
  std::vector<Eigen::Vector3f> vertices;   // [m]
  std::vector<uint32_t> indices;           // three per triangle
  std::optional<Eigen::Vector4d> colour;   // the file's first material's diffuse colour, when it has one
};

// A geometric primitive placed in its link frame.
struct Shape {
  ShapeType type = ShapeType::Box;
  Eigen::Vector3d size = Eigen::Vector3d::Zero();      // [m] box edge lengths
  double radius = 0.0;                                 // [m] cylinder, sphere
  double length = 0.0;                                 // [m] cylinder, along its local z
  std::string mesh_uri;                                // mesh file name or package:// URI, as written
  Eigen::Vector3d mesh_scale = Eigen::Vector3d::Ones();
  std::string mesh_path;                               // the file mesh_uri resolved to ("" until loaded)
  std::shared_ptr<const TriMesh> mesh;                 // its triangles (null until loaded)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();   // plane normal, shape frame
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  // shape frame in the link frame
  // The link this shape was written on when fixed-joint lumping moved it into its parent ("" = its own link);
  // that link's <gazebo reference> surface settings apply to it (RobotModel::surface).
  std::string lumped_from;
};

// A URDF material: name and colour. has_rgba is false when none was given or urdfdom rejected it.
struct Material {
  std::string name;
  bool has_rgba = false;
  Eigen::Vector4d rgba = Eigen::Vector4d(0.5, 0.5, 0.5, 1.0);
  std::string texture;
};

struct Visual {
  std::string name;
  Shape shape;
  Material material;
};

// Mass properties: inertia about the centre of mass, expressed in the inertial frame.
struct Inertial {
  double mass = 0.0;                                          // [kg]
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();   // inertial frame in the link frame
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();          // [kg m^2], inertial frame
};

// Gazebo surface and rendering settings of one link (<gazebo reference="LINK">).
// Unset values keep Gazebo's defaults: mu1 = mu2 = 1, kp/kd from the physics engine.
struct GazeboLinkExt {
  std::optional<double> mu1, mu2;  // [-] friction coefficients
  std::optional<double> kp, kd;    // [N/m], [N s/m] contact stiffness and damping
  std::optional<double> laser_retro;
  std::optional<bool> self_collide;
  std::string material;            // e.g. "Gazebo/Yellow"
  // Surface and link physics (docs/COMPAT-physics.md). Unset values keep Gazebo's defaults.
  std::optional<Eigen::Vector3d> fdir1;  // [-] first friction direction, collision frame
  std::optional<double> min_depth;       // [m] penetration allowed before the contact pushes back
  std::optional<double> max_vel;         // [m/s] largest penetration-correction velocity
  std::optional<int> max_contacts;       // [-] most contact points per pair
  std::optional<bool> gravity;           // <gravity>; false = the link feels no gravity
  std::optional<bool> turn_gravity_off;  // <turnGravityOff>; true = the link feels no gravity
  std::optional<double> damping_factor;  // [-] per-step velocity decay: v <- v (1 - f)
  ParamList other;                 // any other element of the block, kept for listing
};

struct Link {
  std::string name;
  std::optional<Inertial> inertial;
  std::vector<Shape> collisions;
  std::vector<Visual> visuals;
  GazeboLinkExt gazebo;
};

enum class JointType { Fixed, Continuous, Revolute, Prismatic, Floating, Planar };
const char* to_string(JointType t);

struct JointLimits {
  double lower = 0.0, upper = 0.0;  // [rad] or [m]
  double effort = 0.0;              // [N m] or [N]
  double velocity = 0.0;            // [rad/s] or [m/s]
};

struct Joint {
  std::string name;
  JointType type = JointType::Fixed;
  std::string parent, child;
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  // child frame in the parent link frame
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();           // unit vector, joint frame
  Eigen::Vector3d axis_as_written = Eigen::Vector3d::UnitX();
  std::optional<JointLimits> limits;
  double damping = 0.0, friction = 0.0;
  // car's own: a fixed joint from `world` that anchors a static SDF model's link (Gazebo has no such joint; its
  // static links are not simulated), left out of what Gazebo's API and gazebo_ros list
  bool anchor = false;
};

// A <plugin> element: its name, file name and parameters as written.
struct PluginSpec {
  std::string name;
  std::string filename;
  ParamList params;
  int line = 0;  // line of <plugin> in the source document
  std::string xml;  // the <plugin> element as written, for a world's own plug-ins ("" for a model's)
};

// A <sensor> element inside <gazebo reference="LINK">.
struct SensorSpec {
  std::string name;
  std::string type;   // "ray", "gpu_ray", "depth", "camera", "imu", ...
  std::string link;   // the link it is attached to
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // sensor frame in the link frame
  double update_rate = 0.0;   // [Hz]; 0 = every step
  bool always_on = false;
  bool visualize = false;
  ParamList params;           // everything else, flattened, e.g. "camera/image/width"
  std::vector<PluginSpec> plugins;
  int line = 0;               // line of <sensor> in the source document
  std::string lumped_from;    // the link it was written on when lumping moved it to `link` ("" = none)
};

// A link merged into its parent by fixed-joint lumping, as sdformat's URDF reader does (docs/COMPAT-spawn.md).
struct LumpedLink {
  std::string name;
  std::string parent;   // the kept link it now belongs to (after every lumping step)
  std::string joint;    // the fixed joint that joined it to its URDF parent
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // its frame in the parent's frame
  GazeboLinkExt gazebo; // its own <gazebo reference> settings: they apply to the shapes it brought
  int line = 0;         // line of its <link>
};

// A link Gazebo does not model: massless (no <inertial> or mass 0) on a moving joint. Its subtree goes with it.
struct DroppedLink {
  std::string name;
  std::string joint;                // its parent joint
  std::vector<std::string> subtree; // links below it, dropped with it
  int line = 0;
};

// A URDF <transmission> (transmission_interface's format, docs/COMPAT-control.md): the joints it moves and the
// hardware interfaces each offers ("PositionJointInterface", prefix "hardware_interface/" removed).
struct Transmission {
  std::string name;
  std::string type;  // e.g. "transmission_interface/SimpleTransmission"
  struct JointEntry {
    std::string joint;
    std::vector<std::string> interfaces;
  };
  std::vector<JointEntry> joints;
  std::vector<std::string> actuators;
  double reduction = 1.0;  // [-] first actuator's <mechanicalReduction>
  int line = 0;            // line of <transmission>
};

// A robot as the core sees it, with findings made while loading.
struct RobotModel {
  std::string name;
  std::string source;     // file name, or "<string>"
  std::string root_link;
  std::vector<Link> links;
  std::vector<Joint> joints;
  std::vector<PluginSpec> plugins;   // robot-level <gazebo><plugin>
  std::vector<SensorSpec> sensors;   // link-level <gazebo reference><sensor>
  std::vector<Diagnostic> diagnostics;
  // Fixed-joint lumping and world anchoring (filled by the URDF loader).
  std::vector<LumpedLink> lumped;
  std::vector<DroppedLink> dropped;
  std::set<std::string> preserved_fixed_joints;  // <gazebo reference=J><preserveFixedJoint> (or disable...)
  std::vector<std::string> world_joints;         // joints from the link `world`: the model is anchored
  bool is_static = false;                        // an SDF model's <static>true (Gazebo's Model::IsStatic)
  std::vector<Transmission> transmissions;       // URDF <transmission>s, as written (ros_control)
  // The root link's pose in the model frame [m, rad]: identity for URDF and anchored models; an SDF model's root
  // <link><pose>. Gazebo's model pose is the model frame (Model::WorldPose): World::model_state reports root link
  // pose * root_in_model^-1, and set_model_state places the root link at pose * root_in_model.
  Eigen::Isometry3d root_in_model = Eigen::Isometry3d::Identity();

  const Link* find_link(const std::string& name) const;
  const Joint* find_joint(const std::string& name) const;
  // The joint whose child is this link, or nullptr for the root.
  const Joint* parent_joint(const std::string& link) const;
  // Pose of a link's frame in the root link's frame, through the joints at zero position.
  // Lumped links too (through their parent).
  Eigen::Isometry3d link_pose_in_root(const std::string& link) const;
  // A lumped link by its URDF name, or nullptr.
  const LumpedLink* find_lumped(const std::string& name) const;
  // A link or a lumped link: the kept link that carries the frame and the frame's pose in it; false if neither.
  bool resolve_frame(const std::string& name, std::string* link, Eigen::Isometry3d* pose_in_link) const;
  // The <gazebo reference> surface settings that apply to a shape of link l (those of the link it came from).
  const GazeboLinkExt& surface(const Link& l, const Shape& s) const;
  // True when a joint from the link `world` anchors the model (fixed base).
  bool anchored() const { return !world_joints.empty(); }
};

// Why mass properties cannot be loaded ("" when they can): a mass that is not > 0 (Gazebo 11's ODELink::UpdateMass
// throws for it). code names the kind ("mass-nonpositive").
std::string inertial_problem(double mass, const Eigen::Matrix3d& inertia, std::string* code = nullptr);

// What Gazebo 11 loads but no rigid body has ("" when nothing): a tensor that is not positive definite (ODE's
// dBodySetMass cannot invert it and takes an identity inverse), or principal moments that break the triangle
// inequality (simulated as written). The message says what car simulates. code: "inertia-not-positive-definite"
// or "inertia-triangle". docs/COMPAT-validation.md "Inertia".
std::string inertial_warning(const Eigen::Matrix3d& inertia, std::string* code = nullptr);

// The tensor [kg m^2] the physics takes for a link's written one: the same, or the identity (1 kg m^2 about every
// axis) where ODE's Cholesky factorisation fails, as Gazebo 11's dBodySetMass falls back to an identity inverse.
Eigen::Matrix3d simulated_inertia(const Eigen::Matrix3d& inertia);

struct LoadOptions {
  // Throw on the first Error-severity finding (a simulator must); false keeps every finding in
  // RobotModel::diagnostics (the model check wants them all). Unreadable XML always throws.
  bool throw_on_error = true;
  // Fixed-joint lumping as sdformat's URDF reader does it (on in Gazebo; off only for tools that want the
  // links as written).
  bool lump_fixed_joints = true;
};

// The spawn service's namespace rule (gazebo_ros_api_plugin walkChildAddRobotNamespace): with a non-empty
// robot_namespace, every <plugin> (robot-level and in sensors) that has no <robotNamespace> gets one with it;
// an explicit one is kept, an empty one too (each plug-in file reads it by its own rule: plugin_robot_namespace
// in car_sim/plugins.hpp). See docs/COMPAT-spawn.md.
void apply_robot_namespace(RobotModel* model, const std::string& robot_namespace);

// Loads a URDF document. Throws LoadError naming source, line (where known), element and reason.
RobotModel load_urdf_string(const std::string& xml, const std::string& source_name = "<string>",
                            const LoadOptions& options = LoadOptions());
RobotModel load_urdf_file(const std::string& path, const LoadOptions& options = LoadOptions());

}  // namespace car_sim
