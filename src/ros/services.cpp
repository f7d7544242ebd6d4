// The Gazebo-style services under /gazebo: spawn, delete, model state, world properties, reset, pause.
#include <Eigen/Geometry>

#include "conversions.hpp"
#include "node.hpp"

namespace car_ros {

namespace {

bool world_frame(const std::string& f) { return f.empty() || f == "world" || f == "map"; }

}  // namespace

void SimNode::advertise_services() {
  services_.push_back(gz_.advertiseService("spawn_urdf_model", &SimNode::spawn, this));
  services_.push_back(gz_.advertiseService("delete_model", &SimNode::remove, this));
  services_.push_back(gz_.advertiseService("get_model_state", &SimNode::get_state, this));
  services_.push_back(gz_.advertiseService("set_model_state", &SimNode::set_state, this));
  services_.push_back(gz_.advertiseService("get_world_properties", &SimNode::properties, this));
  services_.push_back(gz_.advertiseService("reset_simulation", &SimNode::reset_simulation, this));
  services_.push_back(gz_.advertiseService("reset_world", &SimNode::reset_world, this));
  services_.push_back(gz_.advertiseService("pause_physics", &SimNode::pause, this));
  services_.push_back(gz_.advertiseService("unpause_physics", &SimNode::unpause, this));
}

bool SimNode::spawn(car::SpawnModel::Request& req, car::SpawnModel::Response& res) {
  res.success = false;
  if (!world_frame(req.reference_frame)) {
    res.status_message = "reference_frame '" + req.reference_frame + "' is not supported (use '' or 'world')";
    return true;
  }
  try {
    const car_sim::RobotModel model = car_sim::load_urdf_string(req.model_xml, req.model_name);
    for (const auto& d : model.diagnostics) {
      if (d.severity == car_sim::Severity::Warning)
        ROS_WARN("car: %s: %s: %s", req.model_name.c_str(), d.element.c_str(), d.message.c_str());
      // what the URDF import did to the links, one line each (docs/COMPAT-spawn.md)
      else if (d.code == "link-lumped" || d.code == "world-anchor")
        ROS_INFO("car: %s: %s", req.model_name.c_str(), d.message.c_str());
    }
    world_->spawn(model, req.model_name, from_pose(req.initial_pose), req.robot_namespace);
    for (const auto& d : world_->robot(req.model_name).config.diagnostics)
      if (d.severity == car_sim::Severity::Warning)
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

bool SimNode::remove(car::DeleteModel::Request& req, car::DeleteModel::Response& res) {
  try {
    world_->remove(req.model_name);
  } catch (const std::exception& e) {
    res.success = false;
    res.status_message = std::string("DeleteModel: ") + e.what();
    return true;
  }
  for (auto it = route_.begin(); it != route_.end();) it = it->first.first == req.model_name ? route_.erase(it) : ++it;
  io_.erase(req.model_name);
  ROS_INFO("car: deleted '%s'", req.model_name.c_str());
  res.success = true;
  res.status_message = "DeleteModel: successfully deleted model";
  return true;
}

bool SimNode::get_state(car::GetModelState::Request& req, car::GetModelState::Response& res) {
  res.header.stamp = stamp(world_->tick());
  res.header.frame_id = "world";
  if (!world_frame(req.relative_entity_name)) {
    res.success = false;
    res.status_message = "GetModelState: relative_entity_name '" + req.relative_entity_name + "' is not supported";
    return true;
  }
  try {
    const car_sim::ModelState s = world_->model_state(req.model_name);
    res.pose = to_pose(s.pose);
    res.twist = to_twist(s.linear, s.angular);
  } catch (const std::exception& e) {
    res.success = false;
    res.status_message = std::string("GetModelState: ") + e.what();
    return true;
  }
  res.success = true;
  res.status_message = "GetModelState: got properties";
  return true;
}

bool SimNode::set_state(car::SetModelState::Request& req, car::SetModelState::Response& res) {
  const auto& m = req.model_state;
  if (!world_frame(m.reference_frame)) {
    res.success = false;
    res.status_message = "SetModelState: reference_frame '" + m.reference_frame + "' is not supported";
    return true;
  }
  car_sim::ModelState s;
  s.pose = from_pose(m.pose);
  s.linear = Eigen::Vector3d(m.twist.linear.x, m.twist.linear.y, m.twist.linear.z);
  s.angular = Eigen::Vector3d(m.twist.angular.x, m.twist.angular.y, m.twist.angular.z);
  try {
    world_->set_model_state(m.model_name, s);
  } catch (const std::exception& e) {
    res.success = false;
    res.status_message = std::string("SetModelState: ") + e.what();
    return true;
  }
  res.success = true;
  res.status_message = "SetModelState: set model state done";
  return true;
}

bool SimNode::properties(car::GetWorldProperties::Request&, car::GetWorldProperties::Response& res) {
  res.sim_time = world_->time();
  res.model_names = world_->model_names();
  res.rendering_enabled = false;
  res.success = true;
  res.status_message = "GetWorldProperties: got properties";
  return true;
}

bool SimNode::reset_simulation(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  world_->reset();
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
  paused_ = true;
  return true;
}

bool SimNode::unpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  paused_ = false;
  return true;
}

}  // namespace car_ros
