// The calls half of the ROS bridge: controller_manager_msgs requests -> car_sim::CallRequest, by call type; and a
// plug-in's parameters from the parameter server, read once (CallType::SetParameters).
#include "calls.hpp"

#include <controller_manager_msgs/ListControllerTypes.h>
#include <controller_manager_msgs/ListControllers.h>
#include <controller_manager_msgs/LoadController.h>
#include <controller_manager_msgs/ReloadControllerLibraries.h>
#include <controller_manager_msgs/SwitchController.h>
#include <controller_manager_msgs/UnloadController.h>

#include <cstdio>
#include <memory>

namespace car_ros {

namespace {

namespace cm = controller_manager_msgs;

// The parameter server's value under a controller's namespace, flattened: "pid/p" -> {"100"}, "joints" -> list.
void flatten(const XmlRpc::XmlRpcValue& v, const std::string& key, car_sim::CallParams* out) {
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

// One service of one plug-in instance: its names, and the call into the world.
struct Service {
  std::string robot, plugin;
  car_sim::ServicePort port;
  NodeContext* node = nullptr;
  ServicePorts::PortsChanged changed;

  // Calls the world, logs what it says, reads the ports again when they changed.
  car_sim::CallResponse call(const car_sim::CallRequest& rq) const {
    car_sim::CallResponse r = node->world().call(robot, plugin, port.name, rq);
    for (const auto& e : r.errors) ROS_ERROR("car: %s", e.c_str());
    for (const auto& w : r.warnings) ROS_WARN("car: %s", w.c_str());
    for (const auto& i : r.infos) ROS_INFO("car: %s", i.c_str());
    if (r.ports_changed && changed) changed();
    return r;
  }
};

// A service with a typed callback (generic lambdas are ambiguous for advertiseService's overloads).
template <class S, class F>
ros::ServiceServer serve(ros::NodeHandle& nh, const std::string& name, F f) {
  using Rq = typename S::Request;
  using Rs = typename S::Response;
  return nh.advertiseService<Rq, Rs>(name, boost::function<bool(Rq&, Rs&)>([f](Rq& rq, Rs& rs) { return f(rq, rs); }));
}

ros::ServiceServer advertise(const std::shared_ptr<Service>& s) {
  ros::NodeHandle& nh = s->node->nh();
  const std::string& name = s->port.topic;
  using T = car_sim::CallType;
  switch (s->port.type) {
    case T::LoadController:
      return serve<cm::LoadController>(nh, name, [s](auto& rq, auto& rs) {
        // the controller's parameters at <ns>/<name>/, as controller_manager reads them
        const std::string pns = s->port.ns + "/" + rq.name;
        XmlRpc::XmlRpcValue v;
        if (!ros::param::get(pns, v)) {
          ROS_ERROR("car: controller_manager: could not load controller '%s': no parameters at %s (load the YAML "
                    "first)", rq.name.c_str(), pns.c_str());
          rs.ok = false;
          return true;
        }
        car_sim::CallRequest c;
        c.name = rq.name;
        flatten(v, "", &c.params);
        rs.ok = s->call(c).ok;
        return true;
      });
    case T::UnloadController:
      return serve<cm::UnloadController>(nh, name, [s](auto& rq, auto& rs) {
        car_sim::CallRequest c;
        c.name = rq.name;
        rs.ok = s->call(c).ok;
        return true;
      });
    case T::SwitchController:
      return serve<cm::SwitchController>(nh, name, [s](auto& rq, auto& rs) {
        car_sim::CallRequest c;
        c.start = rq.start_controllers;
        c.stop = rq.stop_controllers;
        c.strictness = rq.strictness;
        rs.ok = s->call(c).ok;
        return true;
      });
    case T::ListControllers:
      return serve<cm::ListControllers>(nh, name, [s](auto&, auto& rs) {
        for (const auto& l : s->call({}).controllers) {
          cm::ControllerState st;
          st.name = l.name;
          st.type = l.type;
          st.state = l.state;
          for (const auto& [iface, joints] : l.claimed) {
            cm::HardwareInterfaceResources h;
            h.hardware_interface = iface;
            h.resources = joints;
            st.claimed_resources.push_back(h);
          }
          rs.controller.push_back(st);
        }
        return true;
      });
    case T::ListControllerTypes:
      return serve<cm::ListControllerTypes>(nh, name, [s](auto&, auto& rs) {
        for (const auto& [type, base] : s->call({}).types) {
          rs.types.push_back(type);
          rs.base_classes.push_back(base);
        }
        return true;
      });
    case T::ReloadControllerLibraries:
      return serve<cm::ReloadControllerLibraries>(nh, name, [s](auto& rq, auto& rs) {
        car_sim::CallRequest c;
        c.force_kill = rq.force_kill;
        rs.ok = s->call(c).ok;
        return true;
      });
    case T::SetParameters: {
      // no service: one call now with what the parameter server holds under ns, as a plug-in's Load reads it
      XmlRpc::XmlRpcValue v;
      if (ros::param::get(s->port.ns, v)) {
        car_sim::CallRequest c;
        flatten(v, "", &c.params);
        s->call(c);
      }
      return {};
    }
  }
  return {};
}

}  // namespace

std::string ServicePorts::setup(const car_sim::PluginInfo& plugin, NodeContext& node, PortsChanged changed) {
  std::string where;
  for (const car_sim::ServicePort& sp : plugin.services) {
    auto s = std::make_shared<Service>();
    s->robot = plugin.robot;
    s->plugin = plugin.config.name;
    s->port = sp;
    s->node = &node;
    s->changed = changed;
    servers_.push_back(advertise(s));
    if (sp.topic.empty()) continue;  // a call made once (SetParameters), no service
    const std::string ns = sp.topic.substr(0, sp.topic.rfind('/'));
    if (where.find(ns) == std::string::npos) where += (where.empty() ? "" : ", ") + ns;
  }
  return where.empty() ? "" : "services under " + where;
}

}  // namespace car_ros
