// The output half of the ROS bridge: samples -> messages, by sample type (the camera types: outputs_image.cpp).
#include "outputs.hpp"

#include <nav_msgs/Odometry.h>
#include <sensor_msgs/JointState.h>

#include <cctype>
#include <map>

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

}  // namespace

std::string OutputPorts::setup(const car_sim::PluginInfo& plugin, const car_sim::RobotInfo& robot, NodeContext& node) {
  model_ = &robot.model;
  std::string offers;
  auto add = [&offers](const std::string& s) { offers += (offers.empty() ? "" : ", ") + s; };
  using T = car_sim::SampleType;
  for (const car_sim::OutputPort& op : plugin.outputs) {
    Port p;
    p.port = op;
    // GazeboRos::resolveTF: tf_prefix from the plug-in's namespace (docs/COMPAT-spawn.md rule 4)
    if (op.tf_prefix) {
      p.prefix = tf_prefix_param(op.ns);
      p.frame = resolve_tf(p.prefix, op.frame);
      p.child_frame = resolve_tf(p.prefix, op.child_frame);
    } else {
      p.frame = frame(op.frame);
      p.child_frame = op.child_frame;
    }
    switch (op.type) {
      case T::Odometry:
        if (!op.topic.empty()) p.pub = node.nh().advertise<nav_msgs::Odometry>(op.topic, op.queue);
        else
          ROS_WARN("car: %s: %s: no odometry topic at all (like gazebo_ros with publishTf false)", plugin.robot.c_str(),
                   plugin.config.name.c_str());
        add("odometry " + (op.topic.empty() ? std::string("(none)") : op.topic) + " (" + p.frame + " -> " +
            p.child_frame + (op.tf != car_sim::TfOrder::None ? ", TF" : "") + ")");
        break;
      case T::JointStates:
        p.pub = node.nh().advertise<sensor_msgs::JointState>(op.topic, op.queue);
        add("joint states " + op.topic);
        break;
      case T::JointTransforms: add("wheel TF"); break;
      case T::Image:
      case T::CameraInfo:
      case T::DepthImage:
      case T::DepthCloud: add(setup_image(p, node)); break;
    }
    ports_.push_back(std::move(p));
  }
  // ---- cameras: a camera_info sent only with its frame's image finds that image's port
  for (Port& p : ports_)
    if (p.port.type == T::CameraInfo && p.port.image.with_image)
      for (size_t i = 0; i < ports_.size(); ++i)
        if (ports_[i].port.type == T::Image && ports_[i].port.image.frame == p.port.image.frame)
          p.image_of = static_cast<int>(i);
  set_debug_level(plugin.config);
  return offers;
}

bool OutputPorts::listened() const {
  for (const Port& p : ports_)
    if (p.pub && p.pub.getNumSubscribers() > 0) return true;
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
  car_sim::OdometrySample o;
  const bool has_odometry = out.odometry_sample(&o);
  static const std::vector<car_sim::JointState> kNone;
  const std::vector<car_sim::JointState>* sample = out.joint_states_sample();
  const std::vector<car_sim::JointState>& joints = sample ? *sample : kNone;
  using T = car_sim::SampleType;
  for (Port& p : ports_) {
    switch (p.port.type) {
      case T::Odometry: {
        if (!has_odometry) break;
        nav_msgs::Odometry m;
        m.header.stamp = stamp;
        m.header.frame_id = p.frame;
        m.child_frame_id = p.child_frame;
        m.pose.pose = to_pose(o.pose);
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
    }
  }
}

}  // namespace car_ros
