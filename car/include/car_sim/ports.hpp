// Typed ports: what a plug-in kind declares it takes and gives, as small closed sets of sample types that mirror the
// ROS message families: inputs (Twist, Wrench, JointTrajectory, a pose target, ...), which World::command checks
// once, and outputs (the table Sample: one alternative per family, one converter each in a skin). Each port carries
// its topic, namespace and frames, resolved once in the core from the kind's schema. No ROS headers.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include "car_sim/state.hpp"

namespace car_sim {

// ---- input samples ----------------------------------------------------------------------------------------

// A body twist command: linear [m/s] and angular [rad/s], in the robot's base frame.
struct Twist {
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();
};

struct TrajectoryPoint {
  std::vector<double> positions;  // [rad] or [m], one per joint name
  double time_from_start = 0.0;   // [s]; upstream uses it as the wait after this point
  // [rad/s] or [m/s], [rad/s^2] or [m/s^2]: empty when not given (gazebo_ros_joint_pose_trajectory ignores them)
  std::vector<double> velocities, accelerations;
};

struct JointTrajectory {
  std::vector<std::string> joint_names;
  std::vector<TrajectoryPoint> points;
  double start = 0.0;    // [s] sim time of the first point (earlier: now)
  std::string frame_id;  // the header's frame ("" = none), as written
};

// A pose target, world frame.
struct PoseCommand {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  bool found = true;  // false: the pose could not be had this step (a TF lookup failed); `pose` means nothing
};

// A bare event (std_msgs/Empty): e.g. render one camera frame.
struct Trigger {};

// One number (std_msgs/Float64): a joint controller's command [rad], [rad/s] or [N m].
struct Float64 {
  double data = 0.0;
};

// Numbers (std_msgs/Float64MultiArray's data): a joint group controller's commands, one per joint.
struct Float64Array {
  std::vector<double> data;
};

// A trajectory goal of an action (control_msgs/FollowJointTrajectory), or the cancel of one. The skin numbers its
// goals; the goal's end comes back as a GoalResult sample with that id.
struct TrajectoryGoal {
  uint64_t id = 0;
  bool cancel = false;                    // cancel goal `id` (the other fields are unused)
  JointTrajectory trajectory;
  // tolerances by joint name [rad] or [m]: 0 unchecked, < 0 none
  std::map<std::string, double> path_position, goal_position;
  std::optional<double> goal_time_tolerance;  // [s]; none: the controller's own
};

// One value for an input port; its alternative must match the port's type (the same order as InputType).
using Command =
    std::variant<Twist, Wrench, JointTrajectory, PoseCommand, Trigger, Float64, Float64Array, TrajectoryGoal>;

enum class InputType { Twist, Wrench, JointTrajectory, Pose, Trigger, Float64, Float64Array, TrajectoryGoal };

// The components of a Twist a port reads; the others are dropped before the value is checked.
enum TwistAxes : uint32_t {
  kLinearX = 1u << 0, kLinearY = 1u << 1, kLinearZ = 1u << 2,
  kAngularX = 1u << 3, kAngularY = 1u << 4, kAngularZ = 1u << 5,
  kAllAxes = 63u,
};

// An input of one plug-in instance, resolved.
struct InputPort {
  std::string name;           // the kind's name for it, e.g. "cmd_vel"
  InputType type = InputType::Twist;
  std::string topic;          // absolute ("/ns/cmd_vel"); "" = not a topic (a Pose read from TF, a missing topic)
  std::string frame;          // Pose from TF: the target's frame, read relative to parent_frame
  std::string parent_frame;
  uint32_t queue = 1;         // the subscriber's queue length, as upstream
  uint32_t axes = kAllAxes;   // Twist: the components the kind reads
};

// What became of one command.
struct CommandResult {
  bool accepted = true;  // it passed the world's checks and went to the plug-in
  std::string reason;    // rejected or refused: why ("a non-finite value (linear.x nan, angular.z 0)")
  // The plug-in refused it: a TrajectoryGoal is rejected with `code` (control_msgs/FollowJointTrajectoryResult's
  // error codes) and `reason`.
  bool refused = false;
  int code = 0;
  // Accepted or not, what the skin should log, as upstream logs it (a point skipped, an unknown joint).
  struct Note {
    bool error = false;  // an error (else a warning)
    std::string text;
  };
  std::vector<Note> notes;
};

// ---- output samples -----------------------------------------------------------------------------------------
// What output ports carry, one type per message family (the table Sample, below). A kind's output struct derives
// from the samples it holds, so the fields keep their names for the kind's own code, tests and Python fields.
// Frames and covariances are the port's.

// A pose with a twist: a frame in its parent frame, and the velocity of its origin.
struct OdometrySample {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();   // [m/s]
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();  // [rad/s]
  // The pose's orientation as the kind computes it, when it has its own (ros_controllers' quaternion from the
  // yaw: w = cos(yaw/2), z = sin(yaw/2)); none: taken from `pose`.
  std::optional<Eigen::Quaterniond> orientation;
};

// A robot's joint states, as views of the vectors of the output that holds them.
struct JointStatesSample {
  const std::vector<JointState>* joints = nullptr;
  const std::vector<double>* efforts = nullptr;  // [N m] or [N], one per joint (a port with_effort); null: none
};
// The child links' frames relative to their parents from the same joint states (TF only).
struct JointTransformsSample : JointStatesSample {};

// ---- cameras -----------------------------------------------------------------------------------------------

// One camera frame, as views of the arrays of the output that holds it (a value in Sample): the bridge keeps
// that output alive until the frame's messages are serialised, straight from these arrays. A part the plug-in left
// out (Plugin::set_parts) is null.
struct ImageSample {
  int width = 0, height = 0;           // [px]
  double f = 0, cx = 0, cy = 0;        // [px] focal length, principal point
  std::string encoding;                // "rgb8", "bgr8", "mono8", "rgb16", "mono16"
  uint32_t step = 0;                   // [bytes] per image row
  const uint8_t* image = nullptr;      // step x height bytes, top row first; 16-bit channels little-endian
  size_t image_bytes = 0;
  const float* depth = nullptr;        // [m] width x height, along the optical axis; NaN where there is none
  const float* points = nullptr;       // x y z per pixel [m], optical frame (z forward, x right, y down)
  const uint8_t* point_rgb = nullptr;  // r g b per pixel
};

// A depth [m] as a 16UC1 depth image carries it (openni_kinect's `dest_uint16 = depth * 1000.0`): the float
// depth times 1000.0 in double, truncated to whole millimetres; 0 where there is no depth (NaN). Beyond 65.535 m
// (past every cutoff; undefined upstream) it is 65535. Inline: the bridge calls it per pixel.
inline uint16_t depth_mm(float d) {
  if (!std::isfinite(d) || d <= 0.0f) return 0;
  const double mm = static_cast<double>(d) * 1000.0;
  return mm >= 65535.0 ? 65535 : static_cast<uint16_t>(mm);
}
// Whether a pixel of the organized cloud has a point (x y z [m]; z is its depth, NaN where there is none).
inline bool has_point(const float* xyz) { return std::isfinite(xyz[2]); }

// The same frame, read by the ports of the other camera families (an output lists its ImageSample once).
struct CameraInfoSample : ImageSample {};  // sensor_msgs/CameraInfo: reads no array
struct DepthImageSample : ImageSample {};  // the depth image: reads `depth`
struct DepthCloudSample : ImageSample {};  // the organized cloud: reads `points` and `point_rgb`

// ---- sensors: laser, range, imu, gps, magnetic, wrench, contacts, pose ----

// A planar scan, sensor frame.
struct LaserScanSample {
  float angle_min = 0, angle_max = 0, angle_increment = 0;  // [rad]
  float range_min = 0, range_max = 0;                       // [m]
  std::vector<float> ranges;       // [m]; +inf: no hit within range_max
  std::vector<float> intensities;  // laser_retro of the hit surface
};

// Points with one channel of intensities, sensor frame.
struct PointCloudSample {
  std::vector<float> points;       // x y z per point [m]
  std::vector<float> intensities;  // one per point
};

// A multi-beam lidar's points with intensity and ring (beam index), sensor frame.
struct LidarCloudSample {
  std::vector<float> points;       // x y z per point [m]
  std::vector<float> intensities;  // one per point
  std::vector<uint16_t> rings;     // one per point, 0 = the lowest beam
};

// One range reading (sensor_msgs/Range's fields).
struct RangeSample {
  int radiation = 0;                   // 0 ULTRASOUND, 1 INFRARED
  float field_of_view = 0;             // [rad]
  float min_range = 0, max_range = 0;  // [m]
  float range = 0;                     // [m]
};

// An inertial measurement, sensor frame.
struct ImuSample {
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // sensor frame in the world
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();       // [rad/s]
  Eigen::Vector3d linear_acceleration = Eigen::Vector3d::Zero();    // [m/s^2]
};

// A satellite fix.
struct NavSatFixSample {
  double latitude = 0, longitude = 0, altitude = 0;             // [deg], [deg], [m]
  int status = 0, service = 0;                                  // sensor_msgs/NavSatStatus
  Eigen::Vector3d position_variance = Eigen::Vector3d::Zero();  // [m^2] diagonal, DIAGONAL_KNOWN
};

// A vector, e.g. a velocity [m/s] (hector_gps) or a magnetic field (hector_magnetic), in the port's frame.
struct Vector3Sample {
  Eigen::Vector3d vector = Eigen::Vector3d::Zero();
};
// The same vector as sensor_msgs/MagneticField (hector_magnetic's useMagneticFieldMsgs).
struct MagneticFieldSample : Vector3Sample {};

// A force [N] and torque [N m] (f3d: world frame; ft_sensor: the joint's child link).
struct WrenchSample {
  Wrench wrench;
};

// One pair of bodies in contact: gazebo_msgs/ContactState's fields.
struct ContactPair {
  std::string collision1, collision2;   // "model::link::collision" (this sensor's), "model::link" (the other)
  std::vector<Wrench> wrenches;         // [N], world frame: force on collision1 at each point (torque 0)
  Wrench total;                         // sum of wrenches
  std::vector<Eigen::Vector3d> positions;  // [m], world frame
  std::vector<Eigen::Vector3d> normals;    // unit, world frame, from collision2 into collision1
  std::vector<double> depths;              // [m]
};
// What a bumper touched during the last step: gazebo_msgs/ContactsState's states.
struct ContactsSample {
  std::vector<ContactPair> states;
};

// A frame in its parent frame (TF only).
struct TransformSample {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
};

// ---- ros_control's controllers ----

// control_msgs/JointControllerState of the PID joint controllers.
struct ControllerStateSample {
  double set_point = 0, process_value = 0, process_value_dot = 0, error = 0, time_step = 0, command = 0;
  double p = 0, i = 0, d = 0, i_clamp = 0;  // the PID's gains and its integral clamp
  bool antiwindup = false;
};

// joint_trajectory_controller's state: desired and actual per joint (the error is desired - actual).
struct TrajectoryStateSample {
  std::vector<std::string> joints;
  std::vector<double> desired_position, desired_velocity, actual_position, actual_velocity;
};

// How a TrajectoryGoal ended.
struct GoalResultSample {
  enum class Status { Succeeded, Canceled, Aborted };
  uint64_t goal = 0;  // the TrajectoryGoal's id
  Status status = Status::Succeeded;
  int error_code = 0;  // control_msgs/FollowJointTrajectoryResult's
  std::string error_string;
};

// ---- the table of sample types --------------------------------------------------------------------------------

// Every sample type of output ports, one per message family: the closed set, and the one table a new family joins
// (docs/ARCHITECTURE.md "A new message family"). A sample the output holds (its struct derives from it) is handed
// over as a pointer, so scans, clouds and contacts are never copied; one made when asked (a view of a camera
// frame's arrays, ros_controllers' odometry) as a value. A ROS skin has one converter per alternative.
using Sample = std::variant<std::monostate,                 // none: the output has no sample for that port
                            OdometrySample,                 // nav_msgs/Odometry, and its transform (OutputPort::tf)
                            JointStatesSample,              // sensor_msgs/JointState
                            JointTransformsSample,          // TF: each driven joint's child link in its parent
                            ImageSample,                    // sensor_msgs/Image: the frame's colour image
                            CameraInfoSample,               // sensor_msgs/CameraInfo
                            DepthImageSample,               // sensor_msgs/Image: 32FC1 [m] or 16UC1 [mm]
                            DepthCloudSample,               // sensor_msgs/PointCloud2, organized
                            const LaserScanSample*,         // sensor_msgs/LaserScan
                            const PointCloudSample*,        // sensor_msgs/PointCloud, one channel (block_laser)
                            const LidarCloudSample*,        // sensor_msgs/PointCloud2: x y z intensity ring
                            const RangeSample*,             // sensor_msgs/Range
                            ImuSample,                      // sensor_msgs/Imu
                            const NavSatFixSample*,         // sensor_msgs/NavSatFix
                            Vector3Sample,                  // geometry_msgs/Vector3Stamped
                            MagneticFieldSample,            // sensor_msgs/MagneticField
                            const WrenchSample*,            // geometry_msgs/WrenchStamped
                            const ContactsSample*,          // gazebo_msgs/ContactsState
                            TransformSample,                // TF only: frame -> child_frame
                            const ControllerStateSample*,   // control_msgs/JointControllerState
                            const TrajectoryStateSample*,   // control_msgs/JointTrajectoryControllerState
                            const GoalResultSample*>;       // a TrajectoryGoal's end: to the action server

// A port's sample type: the index of its alternative in Sample (sample_type<LaserScanSample>()).
struct SampleType {
  size_t index = 0;
  bool operator==(SampleType o) const { return index == o.index; }
  bool operator!=(SampleType o) const { return index != o.index; }
};

namespace detail {
template <class T, class V>
struct IndexIn;
// The index of T among the alternatives, or their count when T is none of them.
template <class T, class... As>
struct IndexIn<T, std::variant<As...>> {
  static constexpr size_t find() {
    constexpr bool same[] = {std::is_same_v<T, As>...};
    for (size_t i = 0; i < sizeof...(As); ++i)
      if (same[i]) return i;
    return sizeof...(As);
  }
  static constexpr size_t value = find();
};
constexpr size_t kSampleTypes = std::variant_size_v<Sample>;
template <class S>
constexpr bool kByPointer = IndexIn<const S*, Sample>::value < kSampleTypes;
}  // namespace detail

// The sample type S, held by value or by pointer.
template <class S>
constexpr SampleType sample_type() {
  constexpr size_t i = detail::kByPointer<S> ? detail::IndexIn<const S*, Sample>::value
                                             : detail::IndexIn<S, Sample>::value;
  static_assert(i < detail::kSampleTypes && i > 0, "not a sample type of car_sim::Sample");
  return {i};
}

// What a reader gets of a sample type S (Output::sample_of): the pointer where Sample holds S by pointer, else an
// optional copy of the value; both empty when the output has none.
template <class S>
using SampleHandle = std::conditional_t<detail::kByPointer<S>, const S*, std::optional<S>>;

// The samples one output hands over (Output::samples), and which of them each port reads.
class SampleList {
 public:
  // A sample for every port of its type and of the types whose sample derives from it with nothing of its own (a
  // camera frame's ImageSample serves its CameraInfo, DepthImage and DepthCloud ports too); or, with `port`, for the
  // port of that name only (hector_imu's "bias"). frame: the output's frame it belongs to (a multicamera's side).
  void add(Sample sample, std::string_view port = {}, size_t frame = 0) {
    entries_.push_back({std::move(sample), port, frame});
  }
  // The sample a port of type `type`, named `port`, reading frame `frame`, takes: the one added for that port, else
  // the first added for every port (made into `type` where it serves it); std::monostate when there is none.
  Sample find(SampleType type, std::string_view port, size_t frame) const;
  size_t size() const { return entries_.size(); }
  void clear() { entries_.clear(); }

 private:
  struct Entry {
    Sample sample;
    std::string_view port;  // "" = every port
    size_t frame = 0;
  };
  std::vector<Entry> entries_;
};

// ---- output ports -----------------------------------------------------------------------------------------

// What an Image, CameraInfo, DepthImage or DepthCloud port needs besides its topic and frame, resolved from the
// kind's schema (gazebo_ros_camera_utils' keys).
struct ImagePortSettings {
  size_t frame = 0;                     // which frame of the output (a multicamera's side)
  // CameraInfo: plumb_bob D (k1 k2 t1 t2 k3), P[3] = -f * baseline [m], one message per `period` [s] (0: with
  // every frame)
  std::array<double, 5> distortion{};
  double baseline = 0.0;
  double period = 0.0;
  // CameraInfo: camera_utils' <Cx>, <Cy>, <focalLength> [px]; a non-zero value replaces the sample's computed
  // one in K and P (the images are rendered from horizontal_fov whatever they say)
  double cx = 0.0, cy = 0.0, focal_length = 0.0;
  bool millimetres = false;             // DepthImage: 16UC1 [mm] (0 where there is no depth), else 32FC1 [m]
};

// Whether a sample's transform also goes out on TF, before or after its message (as each upstream file orders it).
enum class TfOrder { None, Before, After };

// How a skin writes a port's frames: gazebo_plugins' tf_prefix rules, each file's own (docs/COMPAT-spawn.md rule
// 4). car's ROS node applies them in one place (src/ros/frames.cpp).
enum class FrameRule {
  // both frames tf::resolve(tf_prefix, name), tf_prefix searched upwards from the port's namespace
  // (tf::getPrefixParam): the drives' GazeboRos::resolveTF, the laser, camera_utils
  PrefixSearched,
  // header.frame_id only tf::resolve(tf_prefix, frame), tf_prefix read in the namespace itself
  // (getParam("tf_prefix")): p3d, f3d, ft_sensor, range, bumper, block_laser; the child frame as written
  PrefixHere,
  // no tf_prefix: the frame loses its leading '/'s, the child frame as written (the IMUs, hector's sensors,
  // velodyne, hand_of_god)
  NoPrefix,
  // both frames exactly as written (ros_controllers)
  AsWritten,
};

// An output of one plug-in instance, resolved.
struct OutputPort {
  std::string name;            // the kind's name for it, e.g. "odom"
  SampleType type = sample_type<OdometrySample>();
  std::string topic;           // absolute; "" = no message (an Odometry port may still send its TF)
  uint32_t queue = 1;          // the publisher's queue length, as upstream
  std::string ns;              // the plug-in's namespace: where a ROS skin looks tf_prefix up (gazebo_ros resolveTF)
  std::string frame;           // header.frame_id as written (a ROS skin prefixes it with tf_prefix)
  std::string child_frame;     // child_frame_id as written
  FrameRule frame_rule = FrameRule::PrefixSearched;  // how a skin writes frame and child_frame
  bool with_effort = false;        // JointStates: each joint's effort too (joint_state_controller)
  TfOrder tf = TfOrder::None;  // Odometry: also the transform frame -> child_frame
  bool planar_position = false;  // Odometry: the message's position.z stays 0, the TF keeps it (skid steer, planar
                                 // move: upstream's publishOdometry fills x and y only)
  std::array<double, 6> pose_covariance{};   // the diagonal (x, y, z, roll, pitch, yaw)
  std::array<double, 6> twist_covariance{};
  // Lazy parts (Plugin::set_parts): the parts of the output this port's messages need while it has subscribers;
  // idle_parts: what a port that needs no part of its own (camera_info) asks to be made while no subscribed port
  // takes one. No port with either: every part.
  uint32_t parts = 0;
  uint32_t idle_parts = 0;
  ImagePortSettings image;     // the camera sample types
  // ---- sensors: laser, range, imu, gps, magnetic, wrench, contacts, pose ----
  // Imu: the diagonals of the three covariances (x, y, z; orientation as roll, pitch, yaw)
  std::array<double, 3> orientation_covariance{};
  std::array<double, 3> angular_velocity_covariance{};
  std::array<double, 3> linear_acceleration_covariance{};
  // At most one message per period [s] of sim time by PeriodGate's rule (gazebo_ros_range's updateRate, the camera's
  // images: throttle_images); 0 = every sample.
  double min_period = 0.0;
};

// Gazebo's common::Time(double) in whole nanoseconds: floor for the seconds, the rest rounded to the nanosecond.
// Beyond +-4.6e9 s (a period of a rate such as 1e-300 Hz, which never elapses) it saturates at +-4.6e18 ns, where
// common::Time's int32 seconds would overflow; NaN gives the upper bound.
inline int64_t common_time_ns(double seconds) {
  constexpr int64_t kMaxNs = 4600000000000000000;
  if (!(seconds < 4.6e9)) return kMaxNs;
  if (!(seconds > -4.6e9)) return -kMaxNs;
  const double whole = std::floor(seconds);
  return static_cast<int64_t>(whole) * 1000000000 + std::llround((seconds - whole) * 1e9);
}
// [ns] The sim time of a tick at step dt [s], as Gazebo's sim time adds common::Time(dt) per step.
inline int64_t tick_time_ns(uint64_t tick, double dt) { return static_cast<int64_t>(tick) * common_time_ns(dt); }
// common::Time::Double() of a time in nanoseconds: sec + nsec * 1e-9, in that order. A negative time too: Time's
// Correct() gives sec and nsec one sign, as the division here (towards zero) does.
inline double common_time_double(int64_t ns) {
  return static_cast<double>(ns / 1000000000) + static_cast<double>(ns % 1000000000) * 1e-9;
}

// The rule of gazebo_ros's throttled publishers (gazebo_ros_range's updateRate, camera_utils' camera_info period;
// docs/COMPAT-sensors.md "Throttled publishers"): a message at sim time t goes out when t - last >= period, `last`
// starting at 0, so the first one waits a whole period after time 0. Time going back (a reset) restarts the count
// from t. Whole nanoseconds, as Gazebo's common::Time.
class PeriodGate {
 public:
  PeriodGate() = default;
  // period [s]; <= 0: every message. Rounded to the nanosecond as common::Time(double): floor, then round.
  explicit PeriodGate(double period) : period_ns_(period > 0 ? common_time_ns(period) : 0) {}
  // Whether a message at sim time t [ns] goes out; if so it becomes the last.
  bool due(int64_t t_ns) {
    if (t_ns < last_ns_) last_ns_ = t_ns;
    if (t_ns - last_ns_ < period_ns_) return false;
    last_ns_ = t_ns;
    return true;
  }
  int64_t period_ns() const { return period_ns_; }

 private:
  int64_t period_ns_ = 0;  // [ns]
  int64_t last_ns_ = 0;    // [ns] sim time of the last message that went out
};


// ---- calls: a plug-in's services (controller_manager's) ----

// The call families: controller_manager_msgs' services, and SetParameters, which is no service: the skin makes it
// once, when it sets up the instance's ports, with the parameters it finds under the port's `ns` (none: no call),
// as a Gazebo plug-in reads the parameter server in its Load (gazebo_ros_control's pid_gains).
enum class CallType {
  LoadController, UnloadController, SwitchController, ListControllers, ListControllerTypes,
  ReloadControllerLibraries, SetParameters,
};

// A service of one plug-in instance, resolved.
struct ServicePort {
  std::string name;  // the kind's name for it, e.g. "load_controller"
  CallType type = CallType::LoadController;
  std::string topic;  // absolute service name ("" for SetParameters)
  // LoadController: where the skin reads a controller's parameters (<ns>/<controller name>); SetParameters: the
  // parameters it reads (absolute)
  std::string ns;
};

// A controller's configuration: key path ("pid/p", "joints") -> its values (one for a scalar, several for a list),
// as the parameter server holds them under <ns>/<controller name>/.
using CallParams = std::map<std::string, std::vector<std::string>>;

// One call's arguments: the fields its family uses.
struct CallRequest {
  std::string name;                          // Load-, UnloadController: the controller
  CallParams params;                         // LoadController: its parameters; SetParameters: those under ns
  std::vector<std::string> start, stop;      // SwitchController
  int strictness = 0;                        // SwitchController: 1 BEST_EFFORT, 2 STRICT
  bool force_kill = false;                   // ReloadControllerLibraries
};

struct ControllerStatus {
  std::string name, type, state;  // state: "running" or "stopped"
  std::vector<std::pair<std::string, std::vector<std::string>>> claimed;  // (hardware interface, joints)
};

// What a call did: ok, the lines for the skin's log, and the answers of the List calls.
struct CallResponse {
  bool ok = true;
  std::vector<std::string> errors, warnings, infos;  // for the log, as controller_manager logs them
  std::vector<ControllerStatus> controllers;                  // ListControllers
  std::vector<std::pair<std::string, std::string>> types;     // ListControllerTypes: (type, base class)
  bool ports_changed = false;  // the instance's ports changed (a controller came or went): the skin reads them again
};

// A frame name as tf2 wants it: leading '/'s dropped.
std::string strip_frame(const std::string& frame);

// A topic of a plug-in: an absolute name stays, another goes under the namespace ("" = global).
std::string resolve_topic(const std::string& ns, const std::string& topic);

// What a command's messages are called in the skins' log lines ("cmd_vel", "wrench", ...).
const char* command_noun(InputType type);

}  // namespace car_sim
