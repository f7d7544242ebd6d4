// The output half of the ROS bridge: one converter per sample type, beside its to_msg (the camera types:
// outputs_image.cpp), and the table OutputPorts picks them from by a port's type.
#include "outputs.hpp"

#include <control_msgs/JointControllerState.h>
#include <control_msgs/JointTrajectoryControllerState.h>
#include <nav_msgs/Odometry.h>
#include <sensor_msgs/JointState.h>
// ---- sensors: laser, range, imu, gps, magnetic, wrench, contacts, pose ----
#include <gazebo_msgs/ContactsState.h>
#include <geometry_msgs/Vector3Stamped.h>
#include <geometry_msgs/WrenchStamped.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/MagneticField.h>
#include <sensor_msgs/NavSatFix.h>
#include <sensor_msgs/PointCloud.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/Range.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstring>
#include <map>
#include <sstream>
#include <type_traits>
#include <utility>

#include "conversions.hpp"

namespace car_ros {

using car_sim::Sample;

namespace {

// rosDebugLevel (Debug, Info, Warn, Error, Fatal; "na" leaves it) sets this node's logger level, as the gazebo_ros
// plug-ins that have the key do.
void set_debug_level(const car_sim::PluginConfig& c) {
  if (!c.has("rosDebugLevel")) return;
  static const std::map<std::string, ros::console::levels::Level> levels = {
      {"debug", ros::console::levels::Debug}, {"info", ros::console::levels::Info},
      {"warn", ros::console::levels::Warn},   {"error", ros::console::levels::Error},
      {"fatal", ros::console::levels::Fatal}};
  std::string l = c.text("rosDebugLevel");
  for (auto& ch : l) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  const auto it = levels.find(l);
  if (it == levels.end()) return;
  if (ros::console::set_logger_level(ROSCONSOLE_DEFAULT_NAME, it->second)) ros::console::notifyLoggerLevelsChanged();
}

// A port with a publisher of M and nothing else: the log line's words are its topic and frame.
template <class M>
std::string advertise_topic(OutPort& p, const SetupContext& c) {
  p.pub = c.node.advertise<M>(p.port.topic, p.port.queue);
  return p.pub.getTopic() + (p.frames.frame.empty() ? std::string() : " (frame " + p.frames.frame + ")");
}

geometry_msgs::Vector3 to_vector3(const Eigen::Vector3d& v) {
  geometry_msgs::Vector3 m;
  m.x = v.x();
  m.y = v.y();
  m.z = v.z();
  return m;
}

geometry_msgs::Wrench to_wrench(const car_sim::Wrench& w) {
  geometry_msgs::Wrench m;
  m.force = to_vector3(w.force);
  m.torque = to_vector3(w.torque);
  return m;
}

// header and child frame the port's; covariances the port's diagonals; the orientation the kind's own when it has one
nav_msgs::Odometry to_msg(const car_sim::OdometrySample& o, const OutPort& p, const ros::Time& stamp) {
  nav_msgs::Odometry m;
  m.header.stamp = stamp;
  m.header.frame_id = p.frames.frame;
  m.child_frame_id = p.frames.child_frame;
  m.pose.pose = to_pose(o.pose);
  if (p.port.planar_position) m.pose.pose.position.z = 0.0;
  if (o.orientation) {
    m.pose.pose.orientation.x = o.orientation->x();
    m.pose.pose.orientation.y = o.orientation->y();
    m.pose.pose.orientation.z = o.orientation->z();
    m.pose.pose.orientation.w = o.orientation->w();
  }
  m.twist.twist = to_twist(o.linear, o.angular);
  for (int i = 0; i < 6; ++i) {
    m.pose.covariance[i * 7] = p.port.pose_covariance[i];
    m.twist.covariance[i * 7] = p.port.twist_covariance[i];
  }
  return m;
}

sensor_msgs::JointState to_msg(const car_sim::JointStatesSample& s, bool with_effort) {
  sensor_msgs::JointState js;
  const std::vector<car_sim::JointState>& joints = *s.joints;
  js.name.reserve(joints.size());
  js.position.reserve(joints.size());
  js.velocity.reserve(joints.size());
  for (const auto& j : joints) {
    js.name.push_back(j.name);
    js.position.push_back(j.position);
    js.velocity.push_back(j.velocity);
  }
  if (with_effort && s.efforts) js.effort = *s.efforts;
  return js;
}

// ---- sensors: laser, range, imu, gps, magnetic, wrench, contacts, pose ----
sensor_msgs::LaserScan to_msg(const car_sim::LaserScanSample& s) {
  sensor_msgs::LaserScan m;
  m.angle_min = s.angle_min;
  m.angle_max = s.angle_max;
  m.angle_increment = s.angle_increment;
  m.time_increment = 0.f;
  m.scan_time = 0.f;
  m.range_min = s.range_min;
  m.range_max = s.range_max;
  m.ranges = s.ranges;
  m.intensities = s.intensities;
  return m;
}

// one unnamed channel of intensities (upstream never names it)
sensor_msgs::PointCloud to_msg(const car_sim::PointCloudSample& s) {
  sensor_msgs::PointCloud m;
  const size_t n = s.intensities.size();
  m.points.resize(n);
  for (size_t i = 0; i < n; ++i) {
    m.points[i].x = s.points[3 * i];
    m.points[i].y = s.points[3 * i + 1];
    m.points[i].z = s.points[3 * i + 2];
  }
  m.channels.resize(1);
  m.channels[0].values = s.intensities;
  return m;
}

// fields x y z intensity ring, point_step 32
sensor_msgs::PointCloud2 to_msg(const car_sim::LidarCloudSample& s) {
  sensor_msgs::PointCloud2 m;
  const char* names[5] = {"x", "y", "z", "intensity", "ring"};
  const uint32_t offsets[5] = {0, 4, 8, 16, 20};
  for (int k = 0; k < 5; ++k) {
    sensor_msgs::PointField f;
    f.name = names[k];
    f.offset = offsets[k];
    f.datatype = k == 4 ? sensor_msgs::PointField::UINT16 : sensor_msgs::PointField::FLOAT32;
    f.count = 1;
    m.fields.push_back(f);
  }
  const size_t n = s.intensities.size();
  m.point_step = 32;
  m.row_step = static_cast<uint32_t>(32 * n);
  m.height = 1;
  m.width = static_cast<uint32_t>(n);
  m.is_bigendian = false;
  m.is_dense = true;
  m.data.assign(32 * n, 0);
  for (size_t i = 0; i < n; ++i) {
    uint8_t* p = m.data.data() + 32 * i;
    std::memcpy(p, &s.points[3 * i], 12);
    std::memcpy(p + 16, &s.intensities[i], 4);
    std::memcpy(p + 20, &s.rings[i], 2);
  }
  return m;
}

sensor_msgs::Range to_msg(const car_sim::RangeSample& s) {
  sensor_msgs::Range m;
  m.radiation_type = static_cast<uint8_t>(s.radiation);
  m.field_of_view = s.field_of_view;
  m.min_range = s.min_range;
  m.max_range = s.max_range;
  m.range = s.range;
  return m;
}

// covariances: the port's diagonals
sensor_msgs::Imu to_msg(const car_sim::ImuSample& s, const car_sim::OutputPort& port) {
  sensor_msgs::Imu m;
  m.orientation.x = s.orientation.x();
  m.orientation.y = s.orientation.y();
  m.orientation.z = s.orientation.z();
  m.orientation.w = s.orientation.w();
  m.angular_velocity = to_vector3(s.angular_velocity);
  m.linear_acceleration = to_vector3(s.linear_acceleration);
  for (int i = 0; i < 3; ++i) {
    m.orientation_covariance[i * 4] = port.orientation_covariance[i];
    m.angular_velocity_covariance[i * 4] = port.angular_velocity_covariance[i];
    m.linear_acceleration_covariance[i * 4] = port.linear_acceleration_covariance[i];
  }
  return m;
}

sensor_msgs::NavSatFix to_msg(const car_sim::NavSatFixSample& s) {
  sensor_msgs::NavSatFix f;
  f.status.status = static_cast<int8_t>(s.status);
  f.status.service = static_cast<uint16_t>(s.service);
  f.latitude = s.latitude;
  f.longitude = s.longitude;
  f.altitude = s.altitude;
  f.position_covariance_type = sensor_msgs::NavSatFix::COVARIANCE_TYPE_DIAGONAL_KNOWN;
  f.position_covariance[0] = s.position_variance.x();
  f.position_covariance[4] = s.position_variance.y();
  f.position_covariance[8] = s.position_variance.z();
  return f;
}

// gazebo_msgs/ContactsState (car's gazebo_msgs drop-in), with upstream's debug info text per state
gazebo_msgs::ContactsState to_msg(const std::vector<car_sim::ContactPair>& states, const std_msgs::Header& header) {
  gazebo_msgs::ContactsState m;
  m.header = header;
  for (size_t i = 0; i < states.size(); ++i) {
    const car_sim::ContactPair& c = states[i];
    gazebo_msgs::ContactState s;
    s.collision1_name = c.collision1;
    s.collision2_name = c.collision2;
    std::ostringstream info;
    info << "Debug:  i:(" << i << "/" << states.size() << ")     my geom:" << c.collision1
         << "   other geom:" << c.collision2 << "         time:" << header.stamp << "\n";
    s.info = info.str();
    for (size_t k = 0; k < c.positions.size(); ++k) {
      s.wrenches.push_back(to_wrench(c.wrenches[k]));
      s.contact_positions.push_back(to_vector3(c.positions[k]));
      s.contact_normals.push_back(to_vector3(c.normals[k]));
      s.depths.push_back(c.depths[k]);
    }
    s.total_wrench = to_wrench(c.total);
    m.states.push_back(std::move(s));
  }
  return m;
}


// ---- ros_control's controllers ----

control_msgs::JointControllerState to_msg(const car_sim::ControllerStateSample& s) {
  control_msgs::JointControllerState m;
  m.set_point = s.set_point;
  m.process_value = s.process_value;
  m.process_value_dot = s.process_value_dot;
  m.error = s.error;
  m.time_step = s.time_step;
  m.command = s.command;
  m.p = s.p;
  m.i = s.i;
  m.d = s.d;
  m.i_clamp = s.i_clamp;
  m.antiwindup = s.antiwindup;
  return m;
}

// the error is desired - actual, per joint
control_msgs::JointTrajectoryControllerState to_msg(const car_sim::TrajectoryStateSample& s) {
  control_msgs::JointTrajectoryControllerState m;
  m.joint_names = s.joints;
  m.desired.positions = s.desired_position;
  m.desired.velocities = s.desired_velocity;
  m.actual.positions = s.actual_position;
  m.actual.velocities = s.actual_velocity;
  for (size_t k = 0; k < s.joints.size(); ++k) {
    m.error.positions.push_back(s.desired_position[k] - s.actual_position[k]);
    m.error.velocities.push_back(s.desired_velocity[k] - s.actual_velocity[k]);
  }
  return m;
}

}  // namespace

// ---- the converters, one per sample type ----------------------------------------------------------------------

template <>
std::string advertise<car_sim::OdometrySample>(OutPort& p, const SetupContext& c) {
  const car_sim::OutputPort& op = p.port;
  if (!op.topic.empty()) {
    p.pub = c.node.advertise<nav_msgs::Odometry>(op.topic, op.queue);
  } else {
    ROS_WARN("car: %s: %s: no odometry topic at all (like gazebo_ros with publishTf false)", c.plugin.robot.c_str(),
             c.plugin.config.name.c_str());
  }
  return "odometry " + (op.topic.empty() ? std::string("(none)") : op.topic) + " (" + p.frames.frame + " -> " +
         p.frames.child_frame + (op.tf != car_sim::TfOrder::None ? ", TF" : "") + ")";
}
// the message, and its transform on TF before or after it
template <>
void convert<car_sim::OdometrySample>(OutPort& p, const car_sim::OdometrySample& o, PublishContext& c) {
  nav_msgs::Odometry m = to_msg(o, p, c.stamp);
  // the transform is made before the odometry is moved to the publishing thread
  geometry_msgs::TransformStamped t;
  if (p.port.tf != car_sim::TfOrder::None) {
    t.header = m.header;
    t.child_frame_id = m.child_frame_id;
    t.transform = to_transform(o.pose);
    t.transform.rotation = m.pose.pose.orientation;
  }
  if (p.port.tf == car_sim::TfOrder::Before) c.node.send_tf(std::move(t));
  if (p.pub) c.node.publish(p.pub, std::move(m));
  if (p.port.tf == car_sim::TfOrder::After) c.node.send_tf(std::move(t));
}

template <>
std::string advertise<car_sim::JointStatesSample>(OutPort& p, const SetupContext& c) {
  p.pub = c.node.advertise<sensor_msgs::JointState>(p.port.topic, p.port.queue);
  return "joint states " + p.port.topic;
}
// stamped, no frame
template <>
void convert<car_sim::JointStatesSample>(OutPort& p, const car_sim::JointStatesSample& s, PublishContext& c) {
  sensor_msgs::JointState js = to_msg(s, p.port.with_effort);
  js.header.stamp = c.stamp;
  c.node.publish(p.pub, std::move(js));
}

template <>
std::string advertise<car_sim::JointTransformsSample>(OutPort&, const SetupContext&) {
  return "wheel TF";
}
// fix: each child link relative to its parent link (upstream drives publish the wheels relative to the odometry
// frame, or name the child frame after the joint)
template <>
void convert<car_sim::JointTransformsSample>(OutPort& p, const car_sim::JointTransformsSample& s, PublishContext& c) {
  for (const auto& j : *s.joints) {
    const car_sim::Joint* joint = c.model.find_joint(j.name);
    geometry_msgs::TransformStamped w;
    w.header.stamp = c.stamp;
    w.header.frame_id = p.frames.header_frame(joint->parent);
    w.child_frame_id = p.frames.header_frame(joint->child);
    Eigen::Isometry3d T = joint->origin;
    T.rotate(Eigen::AngleAxisd(j.position, joint->axis));
    w.transform = to_transform(T);
    c.node.send_tf(std::move(w));
  }
}

// ---- sensors: laser, range, imu, gps, magnetic, wrench, contacts, pose ----

template <>
std::string advertise<car_sim::LaserScanSample>(OutPort& p, const SetupContext& c) {
  return advertise_topic<sensor_msgs::LaserScan>(p, c);
}
template <>
void convert<car_sim::LaserScanSample>(OutPort& p, const car_sim::LaserScanSample& s, PublishContext& c) {
  send(p, to_msg(s), c);
}

template <>
std::string advertise<car_sim::PointCloudSample>(OutPort& p, const SetupContext& c) {
  return advertise_topic<sensor_msgs::PointCloud>(p, c);
}
template <>
void convert<car_sim::PointCloudSample>(OutPort& p, const car_sim::PointCloudSample& s, PublishContext& c) {
  send(p, to_msg(s), c);
}

template <>
std::string advertise<car_sim::LidarCloudSample>(OutPort& p, const SetupContext& c) {
  return advertise_topic<sensor_msgs::PointCloud2>(p, c);
}
template <>
void convert<car_sim::LidarCloudSample>(OutPort& p, const car_sim::LidarCloudSample& s, PublishContext& c) {
  send(p, to_msg(s), c);
}

template <>
std::string advertise<car_sim::RangeSample>(OutPort& p, const SetupContext& c) {
  return advertise_topic<sensor_msgs::Range>(p, c);
}
// at most one per min_period of sim time (PeriodGate: upstream's rule)
template <>
void convert<car_sim::RangeSample>(OutPort& p, const car_sim::RangeSample& s, PublishContext& c) {
  if (!p.gate.due(static_cast<int64_t>(c.stamp.toNSec()))) return;
  send(p, to_msg(s), c);
}

template <>
std::string advertise<car_sim::ImuSample>(OutPort& p, const SetupContext& c) {
  return advertise_topic<sensor_msgs::Imu>(p, c);
}
template <>
void convert<car_sim::ImuSample>(OutPort& p, const car_sim::ImuSample& s, PublishContext& c) {
  send(p, to_msg(s, p.port), c);
}

template <>
std::string advertise<car_sim::NavSatFixSample>(OutPort& p, const SetupContext& c) {
  return advertise_topic<sensor_msgs::NavSatFix>(p, c);
}
template <>
void convert<car_sim::NavSatFixSample>(OutPort& p, const car_sim::NavSatFixSample& s, PublishContext& c) {
  send(p, to_msg(s), c);
}

template <>
std::string advertise<car_sim::Vector3Sample>(OutPort& p, const SetupContext& c) {
  return advertise_topic<geometry_msgs::Vector3Stamped>(p, c);
}
template <>
void convert<car_sim::Vector3Sample>(OutPort& p, const car_sim::Vector3Sample& s, PublishContext& c) {
  geometry_msgs::Vector3Stamped m;
  m.vector = to_vector3(s.vector);
  send(p, std::move(m), c);
}

template <>
std::string advertise<car_sim::MagneticFieldSample>(OutPort& p, const SetupContext& c) {
  return advertise_topic<sensor_msgs::MagneticField>(p, c);
}
template <>
void convert<car_sim::MagneticFieldSample>(OutPort& p, const car_sim::MagneticFieldSample& s, PublishContext& c) {
  sensor_msgs::MagneticField m;
  m.magnetic_field = to_vector3(s.vector);
  send(p, std::move(m), c);
}

template <>
std::string advertise<car_sim::WrenchSample>(OutPort& p, const SetupContext& c) {
  return advertise_topic<geometry_msgs::WrenchStamped>(p, c);
}
template <>
void convert<car_sim::WrenchSample>(OutPort& p, const car_sim::WrenchSample& s, PublishContext& c) {
  geometry_msgs::WrenchStamped m;
  m.wrench = to_wrench(s.wrench);
  send(p, std::move(m), c);
}

template <>
std::string advertise<car_sim::ContactsSample>(OutPort& p, const SetupContext& c) {
  return advertise_topic<gazebo_msgs::ContactsState>(p, c);
}
template <>
void convert<car_sim::ContactsSample>(OutPort& p, const car_sim::ContactsSample& s, PublishContext& c) {
  c.node.publish(p.pub, to_msg(s.states, c.header));
}

template <>
std::string advertise<car_sim::TransformSample>(OutPort& p, const SetupContext&) {
  return "TF " + p.frames.frame + " -> " + p.frames.child_frame;
}
template <>
void convert<car_sim::TransformSample>(OutPort& p, const car_sim::TransformSample& s, PublishContext& c) {
  geometry_msgs::TransformStamped t;
  t.header = c.header;
  t.child_frame_id = p.frames.child_frame;
  t.transform = to_transform(s.pose);
  c.node.send_tf(std::move(t));
}

// ---- ros_control's controllers ----

template <>
std::string advertise<car_sim::ControllerStateSample>(OutPort& p, const SetupContext& c) {
  return advertise_topic<control_msgs::JointControllerState>(p, c);
}
template <>
void convert<car_sim::ControllerStateSample>(OutPort& p, const car_sim::ControllerStateSample& s, PublishContext& c) {
  send(p, to_msg(s), c);
}

template <>
std::string advertise<car_sim::TrajectoryStateSample>(OutPort& p, const SetupContext& c) {
  return advertise_topic<control_msgs::JointTrajectoryControllerState>(p, c);
}
template <>
void convert<car_sim::TrajectoryStateSample>(OutPort& p, const car_sim::TrajectoryStateSample& s, PublishContext& c) {
  send(p, to_msg(s), c);
}

// no topic of its own: the action server of the input port on the same namespace answers
template <>
std::string advertise<car_sim::GoalResultSample>(OutPort&, const SetupContext&) {
  return "";
}
template <>
void convert<car_sim::GoalResultSample>(OutPort& p, const car_sim::GoalResultSample& s, PublishContext& c) {
  c.node.finish_goal(p.port.topic, s);
}

// ---- the table ------------------------------------------------------------------------------------------------

namespace {

// A sample type's converter, by the index of its alternative in car_sim::Sample.
struct Converter {
  std::string (*advertise)(OutPort& p, const SetupContext& c);
  void (*convert)(OutPort& p, const Sample& s, PublishContext& c);
};

template <size_t I>
Converter converter_of() {
  using A = std::variant_alternative_t<I, Sample>;
  using S = std::remove_const_t<std::remove_pointer_t<A>>;
  const auto convert_one = [](OutPort& p, const Sample& s, PublishContext& c) {
    if constexpr (std::is_pointer_v<A>) {
      if (const A sample = std::get<I>(s)) convert<S>(p, *sample, c);
    } else {
      convert<S>(p, std::get<I>(s), c);
    }
  };
  return {&advertise<S>, convert_one};
}

// Every alternative's but std::monostate's (index 0: no sample)
template <size_t... Is>
std::array<Converter, sizeof...(Is) + 1> converters(std::index_sequence<Is...>) {
  return {{{nullptr, nullptr}, converter_of<Is + 1>()...}};
}

const std::array<Converter, car_sim::detail::kSampleTypes> kConverters =
    converters(std::make_index_sequence<car_sim::detail::kSampleTypes - 1>());

}  // namespace

// ---- OutputPorts ----------------------------------------------------------------------------------------------

std::string OutputPorts::setup(const car_sim::PluginInfo& plugin, const car_sim::RobotInfo& robot, NodeContext& node) {
  model_ = &robot.model;
  std::string offers;
  const SetupContext c{plugin, node};
  std::vector<OutPort> old = std::move(ports_);
  ports_.clear();
  for (const car_sim::OutputPort& op : plugin.outputs) {
    // called again when the instance's ports change: a port of the same name, type and topic keeps its publisher
    auto same = std::find_if(old.begin(), old.end(), [&op](const OutPort& o) {
      return o.port.name == op.name && o.port.type == op.type && o.port.topic == op.topic;
    });
    if (same != old.end()) {
      ports_.push_back(std::move(*same));
      old.erase(same);
      continue;
    }
    OutPort p;
    p.port = op;
    // a throttled publisher's period [s] (range's updateRate; a CameraInfo port sets its own)
    p.gate = car_sim::PeriodGate(op.min_period);
    p.frames = port_frames(op, tf_prefix_param);
    const std::string words = kConverters[op.type.index].advertise(p, c);
    if (!words.empty()) offers += (offers.empty() ? "" : ", ") + words;
    ports_.push_back(std::move(p));
  }
  set_debug_level(plugin.config);
  return offers;
}

bool OutputPorts::listened() const {
  for (const OutPort& p : ports_) {
    if (p.pub && p.pub.getNumSubscribers() > 0) return true;
    // TF has no subscriber count: a port that only sends a transform always has listeners
    if (p.port.type == car_sim::sample_type<car_sim::TransformSample>()) return true;
  }
  return false;
}

uint32_t OutputPorts::parts() const {
  uint32_t taken = 0, idle = 0;
  bool any = false;
  for (const OutPort& p : ports_) {
    any = any || p.port.parts != 0 || p.port.idle_parts != 0;
    idle |= p.port.idle_parts;
    if (p.pub && p.pub.getNumSubscribers() > 0) taken |= p.port.parts;
  }
  if (!any) return ~0u;
  return taken ? taken : idle;
}

void OutputPorts::publish(std::shared_ptr<const car_sim::Output> owned, NodeContext& node) {
  samples_.clear();
  owned->samples(samples_);
  PublishContext c{owned, *model_, node.stamp(owned->tick), {}, node};
  c.header.stamp = c.stamp;
  for (OutPort& p : ports_) {
    // an output for one port (a controller's) goes out on that port only
    if (!owned->port.empty() && owned->port != p.port.name) continue;
    const Sample s = samples_.find(p.port.type, p.port.name, p.port.image.frame);
    if (s.index() == 0) continue;
    c.header.frame_id = p.frames.frame;
    kConverters[s.index()].convert(p, s, c);
  }
  samples_.clear();
}

}  // namespace car_ros
