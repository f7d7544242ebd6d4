// The input half of the ROS bridge: ROS messages -> car_sim::Command, by sample type.
#include "inputs.hpp"

#include <actionlib/server/action_server.h>
#include <control_msgs/FollowJointTrajectoryAction.h>
#include <geometry_msgs/Twist.h>
#include <geometry_msgs/Wrench.h>
#include <std_msgs/Empty.h>
#include <std_msgs/Float64.h>
#include <std_msgs/Float64MultiArray.h>
#include <trajectory_msgs/JointTrajectory.h>

#include <algorithm>
#include <map>

#include "conversions.hpp"

namespace car_ros {

using FjtServer = actionlib::ActionServer<control_msgs::FollowJointTrajectoryAction>;

// One input port of one plug-in instance, and what its messages need: the names to command, the subscriber.
struct InputPorts::Port {
  ~Port() {
    if (action) node->drop_goal_sink(port.topic, this);
  }
  std::string robot, plugin;
  car_sim::InputPort port;
  NodeContext* node = nullptr;
  ros::Subscriber sub;
  // a Pose read from TF: its own buffer and listener; a failed lookup is logged once until one succeeds again
  std::unique_ptr<tf2_ros::Buffer> buffer;
  std::unique_ptr<tf2_ros::TransformListener> listener;
  bool tf_failing = false;
  std::chrono::steady_clock::time_point last_warning;
  // a TrajectoryGoal: the action server and its goals by the id the core knows them by
  std::unique_ptr<FjtServer> action;
  std::map<uint64_t, FjtServer::GoalHandle> goals;
  uint64_t next_goal = 1;

  // Hands one value to the world and logs what came of it.
  car_sim::CommandResult command(car_sim::Command value) {
    const car_sim::CommandResult r = node->world().command(robot, plugin, port.name, std::move(value));
    if (!r.accepted) {
      // throttled in wall time: sim time stands still while paused and restarts at 0 after a reset
      const auto now = std::chrono::steady_clock::now();
      if (last_warning.time_since_epoch().count() == 0 || now - last_warning > std::chrono::seconds(1)) {
        ROS_WARN("car: %s: %s: rejected a %s with %s", robot.c_str(), plugin.c_str(),
                 car_sim::command_noun(port.type), r.reason.c_str());
        last_warning = now;
      }
    }
    for (const auto& n : r.notes) {
      if (n.error)
        ROS_ERROR("car: %s: %s", plugin.c_str(), n.text.c_str());
      else
        ROS_WARN("car: %s: %s", plugin.c_str(), n.text.c_str());
    }
    return r;
  }

  void on_goal(FjtServer::GoalHandle gh);
  void on_cancel(FjtServer::GoalHandle gh);
  void on_result(const car_sim::GoalResultSample& s);
};

namespace {

car_sim::Command from_msg(const geometry_msgs::Twist& m) {
  car_sim::Twist t;
  t.linear = Eigen::Vector3d(m.linear.x, m.linear.y, m.linear.z);
  t.angular = Eigen::Vector3d(m.angular.x, m.angular.y, m.angular.z);
  return t;
}

car_sim::Command from_msg(const geometry_msgs::Wrench& m) {
  car_sim::Wrench w;
  w.force = Eigen::Vector3d(m.force.x, m.force.y, m.force.z);
  w.torque = Eigen::Vector3d(m.torque.x, m.torque.y, m.torque.z);
  return w;
}

car_sim::JointTrajectory to_trajectory(const trajectory_msgs::JointTrajectory& m) {
  car_sim::JointTrajectory t;
  t.joint_names = m.joint_names;
  t.start = m.header.stamp.toSec();
  t.frame_id = m.header.frame_id;
  for (const auto& p : m.points) {
    car_sim::TrajectoryPoint q;
    q.positions = p.positions;
    q.velocities = p.velocities;
    q.accelerations = p.accelerations;
    q.time_from_start = p.time_from_start.toSec();
    t.points.push_back(std::move(q));
  }
  return t;
}

car_sim::Command from_msg(const trajectory_msgs::JointTrajectory& m) { return to_trajectory(m); }
car_sim::Command from_msg(const std_msgs::Empty&) { return car_sim::Trigger{}; }
car_sim::Command from_msg(const std_msgs::Float64& m) { return car_sim::Float64{m.data}; }
car_sim::Command from_msg(const std_msgs::Float64MultiArray& m) { return car_sim::Float64Array{m.data}; }

// A subscriber that hands each message, converted, to the port (the callback runs on the node's thread between
// steps).
template <class M>
ros::Subscriber subscribe(NodeContext& node, const std::shared_ptr<InputPorts::Port>& port) {
  InputPorts::Port* p = port.get();
  return node.nh().subscribe<M>(port->port.topic, port->port.queue,
                                [p](const typename M::ConstPtr& m) { p->command(from_msg(*m)); });
}

}  // namespace

// A goal: numbered, handed to the core; accepted, or rejected with the core's code and reason.
void InputPorts::Port::on_goal(FjtServer::GoalHandle gh) {
  const auto& goal = *gh.getGoal();
  car_sim::TrajectoryGoal g;
  g.id = next_goal++;
  g.trajectory = to_trajectory(goal.trajectory);
  for (const auto& t : goal.path_tolerance) g.path_position[t.name] = t.position;
  for (const auto& t : goal.goal_tolerance) g.goal_position[t.name] = t.position;
  if (!goal.goal_time_tolerance.isZero()) g.goal_time_tolerance = goal.goal_time_tolerance.toSec();
  const car_sim::CommandResult r = command(std::move(g));
  if (!r.accepted || r.refused) {
    control_msgs::FollowJointTrajectoryResult res;
    res.error_code = r.refused ? r.code : control_msgs::FollowJointTrajectoryResult::INVALID_GOAL;
    res.error_string = r.reason;
    gh.setRejected(res, r.reason);
    return;
  }
  gh.setAccepted();
  goals[g.id] = gh;
}

// A cancel: the core stops the goal; the action answers at once.
void InputPorts::Port::on_cancel(FjtServer::GoalHandle gh) {
  for (auto it = goals.begin(); it != goals.end(); ++it)
    if (it->second == gh) {
      car_sim::TrajectoryGoal c;
      c.id = it->first;
      c.cancel = true;
      command(std::move(c));
      control_msgs::FollowJointTrajectoryResult r;
      gh.setCanceled(r);
      goals.erase(it);
      return;
    }
}

// A goal's end, from the port's GoalResult output.
void InputPorts::Port::on_result(const car_sim::GoalResultSample& s) {
  const auto g = goals.find(s.goal);
  if (g == goals.end()) return;
  control_msgs::FollowJointTrajectoryResult res;
  res.error_code = s.error_code;
  res.error_string = s.error_string;
  // the controller's states up to the goal's end go out before its result
  node->flush_published();
  using S = car_sim::GoalResultSample::Status;
  if (s.status == S::Succeeded)
    g->second.setSucceeded(res);
  else if (s.status == S::Canceled)
    g->second.setCanceled(res, s.error_string);
  else
    g->second.setAborted(res, s.error_string);
  goals.erase(g);
}

std::string InputPorts::setup(const car_sim::PluginInfo& plugin, NodeContext& node) {
  std::string topics;
  std::vector<std::shared_ptr<Port>> old = std::move(ports_);
  ports_.clear();
  polled_ = false;
  for (const car_sim::InputPort& ip : plugin.inputs) {
    // a port that stays keeps its subscriber (and its action's goals)
    auto same = std::find_if(old.begin(), old.end(), [&ip](const std::shared_ptr<Port>& o) {
      return o && o->port.name == ip.name && o->port.type == ip.type && o->port.topic == ip.topic;
    });
    if (same != old.end()) {
      polled_ = polled_ || (*same)->buffer != nullptr;
      if ((*same)->sub) topics += (topics.empty() ? "" : ", ") + (*same)->sub.getTopic();
      ports_.push_back(std::move(*same));
      continue;
    }
    auto p = std::make_shared<Port>();
    p->robot = plugin.robot;
    p->plugin = plugin.config.name;
    p->port = ip;
    p->node = &node;
    using T = car_sim::InputType;
    if (ip.type == T::Pose && ip.topic.empty()) {
      p->buffer = std::make_unique<tf2_ros::Buffer>();
      p->listener = std::make_unique<tf2_ros::TransformListener>(*p->buffer);
      polled_ = true;
    } else if (!ip.topic.empty()) {
      switch (ip.type) {
        case T::Twist: p->sub = subscribe<geometry_msgs::Twist>(node, p); break;
        case T::Wrench: p->sub = subscribe<geometry_msgs::Wrench>(node, p); break;
        case T::JointTrajectory: p->sub = subscribe<trajectory_msgs::JointTrajectory>(node, p); break;
        case T::Trigger: p->sub = subscribe<std_msgs::Empty>(node, p); break;
        case T::Float64: p->sub = subscribe<std_msgs::Float64>(node, p); break;
        case T::Float64Array: p->sub = subscribe<std_msgs::Float64MultiArray>(node, p); break;
        case T::Pose: break;
        case T::TrajectoryGoal: {
          Port* raw = p.get();
          p->action = std::make_unique<FjtServer>(
              node.nh(), ip.topic, [raw](FjtServer::GoalHandle gh) { raw->on_goal(gh); },
              [raw](FjtServer::GoalHandle gh) { raw->on_cancel(gh); }, false);
          p->action->start();
          node.set_goal_sink(ip.topic, raw, [raw](const car_sim::GoalResultSample& s) { raw->on_result(s); });
          topics += (topics.empty() ? "" : ", ") + ip.topic + " (action)";
          break;
        }
      }
      if (p->sub) topics += (topics.empty() ? "" : ", ") + p->sub.getTopic();
    }
    ports_.push_back(std::move(p));
  }
  return topics;
}

void InputPorts::poll() {
  for (auto& p : ports_) {
    if (!p->buffer) continue;
    try {
      const geometry_msgs::TransformStamped d =
          p->buffer->lookupTransform(p->port.parent_frame, p->port.frame, ros::Time(0));
      geometry_msgs::Pose pose;
      pose.position.x = d.transform.translation.x;
      pose.position.y = d.transform.translation.y;
      pose.position.z = d.transform.translation.z;
      pose.orientation = d.transform.rotation;
      p->command(car_sim::PoseCommand{from_pose(pose)});
      p->tf_failing = false;
    } catch (const tf2::TransformException& e) {
      if (!p->tf_failing) ROS_ERROR("car: %s: %s", p->plugin.c_str(), e.what());
      p->tf_failing = true;
      car_sim::PoseCommand none;
      none.found = false;
      p->command(none);
    }
  }
}

}  // namespace car_ros
