// libgazebo_ros_control.so on ROS: controller_manager's services under <robotNamespace>/controller_manager/ and
// each controller's topics and actions, as ros_control / ros_controllers Noetic name them (docs/COMPAT-control.md).
// Single-threaded: service and topic callbacks run between steps, in the node's spinOnce.
#include <actionlib/server/action_server.h>
#include <control_msgs/FollowJointTrajectoryAction.h>
#include <control_msgs/JointControllerState.h>
#include <control_msgs/JointTrajectoryControllerState.h>
#include <controller_manager_msgs/ListControllerTypes.h>
#include <controller_manager_msgs/ListControllers.h>
#include <controller_manager_msgs/LoadController.h>
#include <controller_manager_msgs/ReloadControllerLibraries.h>
#include <controller_manager_msgs/SwitchController.h>
#include <controller_manager_msgs/UnloadController.h>
#include <geometry_msgs/Twist.h>
#include <nav_msgs/Odometry.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/Float64.h>
#include <std_msgs/Float64MultiArray.h>
#include <trajectory_msgs/JointTrajectory.h>

#include <map>
#include <memory>

#include "../adapter.hpp"
#include "../conversions.hpp"
#include "ros_control/controllers.hpp"

namespace car_ros {

namespace {

using car_sim::control::ControllerError;
using FjtServer = actionlib::ActionServer<control_msgs::FollowJointTrajectoryAction>;

// The parameter server's value under a controller's namespace, flattened: "pid/p" -> {"100"}, "joints" -> list.
void flatten(const XmlRpc::XmlRpcValue& v, const std::string& key, car_sim::control::Params* out) {
  auto scalar = [](const XmlRpc::XmlRpcValue& x, std::string* s) {
    XmlRpc::XmlRpcValue c = x;
    switch (c.getType()) {
      case XmlRpc::XmlRpcValue::TypeBoolean: *s = static_cast<bool>(c) ? "true" : "false"; return true;
      case XmlRpc::XmlRpcValue::TypeInt: *s = std::to_string(static_cast<int>(c)); return true;
      case XmlRpc::XmlRpcValue::TypeDouble: {
        char b[64];
        std::snprintf(b, sizeof b, "%.17g", static_cast<double>(c));
        *s = b;
        return true;
      }
      case XmlRpc::XmlRpcValue::TypeString: *s = static_cast<std::string>(c); return true;
      default: return false;
    }
  };
  XmlRpc::XmlRpcValue c = v;
  std::string s;
  if (c.getType() == XmlRpc::XmlRpcValue::TypeStruct) {
    for (auto it = c.begin(); it != c.end(); ++it)
      flatten(it->second, key.empty() ? it->first : key + "/" + it->first, out);
  } else if (c.getType() == XmlRpc::XmlRpcValue::TypeArray) {
    auto& list = (*out)[key];
    for (int i = 0; i < c.size(); ++i)
      if (scalar(c[i], &s)) list.push_back(s);
  } else if (scalar(c, &s)) {
    (*out)[key] = {s};
  }
}

// A service with a typed callback (generic lambdas are ambiguous for advertiseService's overloads).
template <class S, class F>
ros::ServiceServer serve(ros::NodeHandle& nh, const std::string& name, F f) {
  using Rq = typename S::Request;
  using Rs = typename S::Response;
  return nh.advertiseService<Rq, Rs>(name, boost::function<bool(Rq&, Rs&)>([f](Rq& rq, Rs& rs) { return f(rq, rs); }));
}

std::string join_ns(const std::string& a, const std::string& b) { return a.empty() ? "/" + b : "/" + a + "/" + b; }

// One loaded controller's topics.
struct CtlRos {
  std::string type;
  ros::Publisher pub;
  ros::Subscriber sub;
  std::unique_ptr<FjtServer> action;
  std::map<uint64_t, FjtServer::GoalHandle> goals;
  uint64_t next_goal = 1;
};

class RosControlAdapter : public Adapter {
 public:
  std::string setup(const car_sim::PluginInfo& p, const car_sim::RobotInfo& robot, NodeContext& node) override {
    node_ = &node;
    // <robotNamespace> absent: the model's name, empty: global, as gazebo_ros_control
    ns_ = car_sim::plugin_robot_namespace(p.config, robot.name);
    while (!ns_.empty() && ns_.front() == '/') ns_.erase(ns_.begin());
    rc_ = dynamic_cast<car_sim::RosControl*>(node.world().plugin(robot.name, p.config.name));
    if (!rc_) return "";
    const std::string cm = join_ns(ns_, "controller_manager");
    auto& nh = node.nh();
    namespace cm_msgs = controller_manager_msgs;
    srv_.push_back(serve<cm_msgs::LoadController>(nh, cm + "/load_controller", [this](auto& rq, auto& rs) {
      rs.ok = load(rq.name);
      return true;
    }));
    srv_.push_back(serve<cm_msgs::UnloadController>(nh, cm + "/unload_controller", [this](auto& rq, auto& rs) {
      rs.ok = unload(rq.name);
      return true;
    }));
    srv_.push_back(serve<cm_msgs::SwitchController>(nh, cm + "/switch_controller", [this](auto& rq, auto& rs) {
      rs.ok = switch_(rq);
      return true;
    }));
    srv_.push_back(serve<cm_msgs::ListControllers>(nh, cm + "/list_controllers", [this](auto&, auto& rs) {
      list(&rs);
      return true;
    }));
    srv_.push_back(serve<cm_msgs::ListControllerTypes>(nh, cm + "/list_controller_types", [](auto&, auto& rs) {
      for (const auto& t : car_sim::control::controller_types()) {
        rs.types.push_back(t.name);
        rs.base_classes.push_back(t.base_class);
      }
      return true;
    }));
    srv_.push_back(serve<cm_msgs::ReloadControllerLibraries>(
        nh, cm + "/reload_controller_libraries", [this](auto& rq, auto& rs) {
          rs.ok = reload(rq.force_kill);
          return true;
        }));
    return "controller_manager services under " + cm + ", " +
           std::to_string(rc_->model().transmissions.size()) + " transmissions";
  }

  void publish(const car_sim::Output& out, NodeContext& node) override {
    const auto* o = dynamic_cast<const car_sim::control::ControllerOutput*>(&out);
    if (!o) return;
    const auto it = ros_.find(o->controller);
    if (it == ros_.end()) return;
    CtlRos& c = *it->second;
    const ros::Time stamp = node.stamp(out.tick);
    using namespace car_sim::control;
    if (const auto* js = dynamic_cast<const JointStatesOutput*>(o)) {
      sensor_msgs::JointState m;
      m.header.stamp = stamp;
      m.name = js->names;
      m.position = js->position;
      m.velocity = js->velocity;
      m.effort = js->effort;
      node.publish(c.pub, std::move(m));
    } else if (const auto* od = dynamic_cast<const DiffDriveOdometryOutput*>(o)) {
      nav_msgs::Odometry m;
      m.header.stamp = stamp;
      m.header.frame_id = od->odom_frame;
      m.child_frame_id = od->base_frame;
      m.pose.pose.position.x = od->x;
      m.pose.pose.position.y = od->y;
      m.pose.pose.orientation.z = std::sin(od->heading / 2);
      m.pose.pose.orientation.w = std::cos(od->heading / 2);
      m.twist.twist.linear.x = od->linear;
      m.twist.twist.angular.z = od->angular;
      for (int i = 0; i < 6; ++i) {
        m.pose.covariance[i * 7] = od->pose_cov[i];
        m.twist.covariance[i * 7] = od->twist_cov[i];
      }
      node.publish(c.pub, m);
      if (od->tf) {
        geometry_msgs::TransformStamped t;
        t.header = m.header;
        t.child_frame_id = m.child_frame_id;
        t.transform.translation.x = od->x;
        t.transform.translation.y = od->y;
        t.transform.rotation = m.pose.pose.orientation;
        node.send_tf(std::move(t));
      }
    } else if (const auto* st = dynamic_cast<const JointControllerStateOutput*>(o)) {
      control_msgs::JointControllerState m;
      m.header.stamp = stamp;
      m.set_point = st->set_point;
      m.process_value = st->process_value;
      m.process_value_dot = st->process_value_dot;
      m.error = st->error;
      m.time_step = st->time_step;
      m.command = st->command;
      m.p = st->pid.p;
      m.i = st->pid.i;
      m.d = st->pid.d;
      m.i_clamp = st->pid.i_max;
      m.antiwindup = st->pid.antiwindup;
      node.publish(c.pub, std::move(m));
    } else if (const auto* ts = dynamic_cast<const TrajectoryStateOutput*>(o)) {
      control_msgs::JointTrajectoryControllerState m;
      m.header.stamp = stamp;
      m.joint_names = ts->joints;
      m.desired.positions = ts->desired_position;
      m.desired.velocities = ts->desired_velocity;
      m.actual.positions = ts->actual_position;
      m.actual.velocities = ts->actual_velocity;
      for (size_t k = 0; k < ts->joints.size(); ++k) {
        m.error.positions.push_back(ts->desired_position[k] - ts->actual_position[k]);
        m.error.velocities.push_back(ts->desired_velocity[k] - ts->actual_velocity[k]);
      }
      node.publish(c.pub, std::move(m));
    } else if (const auto* r = dynamic_cast<const TrajectoryResultOutput*>(o)) {
      const auto g = c.goals.find(r->goal);
      if (g == c.goals.end()) return;
      control_msgs::FollowJointTrajectoryResult res;
      res.error_code = r->error_code == -6 ? 0 : r->error_code;
      res.error_string = r->error_string;
      // the controller's states up to the goal's end go out before its result
      node.flush_published();
      if (r->error_code == 0)
        g->second.setSucceeded(res);
      else if (r->error_code == -6)
        g->second.setCanceled(res, r->error_string);
      else
        g->second.setAborted(res, r->error_string);
      c.goals.erase(g);
    }
  }

 private:
  double now() const { return node_->world().time(); }

  bool load(const std::string& name) {
    // the controller's parameters at <ns>/<name>/, as controller_manager reads them
    const std::string pns = join_ns(ns_, name);
    XmlRpc::XmlRpcValue v;
    if (!ros::param::get(pns, v)) {
      ROS_ERROR("car: controller_manager: could not load controller '%s': no parameters at %s (load the YAML first)",
                name.c_str(), pns.c_str());
      return false;
    }
    car_sim::control::Params params;
    flatten(v, "", &params);
    const auto t = params.find("type");
    if (t == params.end() || t->second.size() != 1) {
      ROS_ERROR("car: controller_manager: could not load controller '%s': %s/type: missing (required key)",
                name.c_str(), pns.c_str());
      return false;
    }
    try {
      rc_->load(name, t->second[0], params);
    } catch (const std::exception& e) {
      ROS_ERROR("car: controller_manager: could not load controller: %s (parameters at %s)", e.what(), pns.c_str());
      return false;
    }
    auto c = std::make_unique<CtlRos>();
    c->type = t->second[0];
    make_topics(name, c.get());
    ros_[name] = std::move(c);
    ROS_INFO("car: controller_manager: loaded '%s' (%s)", name.c_str(), t->second[0].c_str());
    return true;
  }

  void make_topics(const std::string& name, CtlRos* c) {
    auto& nh = node_->nh();
    const std::string cns = join_ns(ns_, name);
    car_sim::control::Controller* ctl = rc_->controller(name);
    const std::string& type = c->type;
    if (type == "joint_state_controller/JointStateController") {
      c->pub = nh.advertise<sensor_msgs::JointState>(join_ns(ns_, "joint_states"), 10);
    } else if (auto* dd = dynamic_cast<car_sim::control::DiffDriveController*>(ctl)) {
      c->pub = nh.advertise<nav_msgs::Odometry>(cns + "/odom", 100);
      c->sub = nh.subscribe<geometry_msgs::Twist>(cns + "/cmd_vel", 1, [this, dd](const geometry_msgs::Twist::ConstPtr& m) {
        dd->set_twist(m->linear.x, m->angular.z, now());
      });
    } else if (auto* tc = dynamic_cast<car_sim::control::TrajectoryController*>(ctl)) {
      c->pub = nh.advertise<control_msgs::JointTrajectoryControllerState>(cns + "/state", 1);
      c->sub = nh.subscribe<trajectory_msgs::JointTrajectory>(
          cns + "/command", 1, [this, tc, name](const trajectory_msgs::JointTrajectory::ConstPtr& m) {
            if (!running(name)) return;
            std::string why;
            int code = 0;
            if (!tc->set_trajectory(to_goal(*m), 0, now(), &why, &code))
              ROS_ERROR("car: controller '%s': trajectory refused: %s", name.c_str(), why.c_str());
          });
      c->action = std::make_unique<FjtServer>(
          nh, cns + "/follow_joint_trajectory",
          [this, tc, name, c](FjtServer::GoalHandle gh) { on_goal(name, tc, c, gh); },
          [this, tc, c](FjtServer::GoalHandle gh) {
            for (auto it = c->goals.begin(); it != c->goals.end(); ++it)
              if (it->second == gh) {
                tc->cancel(it->first, now());
                control_msgs::FollowJointTrajectoryResult r;
                gh.setCanceled(r);
                c->goals.erase(it);
                return;
              }
          },
          false);
      c->action->start();
    } else if (auto* cc = dynamic_cast<car_sim::control::CommandController*>(ctl)) {
      if (type.find("JointGroup") != std::string::npos) {
        c->sub = nh.subscribe<std_msgs::Float64MultiArray>(
            cns + "/command", 1, [cc, name](const std_msgs::Float64MultiArray::ConstPtr& m) {
              std::string why;
              if (!cc->set_command(m->data, &why)) ROS_ERROR("car: controller '%s': %s", name.c_str(), why.c_str());
            });
      } else {
        c->sub = nh.subscribe<std_msgs::Float64>(cns + "/command", 1, [cc, name](const std_msgs::Float64::ConstPtr& m) {
          std::string why;
          if (!cc->set_command({m->data}, &why)) ROS_ERROR("car: controller '%s': %s", name.c_str(), why.c_str());
        });
      }
      if (type.rfind("effort_controllers/JointPositionController", 0) == 0 ||
          type.rfind("effort_controllers/JointVelocityController", 0) == 0)
        c->pub = nh.advertise<control_msgs::JointControllerState>(cns + "/state", 1);
    }
  }

  static car_sim::control::TrajGoal to_goal(const trajectory_msgs::JointTrajectory& m) {
    car_sim::control::TrajGoal g;
    g.joint_names = m.joint_names;
    g.start_time = m.header.stamp.toSec();
    for (const auto& p : m.points) {
      car_sim::control::TrajPoint q;
      q.positions = p.positions;
      q.velocities = p.velocities;
      q.accelerations = p.accelerations;
      q.time_from_start = p.time_from_start.toSec();
      g.points.push_back(q);
    }
    return g;
  }

  bool running(const std::string& name) const {
    for (const auto& l : rc_->loaded())
      if (l.name == name) return l.running;
    return false;
  }

  void on_goal(const std::string& name, car_sim::control::TrajectoryController* tc, CtlRos* c,
               FjtServer::GoalHandle gh) {
    control_msgs::FollowJointTrajectoryResult r;
    if (!running(name)) {
      r.error_code = control_msgs::FollowJointTrajectoryResult::INVALID_GOAL;
      r.error_string = "controller '" + name + "' is not running";
      gh.setRejected(r, r.error_string);
      return;
    }
    const auto& goal = *gh.getGoal();
    car_sim::control::TrajGoal g = to_goal(goal.trajectory);
    for (const auto& t : goal.path_tolerance) g.path_position[t.name] = t.position;
    for (const auto& t : goal.goal_tolerance) g.goal_position[t.name] = t.position;
    if (!goal.goal_time_tolerance.isZero()) g.goal_time_tolerance = goal.goal_time_tolerance.toSec();
    const uint64_t id = c->next_goal++;
    std::string why;
    int code = 0;
    // an active goal is replaced: it ends as canceled (upstream: preempted)
    if (!tc->set_trajectory(g, id, now(), &why, &code)) {
      r.error_code = code;
      r.error_string = why;
      gh.setRejected(r, why);
      return;
    }
    gh.setAccepted();
    c->goals[id] = gh;
  }

  bool unload(const std::string& name) {
    try {
      rc_->unload(name);
    } catch (const std::exception& e) {
      ROS_ERROR("car: controller_manager: could not unload: %s", e.what());
      return false;
    }
    ros_.erase(name);
    ROS_INFO("car: controller_manager: unloaded '%s'", name.c_str());
    return true;
  }

  bool switch_(const controller_manager_msgs::SwitchController::Request& rq) {
    std::string why;
    const bool strict = rq.strictness == controller_manager_msgs::SwitchController::Request::STRICT;
    if (rq.strictness != 1 && rq.strictness != 2) {
      ROS_ERROR("car: controller_manager: switch_controller: strictness %d is neither BEST_EFFORT (1) nor STRICT (2)",
                rq.strictness);
      return false;
    }
    if (!rc_->switch_controllers(rq.start_controllers, rq.stop_controllers, strict, &why)) {
      ROS_ERROR("car: controller_manager: switch_controller refused: %s", why.c_str());
      return false;
    }
    return true;
  }

  bool reload(bool force_kill) {
    // car's controller types are built in: nothing to reload; upstream refuses while controllers are loaded
    if (!rc_->loaded().empty() && !force_kill) {
      ROS_ERROR("car: controller_manager: reload_controller_libraries: controllers are loaded (force_kill false)");
      return false;
    }
    std::vector<std::string> names;
    for (const auto& l : rc_->loaded()) names.push_back(l.name);
    std::string why;
    rc_->switch_controllers({}, names, false, &why);
    for (const auto& n : names) unload(n);
    return true;
  }

  void list(controller_manager_msgs::ListControllers::Response* rs) const {
    for (const auto& l : rc_->loaded()) {
      controller_manager_msgs::ControllerState s;
      s.name = l.name;
      s.type = l.type;
      s.state = l.running ? "running" : "stopped";
      for (const auto& [iface, joints] : l.controller->claimed()) {
        controller_manager_msgs::HardwareInterfaceResources h;
        h.hardware_interface = iface;
        h.resources = joints;
        s.claimed_resources.push_back(h);
      }
      rs->controller.push_back(s);
    }
  }

  NodeContext* node_ = nullptr;
  car_sim::RosControl* rc_ = nullptr;
  std::string ns_;
  std::vector<ros::ServiceServer> srv_;
  std::map<std::string, std::unique_ptr<CtlRos>> ros_;
};

}  // namespace

std::unique_ptr<Adapter> make_ros_control_adapter() { return std::make_unique<RosControlAdapter>(); }

}  // namespace car_ros
