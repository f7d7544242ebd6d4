// The Gazebo-style services under /gazebo: spawn, delete, model and link state, properties, wrenches and efforts,
// physics properties, reset, pause (gazebo_msgs types; the behaviour is written down in docs/COMPAT.md).
#include <Eigen/Geometry>

#include <cmath>

#include "conversions.hpp"
#include "node.hpp"

namespace car_ros {

namespace {

bool world_frame(const std::string& f) { return f.empty() || f == "world" || f == "map" || f == "/map"; }

// A check of the core's (car_sim::check_state...) run before the service's own look-ups: its refusal becomes the
// answer "SERVICE: reason"; true when refused.
template <class Check>
bool refused(const char* service, std::string& status_message, Check&& check) {
  try {
    check();
    return false;
  } catch (const std::invalid_argument& e) {
    status_message = std::string(service) + ": " + e.what();
    return true;
  }
}

Eigen::Vector3d vec(const geometry_msgs::Vector3& v) { return Eigen::Vector3d(v.x, v.y, v.z); }
Eigen::Vector3d vec(const geometry_msgs::Point& v) { return Eigen::Vector3d(v.x, v.y, v.z); }

// A state given in a frame (pose, twist in the frame's axes) -> world frame, as gazebo_ros's set_model_state:
// the pose composed onto the frame's pose, the velocities rotated by the frame's orientation.
car_sim::ModelState in_world(const car_sim::ModelState& f, const car_sim::ModelState& s) {
  car_sim::ModelState w;
  w.pose = f.pose * s.pose;
  w.linear = f.pose.linear() * s.linear;
  w.angular = f.pose.linear() * s.angular;
  return w;
}

// A world-frame state -> relative to a frame, as gazebo_ros's get_model_state and get_link_state.
car_sim::ModelState relative(const car_sim::ModelState& f, const car_sim::ModelState& s) {
  car_sim::ModelState r;
  r.pose = f.pose.inverse() * s.pose;
  r.linear = f.pose.linear().transpose() * (s.linear - f.linear);
  r.angular = f.pose.linear().transpose() * (s.angular - f.angular);
  return r;
}

car_sim::ModelState state_of(const geometry_msgs::Pose& p, const geometry_msgs::Twist& t) {
  car_sim::ModelState s;
  s.pose = from_pose(p);
  s.linear = vec(t.linear);
  s.angular = vec(t.angular);
  return s;
}

}  // namespace

void SimNode::advertise_services() {
  services_.push_back(gz_.advertiseService("spawn_urdf_model", &SimNode::spawn, this));
  // gazebo_ros: spawn_urdf_model and spawn_sdf_model share one handler that takes either format (docs/COMPAT-sdf.md)
  services_.push_back(gz_.advertiseService("spawn_sdf_model", &SimNode::spawn, this));
  services_.push_back(gz_.advertiseService("delete_model", &SimNode::remove, this));
  services_.push_back(gz_.advertiseService("get_model_state", &SimNode::get_state, this));
  services_.push_back(gz_.advertiseService("set_model_state", &SimNode::set_state, this));
  services_.push_back(gz_.advertiseService("get_world_properties", &SimNode::properties, this));
  services_.push_back(gz_.advertiseService("reset_simulation", &SimNode::reset_simulation, this));
  services_.push_back(gz_.advertiseService("reset_world", &SimNode::reset_world, this));
  services_.push_back(gz_.advertiseService("pause_physics", &SimNode::pause, this));
  services_.push_back(gz_.advertiseService("unpause_physics", &SimNode::unpause, this));
  services_.push_back(gz_.advertiseService("get_link_state", &SimNode::get_link_state, this));
  services_.push_back(gz_.advertiseService("set_link_state", &SimNode::set_link_state, this));
  services_.push_back(gz_.advertiseService("get_link_properties", &SimNode::link_properties, this));
  services_.push_back(gz_.advertiseService("get_model_properties", &SimNode::model_properties, this));
  services_.push_back(gz_.advertiseService("get_joint_properties", &SimNode::joint_properties, this));
  services_.push_back(gz_.advertiseService("set_model_configuration", &SimNode::set_configuration, this));
  services_.push_back(gz_.advertiseService("apply_body_wrench", &SimNode::apply_wrench, this));
  services_.push_back(gz_.advertiseService("apply_joint_effort", &SimNode::apply_effort, this));
  services_.push_back(gz_.advertiseService("clear_body_wrenches", &SimNode::clear_wrenches, this));
  services_.push_back(gz_.advertiseService("clear_joint_forces", &SimNode::clear_efforts, this));
  services_.push_back(gz_.advertiseService("get_physics_properties", &SimNode::get_physics, this));
  services_.push_back(gz_.advertiseService("set_physics_properties", &SimNode::set_physics, this));
  link_states_pub_ = gz_.advertise<gazebo_msgs::LinkStates>("link_states", 100);
  // the topics act as the services do; a refused request goes to the log
  set_model_state_sub_ = gz_.subscribe<gazebo_msgs::ModelState>(
      "set_model_state", 10, [this](const gazebo_msgs::ModelState::ConstPtr& m) {
        gazebo_msgs::SetModelState::Request req;
        gazebo_msgs::SetModelState::Response res;
        req.model_state = *m;
        set_state(req, res);
        if (!res.success) ROS_ERROR("car: /gazebo/set_model_state: %s", res.status_message.c_str());
      });
  set_link_state_sub_ = gz_.subscribe<gazebo_msgs::LinkState>(
      "set_link_state", 10, [this](const gazebo_msgs::LinkState::ConstPtr& m) {
        gazebo_msgs::SetLinkState::Request req;
        gazebo_msgs::SetLinkState::Response res;
        req.link_state = *m;
        set_link_state(req, res);
        if (!res.success) ROS_ERROR("car: /gazebo/set_link_state: %s", res.status_message.c_str());
      });
}

std::optional<car_sim::ModelState> SimNode::entity_state(const std::string& name, bool* world) const {
  *world = world_frame(name);
  if (*world) return std::nullopt;
  if (world_->has_model(name)) return world_->model_state(name);
  try {
    return world_->link_state(world_->find_link(name));
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

bool SimNode::spawn(gazebo_msgs::SpawnModel::Request& req, gazebo_msgs::SpawnModel::Response& res) {
  res.success = false;
  if (!world_frame(req.reference_frame)) {
    res.status_message = "reference_frame '" + req.reference_frame + "' is not supported (use '' or 'world')";
    return true;
  }
  try {
    // <sdf> documents (spawn_model -sdf / -database) and URDF alike, as gazebo_ros's spawnSDFModel
    const bool is_sdf = car_sim::is_sdf_document(req.model_xml);
    const car_sim::SdfRobot sdf_robot =
        is_sdf ? car_sim::load_sdf_model_string(req.model_xml, req.model_name) : car_sim::SdfRobot();
    const car_sim::RobotModel model =
        is_sdf ? sdf_robot.model : car_sim::load_urdf_string(req.model_xml, req.model_name);
    for (const auto& d : model.diagnostics) {
      if (d.severity == car_sim::Severity::Warning)
        ROS_WARN("car: %s: %s: %s", req.model_name.c_str(), d.element.c_str(), d.message.c_str());
      // what the URDF import did to the links, one line each (docs/COMPAT-spawn.md)
      else if (d.code == "link-lumped" || d.code == "world-anchor")
        ROS_INFO("car: %s: %s", req.model_name.c_str(), d.message.c_str());
    }
    if (is_sdf)
      world_->spawn_sdf(sdf_robot, req.model_name, from_pose(req.initial_pose), req.robot_namespace);
    else
      world_->spawn(model, req.model_name, from_pose(req.initial_pose), req.robot_namespace);
    for (const auto& d : world_->robot(req.model_name).config.diagnostics)
      if (d.severity == car_sim::Severity::Warning)
        ROS_WARN("car: %s: %s: %s", req.model_name.c_str(), d.element.c_str(), d.message.c_str());
    // what the spawn's mesh loading found (a visual's mesh missing: docs/COMPAT-spawn.md)
    for (const auto& d : world_->robot(req.model_name).model.diagnostics)
      if (d.code == "visual-mesh-missing")
        ROS_WARN("car: %s: %s: %s", req.model_name.c_str(), d.element.c_str(), d.message.c_str());
    make_io(req.model_name);
  } catch (const std::exception& e) {
    if (world_->has_model(req.model_name) && !io_.count(req.model_name)) world_->remove(req.model_name);
    res.status_message = std::string("SpawnModel: failure - ") + e.what();
    ROS_ERROR("car: %s", res.status_message.c_str());
    return true;
  }
  const auto& info = world_->robot(req.model_name);
  const Eigen::Vector3d p = info.spawn_pose.translation();
  ROS_INFO("car: spawned '%s' (%zu links, %zu joints, %zu plug-ins) at (%.3f %.3f %.3f)", req.model_name.c_str(),
           info.model.links.size(), info.model.joints.size(), info.config.plugins.size(), p.x(), p.y(), p.z());
  res.success = true;
  res.status_message = "SpawnModel: Successfully spawned entity";
  return true;
}

bool SimNode::remove(gazebo_msgs::DeleteModel::Request& req, gazebo_msgs::DeleteModel::Response& res) {
  try {
    world_->remove(req.model_name);
  } catch (const std::exception& e) {
    res.success = false;
    res.status_message = std::string("DeleteModel: ") + e.what();
    return true;
  }
  route_.erase(req.model_name);
  io_.erase(req.model_name);
  ROS_INFO("car: deleted '%s'", req.model_name.c_str());
  res.success = true;
  res.status_message = "DeleteModel: successfully deleted model";
  return true;
}

bool SimNode::get_state(gazebo_msgs::GetModelState::Request& req, gazebo_msgs::GetModelState::Response& res) {
  res.header.stamp = stamp(world_->tick());
  res.header.frame_id = req.relative_entity_name;
  res.success = false;
  if (!world_->has_model(req.model_name)) {
    res.status_message = "GetModelState: model [" + req.model_name + "] does not exist";
    return true;
  }
  bool world = false;
  const auto frame = entity_state(req.relative_entity_name, &world);
  if (!world && !frame) {
    res.status_message = "GetModelState: reference relative_entity_name [" + req.relative_entity_name +
                         "] not found, did you forget to scope the body by model name?";
    return true;
  }
  car_sim::ModelState s = world_->model_state(req.model_name);
  if (frame) s = relative(*frame, s);
  res.pose = to_pose(s.pose);
  res.twist = to_twist(s.linear, s.angular);
  res.success = true;
  res.status_message = "GetModelState: got properties";
  return true;
}

bool SimNode::set_state(gazebo_msgs::SetModelState::Request& req, gazebo_msgs::SetModelState::Response& res) {
  const auto& m = req.model_state;
  res.success = false;
  if (!world_->has_model(m.model_name)) {
    res.status_message = "SetModelState: model [" + m.model_name + "] does not exist";
    return true;
  }
  // the conversion keeps a non-finite number non-finite (normalising a quaternion with NaN or inf gives NaN)
  car_sim::ModelState s = state_of(m.pose, m.twist);
  if (refused("SetModelState", res.status_message, [&] { car_sim::check_state(s); })) return true;
  bool world = false;
  const auto frame = entity_state(m.reference_frame, &world);
  if (!world && !frame) {
    res.status_message = "SetModelState: specified reference frame entity [" + m.reference_frame + "] does not exist";
    return true;
  }
  if (frame) s = in_world(*frame, s);
  try {
    world_->set_model_state(m.model_name, s);
  } catch (const std::exception& e) {
    res.status_message = std::string("SetModelState: ") + e.what();
    return true;
  }
  res.success = true;
  res.status_message = "SetModelState: set model state done";
  return true;
}

bool SimNode::properties(gazebo_msgs::GetWorldProperties::Request&, gazebo_msgs::GetWorldProperties::Response& res) {
  res.sim_time = world_->time();
  res.model_names = world_->model_names();
  res.rendering_enabled = false;
  res.success = true;
  res.status_message = "GetWorldProperties: got properties";
  return true;
}

bool SimNode::reset_simulation(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  world_->reset();
  // the schedule restarts from now at tick 0
  repace_ = true;
  // no step waits for an answer to a trigger of the run before, and no pause is due
  lockstep_.reset();
  pause_at_tick_ = 0;
  ROS_INFO("car: simulation reset: time 0, every model where it started");
  publish_clock();
  return true;
}

bool SimNode::reset_world(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  world_->reset_poses();
  ROS_INFO("car: world reset: every model where it started");
  return true;
}

bool SimNode::pause(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  world_->set_paused(true);
  pause_at_tick_ = 0;
  return true;
}

bool SimNode::unpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  // car extra (docs/COMPAT-dropins.md "Pause at"): ~pause_at [s of sim time], set just before this call, makes the
  // run pause itself at the first step at or after that time. Read once here, then deleted: the parameter server
  // answers before the service call is made, so the order is certain, unlike a topic beside the call.
  double at = 0.0;
  if (pnh_.getParam("pause_at", at)) {
    pnh_.deleteParam("pause_at");
    const double now = stamp(world_->tick()).toSec();
    if (const auto steps = car_sim::steps_until(now, at, world_->dt())) {
      pause_at_tick_ = world_->tick() + *steps;
    } else {
      ROS_WARN("car: ~pause_at %g is not after the sim time %.3f s: ignored", at, now);
    }
  }
  world_->set_paused(false);
  return true;
}

// ---- gazebo_ros API ------------------------------------------------------------------------------------------

bool SimNode::get_link_state(gazebo_msgs::GetLinkState::Request& req, gazebo_msgs::GetLinkState::Response& res) {
  res.success = false;
  car_sim::LinkRef link;
  try {
    link = world_->find_link(req.link_name);
  } catch (const std::invalid_argument& e) {
    res.status_message = std::string("GetLinkState: link not found (") + e.what() +
                         "), did you forget to scope the link by model name?";
    return true;
  }
  bool world = false;
  const auto frame = entity_state(req.reference_frame, &world);
  if (!world && !frame) {
    res.status_message = "GetLinkState: reference frame [" + req.reference_frame +
                         "] not found, did you forget to scope the link by model name?";
    return true;
  }
  car_sim::ModelState s = world_->link_state(link);
  if (frame) s = relative(*frame, s);
  res.link_state.link_name = req.link_name;
  res.link_state.pose = to_pose(s.pose);
  res.link_state.twist = to_twist(s.linear, s.angular);
  res.link_state.reference_frame = req.reference_frame;
  res.success = true;
  res.status_message = "GetLinkState: got state";
  return true;
}

bool SimNode::set_link_state(gazebo_msgs::SetLinkState::Request& req, gazebo_msgs::SetLinkState::Response& res) {
  const auto& m = req.link_state;
  res.success = false;
  car_sim::LinkRef link;
  try {
    link = world_->find_link(m.link_name);
  } catch (const std::invalid_argument& e) {
    res.status_message = std::string("SetLinkState: link does not exist (") + e.what() + ")";
    return true;
  }
  car_sim::ModelState s = state_of(m.pose, m.twist);
  if (refused("SetLinkState", res.status_message, [&] { car_sim::check_state(s); })) return true;
  bool world = false;
  const auto frame = entity_state(m.reference_frame, &world);
  if (!world && !frame) {
    res.status_message = "SetLinkState: reference frame [" + m.reference_frame + "] is not a valid entity name";
    return true;
  }
  if (frame) s = in_world(*frame, s);
  try {
    world_->set_link_state(link, s);
  } catch (const std::exception& e) {
    res.status_message = std::string("SetLinkState: ") + e.what();
    return true;
  }
  res.success = true;
  res.status_message = "SetLinkState: success";
  return true;
}

bool SimNode::link_properties(gazebo_msgs::GetLinkProperties::Request& req,
                              gazebo_msgs::GetLinkProperties::Response& res) {
  res.success = false;
  car_sim::LinkProperties p;
  try {
    p = world_->link_properties(world_->find_link(req.link_name));
  } catch (const std::invalid_argument& e) {
    res.status_message = std::string("GetLinkProperties: link not found (") + e.what() +
                         "), did you forget to scope the link by model name?";
    return true;
  }
  res.com.position.x = p.com.x();
  res.com.position.y = p.com.y();
  res.com.position.z = p.com.z();
  res.com.orientation.w = 1.0;  // the inertia below is in the link frame's axes
  res.gravity_mode = p.gravity;
  res.mass = p.mass;
  res.ixx = p.inertia(0, 0);
  res.ixy = p.inertia(0, 1);
  res.ixz = p.inertia(0, 2);
  res.iyy = p.inertia(1, 1);
  res.iyz = p.inertia(1, 2);
  res.izz = p.inertia(2, 2);
  res.success = true;
  res.status_message = "GetLinkProperties: got properties";
  return true;
}

bool SimNode::model_properties(gazebo_msgs::GetModelProperties::Request& req,
                               gazebo_msgs::GetModelProperties::Response& res) {
  if (!world_->has_model(req.model_name)) {
    res.success = false;
    res.status_message = "GetModelProperties: model [" + req.model_name + "] does not exist";
    return true;
  }
  const car_sim::ModelProperties p = world_->model_properties(req.model_name);
  res.body_names = p.bodies;
  res.geom_names = p.geoms;
  res.joint_names = p.joints;
  res.is_static = p.is_static;
  res.success = true;
  res.status_message = "GetModelProperties: got properties";
  return true;
}

bool SimNode::joint_properties(gazebo_msgs::GetJointProperties::Request& req,
                               gazebo_msgs::GetJointProperties::Response& res) {
  car_sim::JointProperties p;
  try {
    p = world_->joint_properties(req.joint_name);
  } catch (const std::invalid_argument& e) {
    res.success = false;
    res.status_message = std::string("GetJointProperties: joint not found (") + e.what() + ")";
    return true;
  }
  using R = gazebo_msgs::GetJointProperties::Response;
  res.type = p.type == car_sim::JointType::Prismatic   ? R::PRISMATIC
             : p.type == car_sim::JointType::Continuous ? R::CONTINUOUS
             : p.type == car_sim::JointType::Fixed      ? R::FIXED
                                                        : R::REVOLUTE;
  res.damping = {p.damping};
  res.position = {p.position};
  res.rate = {p.velocity};
  res.success = true;
  res.status_message = "GetJointProperties: got properties";
  return true;
}

bool SimNode::set_configuration(gazebo_msgs::SetModelConfiguration::Request& req,
                                gazebo_msgs::SetModelConfiguration::Response& res) {
  res.success = false;
  if (!world_->has_model(req.model_name)) {
    res.status_message = "SetModelConfiguration: model [" + req.model_name + "] does not exist";
    return true;
  }
  try {
    world_->set_joint_positions(req.model_name, req.joint_names, req.joint_positions);
  } catch (const std::invalid_argument& e) {
    res.status_message = std::string("SetModelConfiguration: ") + e.what();
    return true;
  }
  res.success = true;
  res.status_message = "SetModelConfiguration: success";
  return true;
}

bool SimNode::apply_wrench(gazebo_msgs::ApplyBodyWrench::Request& req, gazebo_msgs::ApplyBodyWrench::Response& res) {
  res.success = false;
  car_sim::LinkRef link;
  try {
    link = world_->find_link(req.body_name);
  } catch (const std::invalid_argument& e) {
    res.status_message = std::string("ApplyBodyWrench: body does not exist (") + e.what() + ")";
    return true;
  }
  const Eigen::Vector3d f = vec(req.wrench.force), t = vec(req.wrench.torque), p = vec(req.reference_point);
  if (!f.allFinite() || !t.allFinite() || !p.allFinite()) {
    res.status_message = "ApplyBodyWrench: wrench and reference_point must be finite numbers";
    return true;
  }
  bool world = false;
  const auto frame = entity_state(req.reference_frame, &world);
  if (!world && !frame) {
    res.status_message = "ApplyBodyWrench: reference_frame [" + req.reference_frame + "] not found";
    return true;
  }
  // world frame (gazebo_ros): the force at the body's com, torque + reference_point x force.
  // A named frame: force and torque in its axes, acting at reference_point in it (docs/COMPAT.md, fix).
  Eigen::Vector3d force = f, torque = t + p.cross(f);
  if (frame) {
    const Eigen::Matrix3d R = frame->pose.linear();
    force = R * f;
    torque = R * t + (frame->pose * p - world_->body_com(link)).cross(force);
  }
  try {
    world_->apply_wrench(link, force, torque, req.start_time.toSec(), req.duration.toSec());
  } catch (const std::invalid_argument& e) {
    res.status_message = std::string("ApplyBodyWrench: ") + e.what();
    return true;
  }
  // accepted, as upstream, where a static link has no body to push (ODELink::AddForce)
  if (!link.robot && world_->description().find_model(link.model)->is_static)
    ROS_WARN("car: ApplyBodyWrench: model [%s] is static: the wrench on [%s] moves nothing", link.model.c_str(),
             req.body_name.c_str());
  res.success = true;
  res.status_message = "";
  return true;
}

bool SimNode::apply_effort(gazebo_msgs::ApplyJointEffort::Request& req,
                           gazebo_msgs::ApplyJointEffort::Response& res) {
  res.success = false;
  if (refused("ApplyJointEffort", res.status_message, [&] { car_sim::check_effort(req.effort); })) return true;
  try {
    world_->apply_joint_effort(req.joint_name, req.effort, req.start_time.toSec(), req.duration.toSec());
  } catch (const std::invalid_argument& e) {
    res.status_message = std::string("ApplyJointEffort: joint not found (") + e.what() + ")";
    return true;
  }
  res.success = true;
  res.status_message = "ApplyJointEffort: effort set";
  return true;
}

bool SimNode::clear_wrenches(gazebo_msgs::BodyRequest::Request& req, gazebo_msgs::BodyRequest::Response&) {
  const int n = world_->clear_wrenches(req.body_name);
  ROS_INFO("car: cleared %d wrench(es) on '%s'", n, req.body_name.c_str());
  return true;
}

bool SimNode::clear_efforts(gazebo_msgs::JointRequest::Request& req, gazebo_msgs::JointRequest::Response&) {
  const int n = world_->clear_joint_efforts(req.joint_name);
  ROS_INFO("car: cleared %d effort(s) on '%s'", n, req.joint_name.c_str());
  return true;
}

bool SimNode::get_physics(gazebo_msgs::GetPhysicsProperties::Request&,
                          gazebo_msgs::GetPhysicsProperties::Response& res) {
  res.time_step = world_->dt();
  res.pause = world_->paused();
  // Gazebo's real_time_update_rate [Hz]: rtf = rate * step; 0 = as fast as possible
  res.max_update_rate = rtf_ / world_->dt();
  const Eigen::Vector3d g = world_->gravity();
  res.gravity.x = g.x();
  res.gravity.y = g.y();
  res.gravity.z = g.z();
  // Bullet's sequential impulses stand where ODE's projected Gauss-Seidel would; the rest has no equivalent (0)
  res.ode_config.sor_pgs_iters = static_cast<uint32_t>(world_->solver_iterations());
  res.ode_config.sor_pgs_w = 1.0;
  res.success = true;
  res.status_message = "GetPhysicsProperties: got properties";
  return true;
}

bool SimNode::set_physics(gazebo_msgs::SetPhysicsProperties::Request& req,
                          gazebo_msgs::SetPhysicsProperties::Response& res) {
  res.success = false;
  const Eigen::Vector3d g = vec(req.gravity);
  if (refused("SetPhysicsProperties", res.status_message,
              [&] { car_sim::check_physics_properties(g, req.time_step, req.max_update_rate); }))
    return true;
  if (std::abs(req.time_step - world_->dt()) > 1e-12) {
    res.status_message = "SetPhysicsProperties: time_step " + std::to_string(req.time_step) +
                         " s: car keeps the world file's step (" + std::to_string(world_->dt()) +
                         " s) while running; set <max_step_size> in the world";
    return true;
  }
  // only a change reaches the physics: setting gravity wakes every rigid body, and car.testing's waits call this
  // service to change the pace alone (the same gravity back), at ticks that depend on the wall clock
  if (g != world_->gravity()) world_->set_gravity(g);
  if (req.ode_config.sor_pgs_iters > 0 && static_cast<int>(req.ode_config.sor_pgs_iters) != world_->solver_iterations())
    world_->set_solver_iterations(static_cast<int>(req.ode_config.sor_pgs_iters));
  rtf_ = req.max_update_rate * world_->dt();
  repace_ = true;
  ROS_INFO("car: physics updated: gravity (%g %g %g) m/s^2, real-time factor %g, solver %d iterations", g.x(), g.y(),
           g.z(), rtf_, world_->solver_iterations());
  res.success = true;
  res.status_message = "physics engine updated";
  return true;
}

void SimNode::publish_link_states() {
  // every body of every model by its scoped name, world frame
  gazebo_msgs::LinkStates ls;
  for (const auto& model : world_->model_names())
    for (const auto& body : world_->model_properties(model).bodies) {
      const car_sim::ModelState s = world_->link_state({model, body, false});
      ls.name.push_back(model + "::" + body);
      ls.pose.push_back(to_pose(s.pose));
      ls.twist.push_back(to_twist(s.linear, s.angular));
    }
  publish(link_states_pub_, std::move(ls));
}

}  // namespace car_ros
