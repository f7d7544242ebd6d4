// The output half of the ROS bridge: samples -> messages, by sample type (the camera types: outputs_image.cpp).
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
#include <cctype>
#include <cstring>
#include <map>
#include <sstream>

#include "conversions.hpp"

namespace car_ros {

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

// ---- sensors: laser, range, imu, gps, magnetic, wrench, contacts, pose ----

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

}  // namespace

std::string OutputPorts::setup(const car_sim::PluginInfo& plugin, const car_sim::RobotInfo& robot, NodeContext& node) {
  model_ = &robot.model;
  std::string offers;
  auto add = [&offers](const std::string& s) { offers += (offers.empty() ? "" : ", ") + s; };
  using T = car_sim::SampleType;
  std::vector<Port> old = std::move(ports_);
  ports_.clear();
  for (const car_sim::OutputPort& op : plugin.outputs) {
    // called again when the instance's ports change: a port of the same name, type and topic keeps its publisher
    auto same = std::find_if(old.begin(), old.end(), [&op](const Port& o) {
      return o.port.name == op.name && o.port.type == op.type && o.port.topic == op.topic;
    });
    if (same != old.end()) {
      ports_.push_back(std::move(*same));
      old.erase(same);
      continue;
    }
    Port p;
    p.port = op;
    // a throttled publisher's period [s] (range's updateRate, camera_info's)
    p.gate = car_sim::PeriodGate(op.type == T::CameraInfo ? op.image.period : op.min_period);
    // GazeboRos::resolveTF: tf_prefix from the plug-in's namespace (docs/COMPAT-spawn.md rule 4)
    if (op.frames_as_written) {
      p.frame = op.frame;
      p.child_frame = op.child_frame;
    } else if (op.frame_prefix_here) {
      p.prefix = tf_prefix_here(op.ns);
      p.frame = resolve_tf(p.prefix, op.frame);
      p.child_frame = op.child_frame;
    } else if (op.tf_prefix) {
      p.prefix = tf_prefix_param(op.ns);
      p.frame = resolve_tf(p.prefix, op.frame);
      p.child_frame = resolve_tf(p.prefix, op.child_frame);
    } else {
      p.frame = frame(op.frame);
      p.child_frame = op.child_frame;
    }
    switch (op.type) {
      case T::Odometry:
        if (!op.topic.empty()) p.pub = node.advertise<nav_msgs::Odometry>(op.topic, op.queue);
        else
          ROS_WARN("car: %s: %s: no odometry topic at all (like gazebo_ros with publishTf false)", plugin.robot.c_str(),
                   plugin.config.name.c_str());
        add("odometry " + (op.topic.empty() ? std::string("(none)") : op.topic) + " (" + p.frame + " -> " +
            p.child_frame + (op.tf != car_sim::TfOrder::None ? ", TF" : "") + ")");
        break;
      case T::JointStates:
        p.pub = node.advertise<sensor_msgs::JointState>(op.topic, op.queue);
        add("joint states " + op.topic);
        break;
      case T::JointTransforms: add("wheel TF"); break;
      case T::Image:
      case T::CameraInfo:
      case T::DepthImage:
      case T::DepthCloud: add(setup_image(p, node)); break;
      // ---- sensors: laser, range, imu, gps, magnetic, wrench, contacts, pose ----
      case T::LaserScan: p.pub = node.advertise<sensor_msgs::LaserScan>(op.topic, op.queue); break;
      case T::PointCloud: p.pub = node.advertise<sensor_msgs::PointCloud>(op.topic, op.queue); break;
      case T::LidarCloud: p.pub = node.advertise<sensor_msgs::PointCloud2>(op.topic, op.queue); break;
      case T::Range: p.pub = node.advertise<sensor_msgs::Range>(op.topic, op.queue); break;
      case T::Imu: p.pub = node.advertise<sensor_msgs::Imu>(op.topic, op.queue); break;
      case T::NavSatFix: p.pub = node.advertise<sensor_msgs::NavSatFix>(op.topic, op.queue); break;
      case T::Vector3: p.pub = node.advertise<geometry_msgs::Vector3Stamped>(op.topic, op.queue); break;
      case T::MagneticField: p.pub = node.advertise<sensor_msgs::MagneticField>(op.topic, op.queue); break;
      case T::Wrench: p.pub = node.advertise<geometry_msgs::WrenchStamped>(op.topic, op.queue); break;
      case T::Contacts: p.pub = node.advertise<gazebo_msgs::ContactsState>(op.topic, op.queue); break;
      case T::Transform: add("TF " + p.frame + " -> " + p.child_frame); break;
      // ---- ros_control's controllers ----
      case T::ControllerState:
        p.pub = node.advertise<control_msgs::JointControllerState>(op.topic, op.queue);
        break;
      case T::TrajectoryState:
        p.pub = node.advertise<control_msgs::JointTrajectoryControllerState>(op.topic, op.queue);
        break;
      case T::GoalResult: break;  // the action server of the input port on the same namespace answers
    }
    // the sensors' ports: the topic and frame for the log line (the cameras' setup_image says its own words)
    const bool image = op.type == T::Image || op.type == T::CameraInfo || op.type == T::DepthImage ||
                       op.type == T::DepthCloud;
    if (p.pub && op.type != T::Odometry && op.type != T::JointStates && !image)
      add(p.pub.getTopic() + (p.frame.empty() ? std::string() : " (frame " + p.frame + ")"));
    ports_.push_back(std::move(p));
  }
  set_debug_level(plugin.config);
  return offers;
}

bool OutputPorts::listened() const {
  for (const Port& p : ports_) {
    if (p.pub && p.pub.getNumSubscribers() > 0) return true;
    // TF has no subscriber count: a port that only sends a transform always has listeners
    if (p.port.type == car_sim::SampleType::Transform) return true;
  }
  return false;
}

uint32_t OutputPorts::parts() const {
  uint32_t taken = 0, idle = 0;
  bool any = false;
  for (const Port& p : ports_) {
    any = any || p.port.parts != 0 || p.port.idle_parts != 0;
    idle |= p.port.idle_parts;
    if (p.pub && p.pub.getNumSubscribers() > 0) taken |= p.port.parts;
  }
  if (!any) return ~0u;
  return taken ? taken : idle;
}

void OutputPorts::publish(std::shared_ptr<const car_sim::Output> owned, NodeContext& node) {
  const car_sim::Output& out = *owned;
  const ros::Time stamp = node.stamp(out.tick);
  std_msgs::Header header;
  header.stamp = stamp;
  car_sim::OdometrySample o;
  const bool has_odometry = out.odometry_sample(&o);
  static const std::vector<car_sim::JointState> kNone;
  const std::vector<car_sim::JointState>* sample = out.joint_states_sample();
  const std::vector<car_sim::JointState>& joints = sample ? *sample : kNone;
  using T = car_sim::SampleType;
  for (Port& p : ports_) {
    // an output for one port (a controller's) goes out on that port only
    if (!out.port.empty() && out.port != p.port.name) continue;
    header.frame_id = p.frame;
    switch (p.port.type) {
      case T::Odometry: {
        if (!has_odometry) break;
        nav_msgs::Odometry m;
        m.header.stamp = stamp;
        m.header.frame_id = p.frame;
        m.child_frame_id = p.child_frame;
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
        // the transform is made before the odometry is moved to the publishing thread
        geometry_msgs::TransformStamped t;
        if (p.port.tf != car_sim::TfOrder::None) {
          t.header = m.header;
          t.child_frame_id = m.child_frame_id;
          t.transform = to_transform(o.pose);
          t.transform.rotation = m.pose.pose.orientation;
        }
        if (p.port.tf == car_sim::TfOrder::Before) node.send_tf(std::move(t));
        if (p.pub) node.publish(p.pub, std::move(m));
        if (p.port.tf == car_sim::TfOrder::After) node.send_tf(std::move(t));
        break;
      }
      case T::JointStates: {
        if (!sample) break;
        sensor_msgs::JointState js;
        js.header.stamp = stamp;
        js.name.reserve(joints.size());
        js.position.reserve(joints.size());
        js.velocity.reserve(joints.size());
        for (const auto& j : joints) {
          js.name.push_back(j.name);
          js.position.push_back(j.position);
          js.velocity.push_back(j.velocity);
        }
        if (p.port.with_effort)
          if (const std::vector<double>* e = out.joint_efforts_sample()) js.effort = *e;
        node.publish(p.pub, std::move(js));
        break;
      }
      case T::JointTransforms:
        // fix: each child link relative to its parent link (upstream drives publish the wheels relative to the
        // odometry frame, or name the child frame after the joint)
        for (const auto& j : joints) {
          const car_sim::Joint* joint = model_->find_joint(j.name);
          geometry_msgs::TransformStamped w;
          w.header.stamp = stamp;
          w.header.frame_id = resolve_tf(p.prefix, joint->parent);
          w.child_frame_id = resolve_tf(p.prefix, joint->child);
          Eigen::Isometry3d T = joint->origin;
          T.rotate(Eigen::AngleAxisd(j.position, joint->axis));
          w.transform = to_transform(T);
          node.send_tf(std::move(w));
        }
        break;
      case T::Image:
      case T::CameraInfo:
      case T::DepthImage:
      case T::DepthCloud: publish_image(p, owned, stamp, node); break;
      // ---- sensors: laser, range, imu, gps, magnetic, wrench, contacts, pose ----
      case T::LaserScan:
        if (const auto* s = out.laser_scan_sample()) publish(p, to_msg(*s), header, node);
        break;
      case T::PointCloud:
        if (const auto* s = out.point_cloud_sample()) publish(p, to_msg(*s), header, node);
        break;
      case T::LidarCloud:
        if (const auto* s = out.lidar_cloud_sample()) publish(p, to_msg(*s), header, node);
        break;
      case T::Range: {
        const auto* s = out.range_sample();
        if (!s) break;
        // at most one per min_period of sim time (PeriodGate: upstream's rule)
        if (!p.gate.due(static_cast<int64_t>(stamp.toNSec()))) break;
        publish(p, to_msg(*s), header, node);
        break;
      }
      case T::Imu: {
        car_sim::ImuSample s;
        if (out.imu_sample(p.port.name, &s)) publish(p, to_msg(s, p.port), header, node);
        break;
      }
      case T::NavSatFix:
        if (const auto* s = out.nav_sat_fix_sample()) publish(p, to_msg(*s), header, node);
        break;
      case T::Vector3: {
        Eigen::Vector3d v;
        if (!out.vector3_sample(&v)) break;
        geometry_msgs::Vector3Stamped m;
        m.vector = to_vector3(v);
        publish(p, std::move(m), header, node);
        break;
      }
      case T::MagneticField: {
        Eigen::Vector3d v;
        if (!out.vector3_sample(&v)) break;
        sensor_msgs::MagneticField m;
        m.magnetic_field = to_vector3(v);
        publish(p, std::move(m), header, node);
        break;
      }
      case T::Wrench: {
        const car_sim::Wrench* w = out.wrench_sample();
        if (!w) break;
        geometry_msgs::WrenchStamped m;
        m.wrench = to_wrench(*w);
        publish(p, std::move(m), header, node);
        break;
      }
      case T::Contacts:
        if (const auto* s = out.contacts_sample()) node.publish(p.pub, to_msg(*s, header));
        break;
      case T::Transform: {
        Eigen::Isometry3d pose;
        if (!out.pose_sample(&pose)) break;
        geometry_msgs::TransformStamped t;
        t.header = header;
        t.child_frame_id = p.child_frame;
        t.transform = to_transform(pose);
        node.send_tf(std::move(t));
        break;
      }
      // ---- ros_control's controllers ----
      case T::ControllerState: {
        const car_sim::ControllerStateSample* s = out.controller_state_sample();
        if (!s) break;
        control_msgs::JointControllerState m;
        m.set_point = s->set_point;
        m.process_value = s->process_value;
        m.process_value_dot = s->process_value_dot;
        m.error = s->error;
        m.time_step = s->time_step;
        m.command = s->command;
        m.p = s->p;
        m.i = s->i;
        m.d = s->d;
        m.i_clamp = s->i_clamp;
        m.antiwindup = s->antiwindup;
        publish(p, std::move(m), header, node);
        break;
      }
      case T::TrajectoryState: {
        const car_sim::TrajectoryStateSample* s = out.trajectory_state_sample();
        if (!s) break;
        control_msgs::JointTrajectoryControllerState m;
        m.joint_names = s->joints;
        m.desired.positions = s->desired_position;
        m.desired.velocities = s->desired_velocity;
        m.actual.positions = s->actual_position;
        m.actual.velocities = s->actual_velocity;
        for (size_t k = 0; k < s->joints.size(); ++k) {
          m.error.positions.push_back(s->desired_position[k] - s->actual_position[k]);
          m.error.velocities.push_back(s->desired_velocity[k] - s->actual_velocity[k]);
        }
        publish(p, std::move(m), header, node);
        break;
      }
      case T::GoalResult:
        if (const car_sim::GoalResultSample* s = out.goal_result_sample()) node.finish_goal(p.port.topic, *s);
        break;
    }
  }
}

}  // namespace car_ros
