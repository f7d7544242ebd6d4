// The rest of gazebo_ros's API surface (docs/COMPAT-dropins.md): the light and property-setting services car
// cannot honour (they exist with upstream's types and refuse, saying why), /gazebo/performance_metrics, and the
// physics parameters through dynamic_reconfigure (Physics.cfg), wired as gazebo_ros's api plug-in does: the first
// configuration comes from get_physics_properties, a change goes through set_physics_properties.
#include <car/PhysicsConfig.h>
#include <dynamic_reconfigure/server.h>
#include <gazebo_msgs/DeleteLight.h>
#include <gazebo_msgs/GetLightProperties.h>
#include <gazebo_msgs/PerformanceMetrics.h>
#include <gazebo_msgs/SetJointProperties.h>
#include <gazebo_msgs/SetLightProperties.h>
#include <gazebo_msgs/SetLinkProperties.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "node.hpp"

namespace car_ros {

namespace {

// One refusing handler per service type: success false and the reason, the world untouched.
template <class Srv>
void refuse(ros::NodeHandle& nh, std::vector<ros::ServiceServer>& out, const std::string& name,
            const std::string& prefix, const std::string& why) {
  out.push_back(nh.advertiseService<typename Srv::Request, typename Srv::Response>(
      name, [prefix, why](typename Srv::Request&, typename Srv::Response& res) {
        res.success = false;
        res.status_message = prefix + ": " + why;
        return true;
      }));
}

}  // namespace

std::string resolve_world_name(const std::string& name) {
  namespace fs = std::filesystem;
  if (name.empty()) return name;
  if (fs::path(name).is_absolute() || fs::exists(name)) return name;
  // Gazebo's rule: each GAZEBO_RESOURCE_PATH entry (colon-separated) + "/" + name
  std::string searched = "the current folder";
  if (const char* env = std::getenv("GAZEBO_RESOURCE_PATH")) {
    std::stringstream ss(env);
    std::string dir;
    while (std::getline(ss, dir, ':')) {
      if (dir.empty()) continue;
      searched += ", " + dir;
      if (fs::exists(fs::path(dir) / name)) return (fs::path(dir) / name).string();
    }
  } else {
    searched += " (GAZEBO_RESOURCE_PATH is not set)";
  }
  // Gazebo's own empty world: car's built-in one (sun and ground plane)
  if (name == "worlds/empty.world") return "";
  throw car_sim::LoadError(name, 0, "world",
                           "world file not found (searched: " + searched +
                               "); car ships only worlds/empty.world: give a path or extend GAZEBO_RESOURCE_PATH");
}

void SimNode::advertise_dropin() {
  const std::string no_lights = "car has no lights (headless, nothing is rendered with them)";
  refuse<gazebo_msgs::DeleteLight>(gz_, services_, "delete_light", "DeleteLight", no_lights);
  refuse<gazebo_msgs::GetLightProperties>(gz_, services_, "get_light_properties", "getLightProperties", no_lights);
  refuse<gazebo_msgs::SetLightProperties>(gz_, services_, "set_light_properties", "setLightProperties", no_lights);
  refuse<gazebo_msgs::SetLinkProperties>(gz_, services_, "set_link_properties", "SetLinkProperties",
                                         "car cannot change a body's mass, inertia or gravity while running; set "
                                         "them in the model and spawn it again");
  refuse<gazebo_msgs::SetJointProperties>(gz_, services_, "set_joint_properties", "SetJointProperties",
                                          "car cannot change a joint's ODE properties while running; set <limit> "
                                          "and <dynamics> in the model and spawn it again");
  performance_pub_ = gz_.advertise<gazebo_msgs::PerformanceMetrics>("performance_metrics", 10);

  // dynamic_reconfigure on this node's namespace: ~set_parameters, ~parameter_descriptions, ~parameter_updates
  auto server = std::make_shared<dynamic_reconfigure::Server<car::PhysicsConfig>>(gz_);
  server->setCallback([this](car::PhysicsConfig& c, uint32_t) {
    gazebo_msgs::GetPhysicsProperties::Request greq;
    gazebo_msgs::GetPhysicsProperties::Response now;
    get_physics(greq, now);
    if (!reconfigure_ready_) {
      // the first configuration is the world's
      c.time_step = now.time_step;
      c.max_update_rate = now.max_update_rate;
      c.gravity_x = now.gravity.x;
      c.gravity_y = now.gravity.y;
      c.gravity_z = now.gravity.z;
      c.auto_disable_bodies = now.ode_config.auto_disable_bodies;
      c.sor_pgs_precon_iters = static_cast<int>(now.ode_config.sor_pgs_precon_iters);
      c.sor_pgs_iters = static_cast<int>(now.ode_config.sor_pgs_iters);
      c.sor_pgs_w = now.ode_config.sor_pgs_w;
      c.sor_pgs_rms_error_tol = now.ode_config.sor_pgs_rms_error_tol;
      c.cfm = now.ode_config.cfm;
      c.erp = now.ode_config.erp;
      c.contact_surface_layer = now.ode_config.contact_surface_layer;
      c.contact_max_correcting_vel = now.ode_config.contact_max_correcting_vel;
      c.max_contacts = static_cast<int>(now.ode_config.max_contacts);
      reconfigure_ready_ = true;
      return;
    }
    gazebo_msgs::SetPhysicsProperties::Request req;
    gazebo_msgs::SetPhysicsProperties::Response res;
    req.time_step = c.time_step;
    req.max_update_rate = c.max_update_rate;
    req.gravity.x = c.gravity_x;
    req.gravity.y = c.gravity_y;
    req.gravity.z = c.gravity_z;
    req.ode_config = now.ode_config;
    req.ode_config.auto_disable_bodies = c.auto_disable_bodies;
    req.ode_config.sor_pgs_precon_iters = static_cast<uint32_t>(c.sor_pgs_precon_iters);
    req.ode_config.sor_pgs_iters = static_cast<uint32_t>(c.sor_pgs_iters);
    req.ode_config.sor_pgs_w = c.sor_pgs_w;
    req.ode_config.sor_pgs_rms_error_tol = c.sor_pgs_rms_error_tol;
    req.ode_config.cfm = c.cfm;
    req.ode_config.erp = c.erp;
    req.ode_config.contact_surface_layer = c.contact_surface_layer;
    req.ode_config.contact_max_correcting_vel = c.contact_max_correcting_vel;
    req.ode_config.max_contacts = static_cast<uint32_t>(c.max_contacts);
    const bool changed = req.time_step != now.time_step || req.max_update_rate != now.max_update_rate ||
                         req.gravity.x != now.gravity.x || req.gravity.y != now.gravity.y ||
                         req.gravity.z != now.gravity.z ||
                         req.ode_config.sor_pgs_iters != now.ode_config.sor_pgs_iters;
    if (!changed) return;
    set_physics(req, res);
    if (!res.success) {
      ROS_ERROR("car: dynamic_reconfigure: %s", res.status_message.c_str());
      // report the world's values back, not the refused ones
      c.time_step = now.time_step;
      c.max_update_rate = now.max_update_rate;
      c.gravity_x = now.gravity.x;
      c.gravity_y = now.gravity.y;
      c.gravity_z = now.gravity.z;
      c.sor_pgs_iters = static_cast<int>(now.ode_config.sor_pgs_iters);
    }
  });
  reconfigure_ = server;
}

void SimNode::publish_performance() {
  // real-time factor over the last second of wall time [sim s / wall s], while someone listens
  const auto wall = std::chrono::steady_clock::now();
  const uint64_t tick = world_->tick();
  if (perf_tick_ > tick) perf_tick_ = tick;  // a reset went back in time
  const double elapsed = std::chrono::duration<double>(wall - perf_wall_).count();
  if (elapsed < 1.0) return;
  if (performance_pub_ && performance_pub_.getNumSubscribers() > 0) {
    gazebo_msgs::PerformanceMetrics m;
    m.header.stamp = stamp(tick);
    m.real_time_factor = static_cast<double>(tick - perf_tick_) * world_->dt() / elapsed;
    publish(performance_pub_, std::move(m));
  }
  perf_wall_ = wall;
  perf_tick_ = tick;
}

}  // namespace car_ros
