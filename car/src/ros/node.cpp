// The node's loop: pacing against the wall clock (rtf), /clock, the plug-ins' outputs (their ports), joint
// states and model states, and which lazy plug-ins someone listens to.
#include "node.hpp"

#include <ros/callback_queue.h>
#include <ros/names.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/JointState.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <thread>

#include "conversions.hpp"
#include "params.hpp"

namespace car_ros {

// gz_: gazebo_ros's api plug-in advertises in its node's private namespace; launch files name the node gazebo
SimNode::SimNode() : nh_(), pnh_("~"), gz_("~") {}

// roscpp's ros::start() (init.cpp) reads /use_sim_time and, when it is true, sets the time to 0 and subscribes its
// own clockCallback to /clock on its internal queue's thread, which calls ros::Time::setNow with each /clock heard.
// The node publishes /clock after its steps, so that callback would set the time back, at moments of another
// thread's choosing, to a /clock older than the step running. So ros::start() reads /use_sim_time under a name no one
// sets (a remapping, roscpp's param::param resolves names through it, dropped again at once): no subscriber is made,
// and the node alone sets the time, ros::Time::setNow before each step (rostime's time.cpp: setNow also switches
// ros::Time::now() to the value set).
void start_with_sim_time() {
  auto& remappings = const_cast<ros::M_string&>(ros::names::getRemappings());
  const std::string key = "/use_sim_time";
  const auto had = remappings.find(key);
  const std::optional<std::string> before = had == remappings.end() ? std::nullopt : std::optional(had->second);
  remappings[key] = "/car_sim_node/roscpp_clock_subscriber_off";
  ros::start();
  if (before)
    remappings[key] = *before;
  else
    remappings.erase(key);
  // sim time 0, as roscpp's own start with /use_sim_time
  ros::Time::setNow(ros::Time(0, 0));
}

void SimNode::poll_tf_inputs() {
  for (auto& [robot, plugins] : route_)
    for (auto& [plugin, r] : plugins)
      if (r.polled) r.polled->poll();
}

void SimNode::set_ros_time(uint64_t tick) {
  if (tick == ros_time_tick_) return;
  ros::Time::setNow(stamp(tick));
  ros_time_tick_ = tick;
}

ros::Time SimNode::stamp(uint64_t tick) const { return sim_time(tick, world_->dt()); }

bool SimNode::init() {
  roscpp_.connect();
  std::string world_file;
  pnh_.param<std::string>("world_name", world_file, "");
  const bool rtf_finite = finite_param(pnh_, "rtf", 1.0, rtf_);
  bool start_paused = false;
  pnh_.param("paused", start_paused, false);
  pnh_.param("clock_rate", clock_rate_, 100.0);
  pnh_.param("joint_state_rate", joint_state_rate_, 50.0);
  pnh_.param("model_states_rate", model_states_rate_, 100.0);
  pnh_.param("solver_iterations", solver_iterations_, 10);
  // empty_world.launch's use_clock_frequency / pub_clock_frequency and enable_ros_network (gazebo_ros's names)
  pnh_.param("pub_clock_frequency", clock_rate_, clock_rate_);
  bool ros_network = true;
  pnh_.param("enable_ros_network", ros_network, true);
  std::string ignored;
  if (pnh_.getParam("ignored_launch_args", ignored) && !ignored.empty())
    ROS_INFO("car: launch arguments without effect in car (headless, Bullet, no recording): %s", ignored.c_str());
  int seed = 0;
  pnh_.param("seed", seed, 0);
  pnh_.param("car_extras", car_extras_, true);
  int iters = 0;
  pnh_.param("iters", iters, 0);
  if (iters < 0) {
    ROS_FATAL("car: parameter ~iters must be >= 0 (gzserver --iters), got %d", iters);
    return false;
  }
  iters_ = iters;
  if (!rtf_finite || rtf_ < 0.0) {
    ROS_FATAL("car: parameter ~rtf must be >= 0 (0 = as fast as possible), got %g", rtf_);
    return false;
  }
  add_exported_model_paths();
  car_sim::WorldOptions options;
  options.solver_iterations = solver_iterations_;
  options.seed = static_cast<uint64_t>(seed);
  try {
    world_file = resolve_world_name(world_file);
    world_ = std::make_unique<car_sim::World>(
        world_file.empty() ? car_sim::empty_world() : car_sim::load_world_file(world_file), options);
  } catch (const car_sim::LoadError& e) {
    ROS_FATAL("car: cannot load the world: %s", e.what());
    return false;
  }
  // the pause flag lives in the world, where Gazebo plug-ins read and set it (World::IsPaused, SetPaused)
  world_->set_paused(start_paused);
  nh_.setParam("/use_sim_time", true);
  set_periods();
  log_world(world_file);
  // world models with plug-ins or sensors are robots from the start: their topics (docs/COMPAT-sdf.md 16)
  for (const auto& name : world_->robot_names()) make_io(name);
  known_robots_ = world_->robot_count();
  // gzserver's -s plug-ins, once the world is there (Gazebo loads them before it: docs/COMPAT-plugins.md)
  load_system_plugins();
  // after the world robots' plug-ins subscribed: the answers' callbacks come after theirs
  watch_published_ = lockstep_.configure(nh_, pnh_);
  clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 10);
  if (ros_network) {
    model_states_pub_ = gz_.advertise<gazebo_msgs::ModelStates>("model_states", 100);
    advertise_services();
    advertise_dropin();
  } else {
    ROS_INFO("car: enable_ros_network is false: only /clock (no %s/* topics or services, as gazebo_ros)",
             gz_.getNamespace().c_str());
  }
  publish_clock();
  return true;
}

void SimNode::run() {
  using clock = std::chrono::steady_clock;
  auto last_paused_clock = clock::now();
  ros::CallbackQueue& callbacks = *ros::getGlobalCallbackQueue();
  while (ros::ok()) {
    // callbacks (commands, service calls) only when some are queued; before them, every message of the steps
    // so far is sent, so an answer or a command sees the same order as with synchronous publishing
    if (!callbacks.isEmpty()) {
      publisher_.flush();
      ros::spinOnce();
    }
    // a reset_simulation took the time back: so goes roscpp's
    set_ros_time(world_->tick());
    if (world_->paused()) {
      repace_ = true;
      // models a plug-in inserted come in while paused too, as Gazebo's World::Step processes its messages
      run_deferred();
      // time paused does not count against the lockstep guard
      if (watch_published_) lockstep_.resume(clock::now());
      // keep /clock alive while paused, at 10 Hz of wall time
      auto now = clock::now();
      if (now - last_paused_clock > std::chrono::milliseconds(100)) {
        publish_clock();
        last_paused_clock = now;
      }
      // the callback queue is looked at every millisecond: callbacks that arrive together (a latched cmd_vel,
      // then unpause_physics on another connection) run together, in the order roscpp queued them. (Sleeping on
      // the queue instead ran unpause_physics the moment it came, at times before the command: the car of
      // rostest drive started late.)
      publisher_.wake();
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      continue;
    }
    if (watch_published_) {
      if (lockstep_.waiting(clock::now())) {
        // the trigger's answer (and any other callback) is run the moment it is queued; before it, everything
        // published so far has been sent, as for spinOnce above
        publisher_.flush();
        callbacks.callAvailable(ros::WallDuration(0.001));
        lockstep_waited_ = true;
        continue;
      }
      // the wait is not made up by pacing afterwards
      if (lockstep_waited_) repace_ = true;
      lockstep_waited_ = false;
    }
    if (repace_) {
      // (re)start pacing at the start, after a pause, a reset or a new real-time factor
      pacer_.restart(clock::now(), world_->tick());
      repace_ = false;
    }
    // inputs read from TF (hand_of_god's desired frame) before every step, as upstream looks them up in each
    // WorldUpdateBegin: a plug-in that sends nothing until it has its target would otherwise never be read (they were
    // polled after their plug-in's own output)
    poll_tf_inputs();
    // the step's plug-in callbacks see the sim time of the step they run in, as World::SimTime() says
    // (WorldUpdateBegin counts the coming step): ros::Time::now() in a Gazebo plug-in is that time
    set_ros_time(world_->tick() + 1);
    try {
      world_->step(1);
    } catch (const car_sim::SimulationError& e) {
      // a body blew up: stop rather than publish NaN (the guard in the core names the body)
      ROS_ERROR("car: %s; physics paused (call reset_simulation or delete_model, then unpause_physics)", e.what());
      world_->set_paused(true);
      continue;
    }
    // models a Gazebo plug-in inserted in the step get their topics
    if (world_->robot_count() != known_robots_) take_new_robots();
    // the steps' messages wake the publishing thread at most once a millisecond of wall time, and before any
    // sleep (docs/COMPAT-dropins.md "Publishing thread")
    publisher_.hold();
    publish_outputs();
    // real-time factor: looked at every 100 steps (a clock read), published once a wall second
    if (world_->tick() % 100 == 0) publish_performance();
    publisher_.release(std::chrono::milliseconds(1));
    if (lockstep_.fired()) {
      // a trigger went out to someone: hand it to the transport, then wait for the answer before the next step
      publisher_.flush();
      lockstep_.begin(clock::now(), stamp(world_->tick()).toSec());
    }
    if (pause_at_tick_ > 0 && world_->tick() >= pause_at_tick_) {
      // ~pause_at reached: paused after exactly this step, and its time sent at once
      pause_at_tick_ = 0;
      world_->set_paused(true);
      publish_clock();
      publisher_.flush();
      continue;
    }
    if (iters_ > 0 && --iters_ == 0) {
      // gzserver --iters N: N steps, then the server exits
      ROS_INFO("car: --iters reached at %.3f s of sim time: shutting down", stamp(world_->tick()).toSec());
      publisher_.flush();
      ros::shutdown();
      break;
    }
    if (rtf_ > 0.0) {
      // a stall of more than 10 ms of wall time is not made up in a burst (docs/COMPAT-dropins.md "Pacing")
      const auto now = clock::now();
      const auto due = pacer_.due(world_->tick(), world_->dt(), rtf_, now);
      if (due > now) {
        publisher_.wake();
        std::this_thread::sleep_until(due);
      }
    }
  }
}

void SimNode::set_periods() {
  clock_period_ = period_of(clock_rate_);
  joint_state_period_ = period_of(joint_state_rate_);
  model_states_period_ = period_of(model_states_rate_);
}

uint64_t SimNode::period_of(double rate) const {
  if (!(rate > 0.0)) return 1;
  return std::max<uint64_t>(1, std::llround(1.0 / (rate * world_->dt())));
}

void SimNode::log_world(const std::string& file) {
  const auto& d = world_->description();
  int statics = 0;
  for (const auto& m : d.models) statics += m.is_static ? 1 : 0;
  ROS_INFO("car: world '%s' from %s: %zu models (%d static), step %g s, gravity (%g %g %g) m/s^2", d.name.c_str(),
           file.empty() ? "the built-in empty world" : file.c_str(), d.models.size(), statics, d.step_size,
           d.gravity.x(), d.gravity.y(), d.gravity.z());
  for (const auto& m : d.models)
    ROS_INFO("car:   model %-16s %s at (%.3f %.3f %.3f)", m.name.c_str(), m.is_static ? "static " : "dynamic",
             m.pose.translation().x(), m.pose.translation().y(), m.pose.translation().z());
  for (const auto& diag : d.diagnostics) ROS_WARN("car: %s: %s", diag.element.c_str(), diag.message.c_str());
  // the world's own plug-ins: what loaded, and what did not (docs/COMPAT-plugins.md "World and system plug-ins")
  log_world_plugins(0);
  for (const auto& p : d.plugins)
    if (std::none_of(world_->world_diagnostics().begin(), world_->world_diagnostics().end(),
                     [&](const car_sim::Diagnostic& x) { return x.element == "world/plugin[" + p.name + "]"; }))
      ROS_INFO("car: world plug-in '%s' (%s) runs from its library through car's Gazebo API", p.name.c_str(),
               p.filename.c_str());
  // the world's robots' own warnings (a shape left out, a visual mesh missing, ...)
  for (const auto& r : world_->robot_names())
    for (const auto& diag : world_->robot(r).model.diagnostics)
      if (diag.severity == car_sim::Severity::Warning)
        ROS_WARN("car: %s: %s: %s", r.c_str(), diag.element.c_str(), diag.message.c_str());
  ROS_INFO("car: %s, real-time factor %s, solver %d iterations", world_->paused() ? "paused" : "running",
           rtf_ > 0 ? std::to_string(rtf_).c_str() : "0 (as fast as possible)", solver_iterations_);
}

void SimNode::publish_clock() {
  rosgraph_msgs::Clock c;
  c.clock = stamp(world_->tick());
  publish(clock_pub_, std::move(c));
}

void SimNode::publish_outputs() {
  const uint64_t tick = world_->tick();
  const ros::Time now = stamp(tick);
  if (tick % clock_period_ == 0) publish_clock();
  for (auto& o : world_->take_outputs()) {
    const auto robot = route_.find(o->robot);
    if (robot == route_.end()) continue;
    const auto it = robot->second.find(o->plugin);
    if (it == robot->second.end()) continue;
    it->second.outputs->publish(std::move(o), *this);
  }
  if (tick % joint_state_period_ == 0) {
    for (auto& [name, io] : io_) {
      if (io.joint_states.getNumSubscribers() == 0) continue;
      sensor_msgs::JointState js;
      js.header.stamp = now;
      std::vector<car_sim::JointState> joints = world_->joint_states(name);
      js.name.reserve(joints.size());
      js.position.reserve(joints.size());
      js.velocity.reserve(joints.size());
      for (auto& j : joints) {
        js.name.push_back(std::move(j.name));
        js.position.push_back(j.position);
        js.velocity.push_back(j.velocity);
      }
      publish(io.joint_states, std::move(js));
    }
  }
  if (tick % model_states_period_ != 0) return;
  if (model_states_pub_.getNumSubscribers() > 0) {
    // the names moved in as the world lists them; poses and twists written in place
    gazebo_msgs::ModelStates ms;
    ms.name = world_->model_names();
    ms.pose.resize(ms.name.size());
    ms.twist.resize(ms.name.size());
    for (size_t i = 0; i < ms.name.size(); ++i) {
      const car_sim::ModelState s = world_->model_state(ms.name[i]);
      ms.pose[i] = to_pose(s.pose);
      ms.twist[i] = to_twist(s.linear, s.angular);
    }
    publish(model_states_pub_, std::move(ms));
  }
  if (link_states_pub_.getNumSubscribers() > 0) publish_link_states();
}

void SimNode::update_activity() {
  for (auto& [name, io] : io_)
    for (auto& p : io.plugins) {
      if (!p.info.lazy || !p.outputs) continue;
      const bool want = p.outputs->listened();
      if (want != p.active) {
        world_->set_plugin_active(name, p.info.config.name, want);
        p.active = want;
      }
      // only the parts someone takes are made (a depth camera's depth image without its colour and cloud)
      const uint32_t parts = p.outputs->parts();
      if (parts != p.parts) {
        world_->plugin(name, p.info.config.name)->set_parts(parts);
        p.parts = parts;
      }
    }
}

void SimNode::make_io(const std::string& name) {
  const car_sim::RobotInfo& info = world_->robot(name);
  RobotIO io;
  // car-only (docs/COMPAT-dropins.md): ground truth and every joint's state, unless ~car_extras is false
  if (car_extras_) {
    // ground truth of the root link in the world frame, as gazebo_ros users get from a p3d plug-in
    car_sim::PluginSpec truth;
    truth.name = "car_ground_truth";
    truth.filename = "libgazebo_ros_p3d.so";
    truth.params = {{"bodyName", info.model.root_link},
                    {"topicName", "/gazebo/ground_truth/" + name},
                    {"frameName", "world"},
                    {"updateRate", std::to_string(model_states_rate_)}};
    world_->attach_plugin(name, truth);
    io.joint_states = nh_.advertise<sensor_msgs::JointState>(car_sim::resolve_topic(car_sim::strip_frame(info.robot_namespace), "joint_states"), 10);
  }
  for (const auto& p : world_->plugins()) {
    if (p.robot != name) continue;
    PluginIO pio;
    pio.info = p;
    if (p.inputs.empty() && p.outputs.empty() && p.services.empty()) {
      // a plug-in from a shared library (it reads its own keys: docs/PLUGINS.md) does its own ROS, if any
      if (p.kind && p.kind->any_keys)
        ROS_INFO("car: %s: plug-in '%s' (%s) runs from its library through car's Gazebo API", name.c_str(),
                 p.config.name.c_str(), p.config.filename.c_str());
      else
        ROS_WARN("car: %s: plug-in '%s' (%s) is simulated but has no ports; nothing is published for it",
                 name.c_str(), p.config.name.c_str(), p.config.filename.c_str());
      io.plugins.push_back(std::move(pio));
      continue;
    }
    // the output ports: one converter per sample type (outputs.cpp)
    pio.outputs = std::make_unique<OutputPorts>();
    std::string offers = pio.outputs->setup(p, info, *this);
    // the input ports: one subscriber factory per sample type (inputs.cpp)
    pio.inputs = std::make_unique<InputPorts>();
    const std::string inputs = pio.inputs->setup(p, *this);
    if (!inputs.empty()) offers += (offers.empty() ? "input " : ", input ") + inputs;
    // the calls: one service factory per call type (calls.cpp)
    pio.services = std::make_unique<ServicePorts>();
    const std::string plugin = p.config.name;
    const std::string services =
        pio.services->setup(p, *this, [this, name, plugin] { ports_changed(name, plugin); });
    if (!services.empty()) offers += (offers.empty() ? "" : ", ") + services;
    if (!p.summary.empty()) offers += (offers.empty() ? "" : ", ") + p.summary;
    route_[name][p.config.name] = {pio.outputs.get(), pio.inputs->polled() ? pio.inputs.get() : nullptr};
    if (!p.config.sensor.empty())
      ROS_INFO("car: %s: sensor '%s' (%s, %s) on %s at %g Hz: %s", name.c_str(), p.config.sensor.c_str(),
               p.config.sensor_type.c_str(), p.config.filename.c_str(), p.link.c_str(), p.rate, offers.c_str());
    else if (!offers.empty())
      ROS_INFO("car: %s: %s '%s' (%s): %s", name.c_str(), p.config.kind.c_str(), p.config.name.c_str(),
               p.config.filename.c_str(), offers.c_str());
    io.plugins.push_back(std::move(pio));
  }
  io_[name] = std::move(io);
  // a port that only sends a transform is listened to from the start
  update_activity();
  // the new plug-ins subscribed after lockstep's answers: subscribe those again, to come last
  lockstep_.resubscribe();
}

void SimNode::ports_changed(const std::string& robot, const std::string& plugin) {
  for (auto& pio : io_[robot].plugins) {
    if (pio.info.config.name != plugin) continue;
    pio.info = world_->plugin_info(robot, plugin);
    const std::string offers = pio.outputs->setup(pio.info, world_->robot(robot), *this);
    const std::string inputs = pio.inputs->setup(pio.info, *this);
    route_[robot][plugin].polled = pio.inputs->polled() ? pio.inputs.get() : nullptr;
    ROS_DEBUG("car: %s: %s '%s' now offers %s; input %s", robot.c_str(), pio.info.config.kind.c_str(), plugin.c_str(),
              offers.c_str(), inputs.c_str());
  }
  update_activity();
  lockstep_.resubscribe();
}

}  // namespace car_ros

namespace car_ros {

bool SimNode::run_deferred() {
  world_->run_deferred();
  if (world_->robot_count() == known_robots_) return false;
  take_new_robots();
  return true;
}

void SimNode::take_new_robots() {
  known_robots_ = world_->robot_count();
  for (const auto& name : world_->robot_names()) {
    if (io_.count(name)) continue;
    // a model a Gazebo plug-in inserted (World::InsertModel*, ~/factory): its plug-ins' messages and its topics
    const auto& info = world_->robot(name);
    for (const auto& d : info.config.diagnostics)
      if (d.severity != car_sim::Severity::Info)
        ROS_WARN("car: %s: %s: %s", name.c_str(), d.element.c_str(), d.message.c_str());
    make_io(name);
    const Eigen::Vector3d p = info.spawn_pose.translation();
    ROS_INFO("car: inserted '%s' by a plug-in (%zu links, %zu joints, %zu plug-ins) at (%.3f %.3f %.3f)", name.c_str(),
             info.model.links.size(), info.model.joints.size(), info.config.plugins.size(), p.x(), p.y(), p.z());
  }
}

void SimNode::log_world_plugins(size_t from) {
  const auto& diags = world_->world_diagnostics();
  for (size_t k = from; k < diags.size(); ++k) {
    const auto& d = diags[k];
    if (d.severity == car_sim::Severity::Error)
      ROS_ERROR("car: %s: %s", d.element.c_str(), d.message.c_str());
    else if (d.severity == car_sim::Severity::Warning)
      ROS_WARN("car: %s: %s", d.element.c_str(), d.message.c_str());
    else
      ROS_INFO("car: %s: %s", d.element.c_str(), d.message.c_str());
  }
}

// gzserver's -s FILE (docs/COMPAT-plugins.md "World and system plug-ins"): ~system_plugins (file names) and
// ~server_argv (the command line they are loaded with), both lists, set by car's gzserver.
void SimNode::load_system_plugins() {
  std::vector<std::string> files, argv;
  pnh_.getParam("system_plugins", files);
  pnh_.getParam("server_argv", argv);
  if (argv.empty()) argv.push_back("gzserver");
  for (const auto& f : files) {
    const size_t before = world_->world_diagnostics().size();
    const auto found = world_->load_system_plugin(f, argv);
    log_world_plugins(before);
    if (found.empty()) ROS_INFO("car: system plug-in %s runs from its library through car's Gazebo API", f.c_str());
  }
}

}  // namespace car_ros
