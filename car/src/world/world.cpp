// The world: the const description, the physics, and the robots' plug-in instances on their schedules. A step
// runs every plug-in's pre_physics, one physics step, then every plug-in's track and, when due, post_physics.
// No kind is named here: kinds come from the registry, commands reach them through their input ports.
#include "car_sim/world.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <map>
#include <stdexcept>

#include "bodies.hpp"
#include "car_sim/mesh.hpp"
#include "car_sim/parallel.hpp"
#include "car_sim/shared_plugin.hpp"
#include "guard.hpp"
#include "physics.hpp"
#include "services.hpp"
#include "velocity_motor.hpp"

namespace car_sim {

namespace {

// The folder of a model's source file, where its relative mesh URIs start ("" for text).
std::string source_dir(const std::string& source) {
  const auto slash = source.rfind('/');
  return slash == std::string::npos ? "" : source.substr(0, slash);
}

// One plug-in instance of a robot.
struct Instance {
  PluginInfo info;
  std::unique_ptr<Plugin> plugin;
  Schedule schedule;
  bool active = false;  // someone listens (lazy kinds compute only then)
  OutputQueue queue;
  size_t static_inputs = 0, static_outputs = 0;  // the kind's own ports, before the instance's dynamic ones
};

}  // namespace

struct World::Impl : WorldAccess {
  // A spawned robot: what it is, its bodies in the physics, its plug-ins. The plug-ins' handle to it.
  struct RobotRt : RobotHandle {
    RobotInfo info;
    physics::Robot* body = nullptr;
    std::set<std::string> driven;                      // joints a plug-in drives
    std::vector<std::pair<int, double>> motor_claims;  // (joint, max effort) of each motor, in id order
    std::vector<Instance> plugins;

    const std::string& name() const override { return info.name; }
    const RobotModel& model() const override { return info.model; }
    const Eigen::Isometry3d& spawn_pose() const override { return info.spawn_pose; }
    int joint(const std::string& n) const override { return body->joint(n); }
    double joint_position(int j) const override { return body->joint_position(j); }
    double joint_velocity(int j) const override { return body->joint_velocity(j); }
    int add_motor(int j, double max_effort) override {
      motor_claims.emplace_back(j, max_effort);
      return body->add_motor(j, max_effort);
    }
    void set_motor(int motor, const MotorTarget& t) override { body->set_motor(motor, t); }
    void add_joint_effort(int j, double effort) override { physics::add_joint_effort(*body, j, effort); }
    Eigen::Isometry3d link_pose(const std::string& l) const override { return body->link_pose(l); }
    ModelState link_state(const std::string& l) const override { return body->link_state(l); }
    // the model frame (Gazebo's Model::WorldPose, what its drives read), with the root link's twist
    ModelState root_state() const override {
      ModelState s = body->root_state();
      s.pose = s.pose * info.model.root_in_model.inverse();
      return s;
    }

    // ---- motion and contact (issue 11) ----
    std::map<std::string, Wrench> applied;  // what apply_wrench added per link this step; cleared before each step

    void apply_wrench(const std::string& l, const Wrench& w, const Eigen::Vector3d& point, bool in_link_frame) override {
      Wrench world = w;
      Eigen::Vector3d at = point;
      if (in_link_frame) {
        const Eigen::Isometry3d T = body->link_pose(l);
        world.force = T.linear() * w.force;
        world.torque = T.linear() * w.torque;
        at = T * point;
      }
      body->apply_wrench(l, world.force, world.torque, at);
      // [N], [N m] about the body's centre of mass, world frame
      Wrench& sum = applied[l];
      sum.force += world.force;
      sum.torque += world.torque + (at - body->body_com(l)).cross(world.force);
    }
    Wrench applied_wrench(const std::string& l) const override {
      if (!body->has_link(l)) throw std::invalid_argument("robot '" + info.name + "' has no link '" + l + "'");
      const auto it = applied.find(l);
      return it == applied.end() ? Wrench() : it->second;
    }
    void set_root_velocity(const Eigen::Vector3d& linear, const Eigen::Vector3d& angular) override {
      body->set_root_velocity(linear, angular);
    }
    void set_joint_position(int j, double position) override { body->set_joint_position(j, position); }
    bool* physics_on = nullptr;  // the world's switch
    bool physics_enabled() const override { return *physics_on; }
    void set_physics_enabled(bool on) override { *physics_on = on; }
    std::vector<int> wrench_claims;  // joints with a reaction sensor, re-made after a rebuild
    void enable_joint_wrench(int j) override {
      body->enable_joint_wrench(j);
      wrench_claims.push_back(j);
    }
    Wrench joint_wrench(int j) const override { return body->joint_wrench(j); }
    std::vector<LinkContact> link_contacts(const std::string& l) const override { return body->link_contacts(l); }

    // ---- users' own plug-ins: ODE's joint motors (World::set_joint_motor) and links without gravity. The settings
    // are state kept over a rebuild; the motors are remade from them with the bodies.
    std::map<int, JointMotor> joint_motors;                           // multibody joint index -> setting
    std::map<int, std::unique_ptr<physics::VelocityMotor>> velocity_motors;  // its motor in the physics
    std::set<std::string> weightless;                                 // links with gravity off
  };

  Impl(const WorldDescription& d, const WorldOptions& o) : desc(d), options(o) {
    env.gravity = d.gravity;
    env.sun_direction = d.sun_direction;
    env.ambient = d.ambient;
    env.background = d.background;
  }

  physics::Options physics_options() const {
    physics::Options p;
    p.solver_iterations = options.solver_iterations;
    p.residual_threshold = options.residual_threshold;
    p.dt = desc.step_size;
    return p;
  }

  const Environment& environment() const override { return env; }
  const RayScene& rays() const override { return phys->rays(); }
  std::vector<Contact> contacts() const override { return phys->contacts(desc.step_size); }

  RobotRt* find(const std::string& name) const {
    for (const auto& r : robots)
      if (r->info.name == name) return r.get();
    return nullptr;
  }

  RobotRt& robot(const std::string& name) const {
    RobotRt* r = find(name);
    if (!r) throw std::invalid_argument("no robot named '" + name + "'");
    return *r;
  }

  Instance* instance(const std::string& robot, const std::string& plugin) const {
    RobotRt* r = find(robot);
    if (!r) return nullptr;
    for (auto& i : r->plugins)
      if (i.info.config.name == plugin) return &i;
    return nullptr;
  }

  // The same, for the API calls that name one: throws std::invalid_argument when there is none.
  Instance& known_instance(const std::string& robot, const std::string& plugin) const {
    Instance* i = instance(robot, plugin);
    if (!i) throw std::invalid_argument("robot '" + robot + "' has no plug-in '" + plugin + "'");
    return *i;
  }

  // A plug-in instance for a resolved configuration, not yet configured.
  Instance make_instance(const RobotRt& r, const PluginConfig& c) const {
    const PluginKind* kind = find_plugin_kind(c.kind);
    Instance i;
    i.plugin = kind->make(c, r.info.name, options.seed);
    i.info.robot = r.info.name;
    i.info.config = c;
    i.info.kind = kind;
    i.info.link = c.link;
    i.info.rate = i.plugin->update_rate();
    i.info.lazy = kind->lazy;
    if (kind->inputs) i.info.inputs = kind->inputs(c, r.info.name);
    if (kind->outputs) i.info.outputs = kind->outputs(c, r.info.name, env);
    if (kind->services) i.info.services = kind->services(c, r.info.name);
    i.static_inputs = i.info.inputs.size();
    i.static_outputs = i.info.outputs.size();
    return i;
  }

  void configure(RobotRt& r, Instance& i, uint64_t tick) {
    i.plugin->configure(r);
    i.info.summary = i.plugin->summary();
    i.schedule = i.plugin->schedule(desc.step_size, tick);
    i.plugin->start_clock(tick);
  }

  // A fresh physics from the description; robots rebuilt where they were spawned, their motors re-made in id
  // order, every plug-in reset; time_went_back (reset_simulation): every schedule restarts from `tick`, else
  // (reset_world) only those of the plug-ins that say so.
  void rebuild(const std::set<std::string>& removed, uint64_t tick, bool time_went_back) {
    for (auto& r : robots) {
      r->velocity_motors.clear();
      r->body = nullptr;
    }
    phys.reset();
    phys = std::make_unique<physics::Physics>(desc, physics_options(), removed);
    apply_settings();
    for (auto& r : robots) {
      r->body = &phys->add_robot(r->info.model, r->info.name, r->info.spawn_pose, r->driven);
      for (const auto& [joint, effort] : r->motor_claims) r->body->add_motor(joint, effort);
      for (int j : r->wrench_claims) r->body->enable_joint_wrench(j);
      for (const auto& [j, m] : r->joint_motors) make_velocity_motor(*r, j, m);
      for (auto& i : r->plugins) {
        i.plugin->reset();
        i.queue.clear();
        if (time_went_back || i.plugin->restarts_schedule_on_reset_world()) i.schedule.restart(tick);
        if (time_went_back) i.plugin->start_clock(tick);
        if (i.active) i.plugin->set_active(true);
      }
    }
  }

  // gazebo_ros API: wrench and effort jobs on ticks [first, last] (last < 0: until cleared), and the physics
  // settings changed at run time (kept over a reset's rebuild)
  struct WrenchJob {
    LinkRef link;
    Eigen::Vector3d force, torque;
    int64_t first, last;
  };
  struct EffortJob {
    std::string robot, joint;
    double effort;
    int64_t first, last;
  };
  std::vector<WrenchJob> wrenches;
  std::vector<EffortJob> efforts;
  int solver_iterations = -1;  // -1: the options' value

  void apply_jobs(uint64_t tick);
  // ODE's motor on a robot's joint, made on first use (World::set_joint_motor).
  void make_velocity_motor(RobotRt& r, int j, const JointMotor& m) {
    auto& motor = r.velocity_motors[j];
    if (!motor) motor = std::make_unique<physics::VelocityMotor>(*phys, *r.body, j);
    motor->set(m.velocity, m.max_effort, desc.step_size);
  }
  // Gravity taken off the links that have it off: a force -m g at each one's centre of mass [N], world frame.
  void cancel_gravity(World& w) {
    for (auto& r : robots)
      for (const auto& l : r->weightless) {
        const LinkProperties p = w.link_properties({r->info.name, l, true});
        r->body->apply_wrench(l, -p.mass * env.gravity, Eigen::Vector3d::Zero(), r->body->link_pose(l) * p.com);
      }
  }
  void apply_settings() {
    physics::set_gravity(*phys, env.gravity);
    if (solver_iterations > 0) physics::set_solver_iterations(*phys, solver_iterations);
  }

  const WorldDescription& desc;
  WorldOptions options;
  Environment env;
  std::unique_ptr<physics::Physics> phys;
  std::vector<std::unique_ptr<RobotRt>> robots;
  // a step's due plug-ins whose post_physics runs on the threads (Plugin::concurrent), and their queues' sizes before
  struct Due {
    RobotRt* robot;
    Instance* instance;
    size_t before;
  };
  std::vector<Due> concurrent_due;
  // users' own plug-ins' per-step hooks (World::add_step_hook), in the order added. Each on the heap: a hook may add
  // or remove hooks while it runs; one removed then is marked and dropped once the hooks have run.
  struct Hook {
    uint64_t id;
    StepPhase phase;
    StepHook fn;
    bool removed = false;
  };
  std::vector<std::unique_ptr<Hook>> hooks;
  uint64_t next_hook = 1;
  bool running_hooks = false, hooks_dirty = false;
  void run_hooks(StepPhase phase, uint64_t tick) {
    running_hooks = true;
    const size_t n = hooks.size();  // one added inside a hook is first called at its phase's next call
    try {
      for (size_t k = 0; k < n; ++k) {
        Hook& h = *hooks[k];
        if (h.phase == phase && !h.removed) h.fn(tick);
      }
    } catch (...) {
      running_hooks = false;
      drop_removed_hooks();
      throw;
    }
    running_hooks = false;
    drop_removed_hooks();
  }
  void drop_removed_hooks() {
    if (!hooks_dirty) return;
    hooks.erase(std::remove_if(hooks.begin(), hooks.end(), [](const std::unique_ptr<Hook>& h) { return h->removed; }),
                hooks.end());
    hooks_dirty = false;
  }
  bool physics_on = true;  // Gazebo's PhysicsEnabled: off, a step advances time only (RobotHandle::set_physics_enabled)
  // Gazebo's pause flag and its pause and stop hooks (same ids as the step hooks), work deferred to between steps,
  // and the plug-ins that belong to the world rather than a robot: the world's <plugin>s and system plug-ins.
  bool paused = false, stopped = false;
  std::vector<std::pair<uint64_t, std::function<void(bool)>>> pause_hooks;
  std::vector<std::pair<uint64_t, std::function<void()>>> stop_hooks;
  std::vector<std::pair<uint64_t, std::function<void()>>> time_reset_hooks;
  // Runs the time-reset hooks (a copy: a hook may add or remove hooks).
  void time_reset() {
    const auto now = time_reset_hooks;
    for (const auto& h : now) h.second();
  }
  std::vector<std::function<void()>> deferred;
  std::vector<std::unique_ptr<SharedPlugin>> world_plugins, system_plugins;
  std::vector<Diagnostic> world_diagnostics;
};

// ---- World ----------------------------------------------------------------------------------------------------

World::World(WorldDescription desc, WorldOptions options) : desc_(std::move(desc)), options_(options) {
  impl_ = std::make_unique<Impl>(desc_, options_);
  impl_->phys = std::make_unique<physics::Physics>(desc_, impl_->physics_options(), removed_);
  // world models with plug-ins, sensors or joints are robots from the start (docs/COMPAT-sdf.md 16)
  for (const auto& r : desc_.robots) spawn_sdf(r.robot, r.name, r.pose);
  // then the world's own plug-ins, with the models there (Gazebo's World::LoadPlugins; docs/COMPAT-plugins.md)
  impl_->world_plugins = load_world_plugins(*this, desc_.plugins, &impl_->world_diagnostics);
}

World::~World() {
  stop();
  // plug-ins first, the world's before the robots' (Gazebo's World::Fini): one from a shared library removes its
  // hooks as it unloads
  impl_->system_plugins.clear();
  impl_->world_plugins.clear();
  impl_->robots.clear();
}

void World::spawn_sdf(const SdfRobot& robot, const std::string& name, const Eigen::Isometry3d& pose,
                      const std::string& robot_namespace) {
  spawn(robot.model, name, pose * robot.root_pose, robot_namespace);
}

void World::spawn(const RobotModel& model, const std::string& name, const Eigen::Isometry3d& pose,
                  const std::string& robot_namespace) {
  if (name.empty()) throw std::invalid_argument("a model needs a name");
  if (has_model(name)) throw std::invalid_argument("model '" + name + "' exists already");
  if (!pose.matrix().allFinite()) throw std::invalid_argument("the pose to spawn '" + name + "' at is not finite");
  auto r = std::make_unique<Impl::RobotRt>();
  r->physics_on = &impl_->physics_on;
  r->info.name = name;
  r->info.robot_namespace = robot_namespace;
  r->info.model = model;
  r->info.spawn_pose = pose;
  // gazebo_ros's spawn: plug-ins without <robotNamespace> get the spawn namespace (docs/COMPAT-spawn.md)
  apply_robot_namespace(&r->info.model, robot_namespace);
  load_meshes(&r->info.model, source_dir(model.source));
  r->info.config = resolve_plugins(r->info.model);
  for (const auto& c : r->info.config.plugins) r->plugins.push_back(impl_->make_instance(*r, c));
  for (const auto& i : r->plugins)
    for (const auto& j : i.plugin->driven_joints()) r->driven.insert(j);
  r->body = &impl_->phys->add_robot(r->info.model, name, pose, r->driven);
  for (auto& i : r->plugins) impl_->configure(*r, i, tick_);
  Impl::RobotRt& in = *r;
  impl_->robots.push_back(std::move(r));
  // plug-ins from shared libraries load on the robot as it is in the world (its Load may look it up)
  for (size_t k = 0; k < in.plugins.size(); ++k) in.plugins[k].plugin->loaded(*this, &in.info.config.diagnostics);
}

void World::attach_plugin(const std::string& robot, const PluginSpec& spec) {
  Impl::RobotRt& r = impl_->robot(robot);
  if (impl_->instance(robot, spec.name))
    throw std::invalid_argument("robot '" + robot + "' has a plug-in named '" + spec.name + "' already");
  PluginConfig c = resolve_plugin(r.info.model, spec, &r.info.config.diagnostics);
  r.info.config.plugins.push_back(c);
  r.plugins.push_back(impl_->make_instance(r, c));
  impl_->configure(r, r.plugins.back(), tick_);
  r.plugins.back().plugin->loaded(*this, &r.info.config.diagnostics);
}

void World::remove(const std::string& name) {
  auto& robots = impl_->robots;
  auto& w = impl_->wrenches;
  w.erase(std::remove_if(w.begin(), w.end(), [&](const Impl::WrenchJob& j) { return j.link.model == name; }), w.end());
  auto& e = impl_->efforts;
  e.erase(std::remove_if(e.begin(), e.end(), [&](const Impl::EffortJob& j) { return j.robot == name; }), e.end());
  for (auto it = robots.begin(); it != robots.end(); ++it) {
    if ((*it)->info.name != name) continue;
    (*it)->velocity_motors.clear();
    impl_->phys->remove_robot(name);
    robots.erase(it);
    return;
  }
  if (!desc_.find_model(name) || removed_.count(name)) throw std::invalid_argument("no model named '" + name + "'");
  // A world model stays out, also after a reset (as in Gazebo); the description itself does not change.
  removed_.insert(name);
  impl_->phys->remove_world_model(name);
  // its nested models go with it, as in Gazebo (docs/COMPAT-sdf.md 16a)
  for (const auto& m : desc_.models)
    if (nested_in(m.name, name) && !removed_.count(m.name)) remove(m.name);
}

void World::step(uint64_t n) {
  const double dt = desc_.step_size;
  StepContext ctx;
  ctx.dt = dt;
  ctx.world = impl_.get();
  // the outputs a plug-in pushed from `before` on: whose they are and when
  auto stamp = [this](const Impl::RobotRt& robot, Instance& i, size_t before) {
    for (size_t k = before; k < i.queue.size(); ++k) {
      i.queue[k]->robot = robot.info.name;
      i.queue[k]->plugin = i.info.config.name;
      i.queue[k]->tick = tick_;
    }
  };
  for (uint64_t s = 0; s < n; ++s) {
    ctx.tick = tick_;
    for (auto& r : impl_->robots) r->applied.clear();
    if (!impl_->hooks.empty()) impl_->run_hooks(StepPhase::BeforePhysics, tick_);
    for (auto& r : impl_->robots)
      for (auto& i : r->plugins) i.plugin->pre_physics(ctx, *r);
    impl_->apply_jobs(tick_);
    impl_->cancel_gravity(*this);
    try {
      if (impl_->physics_on) impl_->phys->step(dt);
    } catch (const physics::NonFiniteState& e) {
      ++tick_;
      throw SimulationError("t = " + std::to_string(time()) + " s: " + e.what() +
                            " is not finite; the world stops here (reset it, or delete the model)");
    }
    ctx.tick = ++tick_;
    if (!impl_->hooks.empty()) impl_->run_hooks(StepPhase::AfterPhysics, tick_);
    auto& later = impl_->concurrent_due;
    later.clear();
    for (auto& r : impl_->robots) {
      for (auto& i : r->plugins) {
        const bool on = !i.info.lazy || i.active;
        if (on) i.plugin->track(ctx, *r);
        if (!i.schedule.due(tick_)) continue;
        i.schedule.advance(tick_);
        if (!on) {
          i.plugin->idle(ctx, *r);
          continue;
        }
        const size_t before = i.queue.size();
        if (i.plugin->concurrent()) {
          later.push_back({r.get(), &i, before});
          continue;
        }
        i.plugin->post_physics(ctx, *r, &i.queue);
        stamp(*r, i, before);
      }
    }
    if (later.empty()) {
      if (!impl_->deferred.empty()) run_deferred();
      continue;
    }
    // the concurrent ones on the threads (one alone on this thread); the ray scene brought up to date first, so
    // that they only read it
    impl_->rays();
    parallel_for(static_cast<int>(later.size()), [&](int k) {
      later[k].instance->plugin->post_physics(ctx, *later[k].robot, &later[k].instance->queue);
    });
    for (const auto& d : later) stamp(*d.robot, *d.instance, d.before);
    if (!impl_->deferred.empty()) run_deferred();
  }
}

void World::reset() {
  // paused for the reset, then as it was (Gazebo's World::Reset: a running world's pause hooks see true, then false)
  const bool was_paused = impl_->paused;
  set_paused(true);
  // time first: the plug-ins' schedules restart from it; wrench and effort jobs end
  tick_ = 0;
  impl_->wrenches.clear();
  impl_->efforts.clear();
  // Gazebo's World::Reset: ResetTime (its timeReset event) before the entities and plug-ins are reset
  impl_->time_reset();
  impl_->rebuild(removed_, tick_, true);
  // the world's plug-ins after the models' (Gazebo's World::Reset); reset_poses leaves them, as reset_world does
  for (auto& p : impl_->world_plugins) p->reset();
  set_paused(was_paused);
}

void World::reset_poses() { impl_->rebuild(removed_, tick_, false); }

void World::reset_time() {
  tick_ = 0;
  for (auto& r : impl_->robots)
    for (auto& i : r->plugins) {
      i.schedule.restart(tick_);
      i.plugin->start_clock(tick_);
    }
  // after the schedules, as Gazebo's sensor manager (connected first) restarts its sensors before the plug-ins
  impl_->time_reset();
}

std::vector<std::string> World::model_names() const {
  std::vector<std::string> out;
  for (const auto& m : desc_.models)
    if (!removed_.count(m.name)) out.push_back(m.name);
  for (const auto& r : impl_->robots) out.push_back(r->info.name);
  return out;
}

bool World::has_model(const std::string& name) const {
  return (desc_.find_model(name) != nullptr && !removed_.count(name)) || impl_->find(name) != nullptr;
}

std::vector<std::string> World::robot_names() const {
  std::vector<std::string> out;
  for (const auto& r : impl_->robots) out.push_back(r->info.name);
  return out;
}

const RobotInfo& World::robot(const std::string& name) const { return impl_->robot(name).info; }

ModelState World::model_state(const std::string& name) const {
  // the model frame, as Gazebo's Model::WorldPose; the twist is the root (canonical) link's, at its origin
  // (Model::WorldLinearVel)
  if (auto* r = impl_->find(name)) return r->root_state();
  if (auto s = impl_->phys->world_model_state(name)) return *s;
  if (has_model(name)) {
    ModelState s;
    s.pose = desc_.find_model(name)->pose;
    return s;
  }
  throw std::invalid_argument("no model named '" + name + "'");
}

void World::set_model_state(const std::string& name, const ModelState& st) {
  check_state(st);
  if (auto* r = impl_->find(name)) {
    // st.pose is the model frame's (Model::SetWorldPose): the root link goes where the frame takes it
    ModelState root = st;
    root.pose = st.pose * r->info.model.root_in_model;
    r->body->set_root_state(root);
  } else if (!impl_->phys->set_world_model_state(name, st)) {
    throw std::invalid_argument("no model named '" + name + "'");
  }
  impl_->phys->invalidate_rays();
}

std::vector<JointState> World::joint_states(const std::string& robot) const {
  const Impl::RobotRt& r = impl_->robot(robot);
  std::vector<JointState> out;
  for (const auto& j : r.info.model.joints) {
    if (j.type == JointType::Fixed) continue;
    const int i = r.body->joint(j.name);
    out.push_back({j.name, r.body->joint_position(i), r.body->joint_velocity(i)});
  }
  return out;
}

Eigen::Isometry3d World::link_pose(const std::string& robot, const std::string& link) const {
  return impl_->robot(robot).body->link_pose(link);
}

std::vector<PluginInfo> World::plugins() const {
  std::vector<PluginInfo> out;
  for (const auto& r : impl_->robots)
    for (const auto& i : r->plugins) out.push_back(i.info);
  return out;
}

std::vector<PluginInfo> World::sensors() const {
  std::vector<PluginInfo> out;
  for (const auto& r : impl_->robots)
    for (const auto& i : r->plugins)
      if (i.info.lazy) out.push_back(i.info);
  return out;
}

void World::set_plugin_active(const std::string& robot, const std::string& plugin, bool active) {
  Instance* i = &impl_->known_instance(robot, plugin);
  if (active && !i->active) i->plugin->set_active(true);
  if (!active && i->active) i->plugin->set_active(false);
  i->active = active;
}

Plugin* World::plugin(const std::string& robot, const std::string& name) {
  Instance* i = impl_->instance(robot, name);
  return i ? i->plugin.get() : nullptr;
}

OutputQueue World::take_outputs() {
  OutputQueue out;
  for (auto& r : impl_->robots)
    for (auto& i : r->plugins) {
      for (auto& o : i.queue) out.push_back(std::move(o));
      i.queue.clear();
    }
  return out;
}

OutputQueue World::take_outputs_if(const std::function<bool(const Output&)>& pick) {
  OutputQueue out;
  for (auto& r : impl_->robots)
    for (auto& i : r->plugins) {
      OutputQueue keep;
      for (auto& o : i.queue) (pick(*o) ? out : keep).push_back(std::move(o));
      i.queue.swap(keep);
    }
  return out;
}

void World::set_cmd_vel(const std::string& robot, double v, double w) {
  Twist t;
  t.linear.x() = v;
  t.angular.z() = w;
  set_cmd_vel(robot, t);
}

void World::set_cmd_vel(const std::string& robot, const Twist& cmd) {
  if (!cmd.linear.allFinite() || !cmd.angular.allFinite()) throw std::invalid_argument("cmd_vel must be finite");
  for (auto& i : impl_->robot(robot).plugins)
    for (const InputPort& p : i.info.inputs)
      if (p.type == InputType::Twist) command(robot, i.info.config.name, p.name, cmd);
}

namespace {

// "linear.x nan, angular.z 0": the named values, for a rejection's reason.
std::string listed(const std::vector<std::pair<const char*, double>>& values) {
  std::string s;
  for (const auto& v : values) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%s%s %g", s.empty() ? "" : ", ", v.first, v.second);
    s += buf;
  }
  return s;
}

// The non-finite numbers of a command, listed; "" when every number is finite. A trajectory's positions are the
// plug-in's to use as they come (upstream sets them as given).
std::string non_finite(const Command& value) {
  if (const auto* t = std::get_if<Twist>(&value)) {
    if (t->linear.allFinite() && t->angular.allFinite()) return "";
    static const char* names[6] = {"linear.x", "linear.y", "linear.z", "angular.x", "angular.y", "angular.z"};
    std::vector<std::pair<const char*, double>> v;
    for (int k = 0; k < 6; ++k) {
      const double x = k < 3 ? t->linear[k] : t->angular[k - 3];
      if (x != 0.0 || !std::isfinite(x)) v.emplace_back(names[k], x);
    }
    return listed(v);
  }
  if (const auto* w = std::get_if<Wrench>(&value)) {
    if (w->force.allFinite() && w->torque.allFinite()) return "";
    return listed({{"force.x", w->force.x()}, {"force.y", w->force.y()}, {"force.z", w->force.z()},
                   {"torque.x", w->torque.x()}, {"torque.y", w->torque.y()}, {"torque.z", w->torque.z()}});
  }
  if (const auto* p = std::get_if<PoseCommand>(&value))
    return p->pose.matrix().allFinite() ? "" : listed({{"x", p->pose.translation().x()}, {"y", p->pose.translation().y()},
                                                       {"z", p->pose.translation().z()}});
  if (const auto* f = std::get_if<Float64>(&value)) return std::isfinite(f->data) ? "" : listed({{"data", f->data}});
  if (const auto* a = std::get_if<Float64Array>(&value)) {
    for (double x : a->data)
      if (!std::isfinite(x)) {
        std::string s = "data [";
        for (size_t k = 0; k < a->data.size(); ++k) {
          char buf[32];
          std::snprintf(buf, sizeof buf, "%s%g", k ? " " : "", a->data[k]);
          s += buf;
        }
        return s + "]";
      }
  }
  return "";
}

}  // namespace

CommandResult World::command(const std::string& robot, const std::string& plugin, const std::string& port,
                             Command value) {
  Instance* i = &impl_->known_instance(robot, plugin);
  const InputPort* p = nullptr;
  for (const InputPort& q : i->info.inputs)
    if (q.name == port) p = &q;
  if (!p) throw std::invalid_argument("plug-in '" + plugin + "' of robot '" + robot + "' has no input '" + port + "'");
  if (value.index() != static_cast<size_t>(p->type))
    throw std::invalid_argument("input '" + port + "' of plug-in '" + plugin + "' takes a " + command_noun(p->type));
  // a Twist port reads only its components: the others are dropped before the check
  if (auto* t = std::get_if<Twist>(&value)) {
    static const uint32_t bits[6] = {kLinearX, kLinearY, kLinearZ, kAngularX, kAngularY, kAngularZ};
    for (int k = 0; k < 6; ++k)
      if (!(p->axes & bits[k])) (k < 3 ? t->linear[k] : t->angular[k - 3]) = 0.0;
  }
  CommandResult result;
  const std::string bad = non_finite(value);
  if (!bad.empty()) {
    result.accepted = false;
    result.reason = "a non-finite value (" + bad + ")";
    return result;
  }
  i->plugin->command(port, value, &result);
  return result;
}

CallResponse World::call(const std::string& robot, const std::string& plugin, const std::string& service,
                          const CallRequest& request) {
  Instance* i = &impl_->known_instance(robot, plugin);
  const ServicePort* s = nullptr;
  for (const ServicePort& q : i->info.services)
    if (q.name == service) s = &q;
  if (!s) throw std::invalid_argument("plug-in '" + plugin + "' of robot '" + robot + "' has no service '" + service + "'");
  CallResponse r = i->plugin->call(service, request);
  if (r.ports_changed) {
    // the kind's own ports, then the instance's current ones
    i->info.inputs.resize(i->static_inputs);
    i->info.outputs.resize(i->static_outputs);
    i->plugin->dynamic_ports(&i->info.inputs, &i->info.outputs);
  }
  return r;
}

const PluginInfo& World::plugin_info(const std::string& robot, const std::string& plugin) const {
  const Instance* i = &impl_->known_instance(robot, plugin);
  return i->info;
}

std::vector<Contact> World::contacts() const { return impl_->contacts(); }

// ---- gazebo_ros API -----------------------------------------------------------------------------------------

namespace {

// Splits Gazebo's scoped name "MODEL::NAME"; model "" when the name is plain.
std::pair<std::string, std::string> scoped(const std::string& name) {
  const auto at = name.rfind("::");
  if (at == std::string::npos) return {"", name};
  return {name.substr(0, at), name.substr(at + 2)};
}

int64_t first_tick(double start, double dt, uint64_t now) {
  const double t = std::ceil(start / dt - 1e-9);
  return std::max<int64_t>(static_cast<int64_t>(now), static_cast<int64_t>(std::max(t, 0.0)));
}

int64_t last_tick(double start, double duration, double dt, uint64_t now) {
  if (duration < 0.0) return -1;
  const double from = std::max(start, static_cast<double>(now) * dt);
  return static_cast<int64_t>(std::floor((from + duration) / dt + 1e-9));
}

}  // namespace

void World::Impl::apply_jobs(uint64_t tick) {
  const int64_t k = static_cast<int64_t>(tick);
  for (auto it = wrenches.begin(); it != wrenches.end();) {
    if (it->last >= 0 && k > it->last) {
      it = wrenches.erase(it);
      continue;
    }
    if (k >= it->first) {
      if (RobotRt* r = find(it->link.model)) {
        physics::add_link_wrench(*r->body, it->link.link, it->force, it->torque);
      } else if (const WorldModelDesc* m = desc.find_model(it->link.model)) {
        for (size_t i = 0; i < m->links.size(); ++i)
          if (m->links[i].name == it->link.link)
            if (btRigidBody* b = phys->world_model_body(m->name, i)) physics::add_body_wrench(*b, it->force, it->torque);
      }
    }
    ++it;
  }
  for (auto it = efforts.begin(); it != efforts.end();) {
    if (it->last >= 0 && k > it->last) {
      it = efforts.erase(it);
      continue;
    }
    if (k >= it->first)
      if (RobotRt* r = find(it->robot)) physics::add_joint_effort(*r->body, r->body->joint(it->joint), it->effort);
    ++it;
  }
}

LinkRef World::find_link(const std::string& name) const {
  const auto [model, link] = scoped(name);
  for (const auto& m : model_names()) {
    // the link's scoped name "MODEL::LINK", or its name, which may hold "::" itself (an included model's
    // "N::link", docs/COMPAT-sdf.md 16a), as Gazebo 11's Model::GetLink takes either
    const std::string own = name.rfind(m + "::", 0) == 0 ? name.substr(m.size() + 2) : "";
    if (const auto* r = impl_->find(m)) {
      for (const std::string& l : {own, name})
        if (!l.empty() && r->body->has_link(l)) return {m, l, true};
    } else if (const WorldModelDesc* d = desc_.find_model(m)) {
      for (const std::string& l : {own, name})
        for (const auto& wl : d->links)
          if (!l.empty() && wl.name == l) return {m, l, false};
    }
  }
  if (!model.empty() && !has_model(model)) throw std::invalid_argument("no model named '" + model + "'");
  if (!model.empty()) throw std::invalid_argument("model '" + model + "' has no link '" + link + "'");
  throw std::invalid_argument("no model has a link named '" + link + "'");
}

namespace {

const WorldLink& world_link(const WorldModelDesc& m, const std::string& link) {
  for (const auto& l : m.links)
    if (l.name == link) return l;
  throw std::invalid_argument("model '" + m.name + "' has no link '" + link + "'");
}

}  // namespace

ModelState World::link_state(const LinkRef& link) const {
  if (const auto* r = impl_->find(link.model)) return r->body->link_state(link.link);
  const WorldModelDesc* m = desc_.find_model(link.model);
  if (!m || !has_model(link.model)) throw std::invalid_argument("no model named '" + link.model + "'");
  // a world model's links move with the model frame
  const ModelState ms = model_state(link.model);
  ModelState s = ms;
  s.pose = ms.pose * world_link(*m, link.link).pose;
  s.linear = ms.linear + ms.angular.cross(s.pose.translation() - ms.pose.translation());
  return s;
}

void World::set_link_state(const LinkRef& link, const ModelState& target) {
  check_state(target);
  // link frame in the model frame, now: the model goes where the link lands
  const ModelState model = model_state(link.model);
  const ModelState now = link_state(link);
  const Eigen::Isometry3d link_in_model = model.pose.inverse() * now.pose;
  ModelState s;
  s.pose = target.pose * link_in_model.inverse();
  s.angular = target.angular;
  s.linear = target.linear + target.angular.cross(s.pose.translation() - target.pose.translation());
  set_model_state(link.model, s);
}

LinkProperties World::link_properties(const LinkRef& link) const {
  LinkProperties p;
  if (const auto* r = impl_->find(link.model)) {
    p.gravity = r->weightless.count(link.link) == 0;
    // a body's top link carries the merged mass of the links fixed to it, as Gazebo's URDF import lumps them
    const detail::BodyTree tree = detail::build_bodies(r->info.model);
    for (const auto& b : tree.bodies)
      if (b.top == link.link) {
        p.mass = b.mass;
        p.com = b.com;
        p.inertia = b.inertia;
        return p;
      }
    for (const auto& l : r->info.model.links)
      if (l.name == link.link && l.inertial) {
        p.mass = l.inertial->mass;
        p.com = l.inertial->origin.translation();
        p.inertia = l.inertial->origin.linear() * l.inertial->inertia * l.inertial->origin.linear().transpose();
      }
    return p;
  }
  const WorldModelDesc* m = desc_.find_model(link.model);
  if (!m) throw std::invalid_argument("no model named '" + link.model + "'");
  const WorldLink& l = world_link(*m, link.link);
  if (l.inertial) {
    p.mass = l.inertial->mass;
    p.com = l.inertial->origin.translation();
    p.inertia = l.inertial->origin.linear() * l.inertial->inertia * l.inertial->origin.linear().transpose();
  }
  return p;
}

ModelProperties World::model_properties(const std::string& model) const {
  if (!has_model(model)) throw std::invalid_argument("no model named '" + model + "'");
  ModelProperties p;
  if (const auto* r = impl_->find(model)) {
    const detail::BodyTree tree = detail::build_bodies(r->info.model);
    for (const auto& b : tree.bodies) p.bodies.push_back(b.top);
    // Gazebo's URDF naming: LINK_collision, LINK_collision_1, ...; a link merged into its body's top link:
    // TOP_fixed_joint_lump__LINK_collision
    // (a collision the model's lumping moved up names the link it was written on: Shape::lumped_from)
    for (const auto& l : r->info.model.links) {
      const auto it = tree.body_of_link.find(l.name);
      const std::string& top = it == tree.body_of_link.end() ? l.name : tree.bodies[it->second].top;
      std::map<std::string, int> count;  // collisions so far per link written on
      for (const auto& c : l.collisions) {
        const std::string& from = c.lumped_from.empty() ? l.name : c.lumped_from;
        const std::string base = top == from ? from : top + "_fixed_joint_lump__" + from;
        const int i = count[from]++;
        p.geoms.push_back(base + "_collision" + (i ? "_" + std::to_string(i) : std::string()));
      }
    }
    // gazebo_ros lists Model::GetJoints: every joint the model loaded, fixed ones too (a lumped URDF joint is gone;
    // car's anchors of a static SDF model were never Gazebo's)
    for (const auto& j : r->info.model.joints)
      if (!j.anchor) p.joints.push_back(j.name);
    p.is_static = r->info.model.is_static;
    return p;
  }
  const WorldModelDesc* m = desc_.find_model(model);
  p.is_static = m->is_static;
  for (const auto& l : m->links) {
    p.bodies.push_back(l.name);
    for (const auto& c : l.collisions) p.geoms.push_back(c.name);
  }
  return p;
}

namespace {

// (robot, joint) by scoped or plain name, as Gazebo 11's Model::GetJoint, model by model (gazebo_ros
// get_joint_properties): the joint's scoped name "MODEL::JOINT" or its name, which may hold "::" itself (an included
// model's "N::joint", docs/COMPAT-sdf.md 16a). A moving joint only, or (moving false) a fixed one too; never car's
// anchors of a static model, which Gazebo does not have.
template <class Robots>
std::pair<const RobotInfo*, const Joint*> find_joint(const Robots& robots, const std::string& name,
                                                     bool moving = true) {
  for (const auto& r : robots) {
    for (const auto& j : r->info.model.joints)
      if ((j.name == name || r->info.name + "::" + j.name == name) && !j.anchor &&
          (!moving || j.type != JointType::Fixed))
        return {&r->info, &j};
  }
  throw std::invalid_argument(std::string("no robot has a ") + (moving ? "moving " : "") + "joint named '" + name +
                              "'");
}

}  // namespace

JointProperties World::joint_properties(const std::string& name) const {
  const auto [info, joint] = find_joint(impl_->robots, name, false);
  JointProperties p;
  p.model = info->name;
  p.type = joint->type;
  p.damping = joint->damping;
  if (joint->type == JointType::Fixed) {
    // Gazebo's Joint::Position(0) of a fixed joint: NaN (ODEFixedJoint::PositionImpl), 0 on a static model; its
    // GetVelocity 0
    p.position = info->model.is_static ? 0.0 : std::numeric_limits<double>::quiet_NaN();
    p.velocity = 0.0;
    return p;
  }
  const auto* r = impl_->find(info->name);
  const int j = r->body->joint(joint->name);
  p.position = r->body->joint_position(j);
  p.velocity = r->body->joint_velocity(j);
  return p;
}

void World::set_joint_positions(const std::string& model, const std::vector<std::string>& joints,
                                const std::vector<double>& positions, bool keep_speeds) {
  if (joints.size() != positions.size())
    throw std::invalid_argument("joint name and position list have different lengths");
  auto* r = impl_->find(model);
  if (!r) {
    if (has_model(model)) throw std::invalid_argument("model '" + model + "' has no joints");
    throw std::invalid_argument("no model named '" + model + "'");
  }
  std::map<int, double> set;
  for (size_t i = 0; i < joints.size(); ++i) {
    const int j = r->body->joint(joints[i]);
    if (j < 0) throw std::invalid_argument("model '" + model + "' has no moving joint '" + joints[i] + "'");
    if (!std::isfinite(positions[i]))
      throw std::invalid_argument("joint '" + joints[i] + "': position must be finite");
    set[j] = positions[i];
  }
  physics::set_joint_positions(*r->body, set, keep_speeds);
  impl_->phys->invalidate_rays();
}

Eigen::Vector3d World::body_com(const LinkRef& link) const {
  if (const auto* r = impl_->find(link.model)) return physics::body_com(*r->body, link.link);
  // a world model link: its inertial origin
  const WorldModelDesc* m = desc_.find_model(link.model);
  if (!m) throw std::invalid_argument("no model named '" + link.model + "'");
  const WorldLink& l = world_link(*m, link.link);
  const Eigen::Isometry3d pose = link_state(link).pose;
  return l.inertial ? Eigen::Vector3d(pose * l.inertial->origin.translation()) : pose.translation();
}

void World::apply_wrench(const LinkRef& link, const Eigen::Vector3d& force, const Eigen::Vector3d& torque,
                         double start, double duration) {
  if (!force.allFinite() || !torque.allFinite() || !std::isfinite(start) || !std::isfinite(duration))
    throw std::invalid_argument("the wrench, start time and duration must be finite");
  if (!impl_->find(link.model)) {
    const WorldModelDesc* m = desc_.find_model(link.model);
    if (!m || !has_model(link.model)) throw std::invalid_argument("no model named '" + link.model + "'");
    // a static model's link is accepted and moves nothing, as in Gazebo 11 (ODELink::AddForce without a body)
    world_link(*m, link.link);
  }
  impl_->wrenches.push_back({link, force, torque, first_tick(start, dt(), tick_),
                             last_tick(start, duration, dt(), tick_)});
}

void World::apply_joint_effort(const std::string& joint, double effort, double start, double duration) {
  check_effort(effort);
  if (!std::isfinite(start) || !std::isfinite(duration))
    throw std::invalid_argument("the start time and duration must be finite");
  const auto [info, j] = find_joint(impl_->robots, joint);
  impl_->efforts.push_back({info->name, j->name, effort, first_tick(start, dt(), tick_),
                            last_tick(start, duration, dt(), tick_)});
}

// A link's or joint's name, or its scoped name "MODEL::NAME" (find_joint, find_link).
int World::clear_wrenches(const std::string& link) {
  auto& w = impl_->wrenches;
  const size_t before = w.size();
  w.erase(std::remove_if(w.begin(), w.end(),
                         [&](const Impl::WrenchJob& j) {
                           return j.link.link == link || j.link.model + "::" + j.link.link == link;
                         }),
          w.end());
  return static_cast<int>(before - w.size());
}

int World::clear_joint_efforts(const std::string& joint) {
  auto& e = impl_->efforts;
  const size_t before = e.size();
  e.erase(std::remove_if(e.begin(), e.end(),
                         [&](const Impl::EffortJob& j) { return j.joint == joint || j.robot + "::" + j.joint == joint; }),
          e.end());
  return static_cast<int>(before - e.size());
}

Eigen::Vector3d World::gravity() const { return impl_->env.gravity; }

void World::set_gravity(const Eigen::Vector3d& g) {
  if (!g.allFinite()) throw std::invalid_argument("gravity must be finite");
  impl_->env.gravity = g;
  physics::set_gravity(*impl_->phys, g);
}

int World::solver_iterations() const {
  return impl_->solver_iterations > 0 ? impl_->solver_iterations : options_.solver_iterations;
}

void World::set_solver_iterations(int n) {
  if (n < 1) throw std::invalid_argument("solver iterations must be at least 1");
  impl_->solver_iterations = n;
  physics::set_solver_iterations(*impl_->phys, n);
}

// ---- users' own plug-ins ------------------------------------------------------------------------------------

bool World::physics_enabled() const { return impl_->physics_on; }

size_t World::robot_count() const { return impl_->robots.size(); }

uint64_t World::add_step_hook(StepPhase phase, StepHook hook) {
  if (!hook) throw std::invalid_argument("a step hook needs a function");
  const uint64_t id = impl_->next_hook++;
  impl_->hooks.push_back(std::make_unique<Impl::Hook>(Impl::Hook{id, phase, std::move(hook)}));
  return id;
}

void World::remove_step_hook(uint64_t id) {
  for (auto& h : impl_->hooks)
    if (h->id == id) {
      h->removed = true;
      impl_->hooks_dirty = true;
    }
  if (!impl_->running_hooks) impl_->drop_removed_hooks();
  auto& ph = impl_->pause_hooks;
  ph.erase(std::remove_if(ph.begin(), ph.end(), [id](const auto& h) { return h.first == id; }), ph.end());
  for (auto* v : {&impl_->stop_hooks, &impl_->time_reset_hooks})
    v->erase(std::remove_if(v->begin(), v->end(), [id](const auto& h) { return h.first == id; }), v->end());
}

bool World::paused() const { return impl_->paused; }

void World::set_paused(bool paused) {
  if (impl_->paused == paused) return;
  impl_->paused = paused;
  // a copy: a hook may add or remove hooks
  const auto hooks = impl_->pause_hooks;
  for (const auto& h : hooks) h.second(paused);
}

uint64_t World::add_pause_hook(std::function<void(bool)> hook) {
  if (!hook) throw std::invalid_argument("a pause hook needs a function");
  const uint64_t id = impl_->next_hook++;
  impl_->pause_hooks.emplace_back(id, std::move(hook));
  return id;
}

uint64_t World::add_stop_hook(std::function<void()> hook) {
  if (!hook) throw std::invalid_argument("a stop hook needs a function");
  const uint64_t id = impl_->next_hook++;
  impl_->stop_hooks.emplace_back(id, std::move(hook));
  return id;
}

uint64_t World::add_time_reset_hook(std::function<void()> hook) {
  if (!hook) throw std::invalid_argument("a time-reset hook needs a function");
  const uint64_t id = impl_->next_hook++;
  impl_->time_reset_hooks.emplace_back(id, std::move(hook));
  return id;
}

void World::stop() {
  if (impl_->stopped) return;
  impl_->stopped = true;
  const auto hooks = impl_->stop_hooks;
  for (const auto& h : hooks) h.second();
}

void World::defer(std::function<void()> work) {
  if (!work) throw std::invalid_argument("deferred work needs a function");
  impl_->deferred.push_back(std::move(work));
}

void World::run_deferred() {
  std::vector<std::function<void()>> now;
  now.swap(impl_->deferred);
  for (auto& w : now) w();
}

const std::vector<Diagnostic>& World::world_diagnostics() const { return impl_->world_diagnostics; }

std::vector<Diagnostic> World::load_system_plugin(const std::string& filename, const std::vector<std::string>& args) {
  std::vector<Diagnostic> found;
  if (auto p = car_sim::load_system_plugin(*this, filename, args, &found)) impl_->system_plugins.push_back(std::move(p));
  impl_->world_diagnostics.insert(impl_->world_diagnostics.end(), found.begin(), found.end());
  return found;
}

namespace {

// (robot, joint index) of a moving joint, for the per-step calls.
template <class Impl>
std::pair<typename Impl::RobotRt*, int> moving_joint(const Impl& impl, const std::string& robot,
                                                     const std::string& joint) {
  auto* r = impl.find(robot);
  if (!r) throw std::invalid_argument("no robot named '" + robot + "'");
  const int j = r->body->joint(joint);
  if (j < 0) throw std::invalid_argument("model '" + robot + "' has no moving joint '" + joint + "'");
  return {r, j};
}

}  // namespace

void World::add_link_wrench(const LinkRef& link, const Eigen::Vector3d& force, const Eigen::Vector3d& torque,
                            const Eigen::Vector3d& point, Frame frame) {
  if (!force.allFinite() || !torque.allFinite() || !point.allFinite())
    throw std::invalid_argument("force, torque and point must be finite");
  auto* r = impl_->find(link.model);
  if (!r) throw std::invalid_argument("no robot named '" + link.model + "'");
  if (!r->body->has_link(link.link))
    throw std::invalid_argument("model '" + link.model + "' has no link '" + link.link + "'");
  r->apply_wrench(link.link, Wrench{force, torque}, point, frame == Frame::Link);
}

double World::joint_position(const std::string& robot, const std::string& joint) const {
  const auto [r, j] = moving_joint(*impl_, robot, joint);
  return r->body->joint_position(j);
}

double World::joint_velocity(const std::string& robot, const std::string& joint) const {
  const auto [r, j] = moving_joint(*impl_, robot, joint);
  return r->body->joint_velocity(j);
}

double World::add_joint_force(const std::string& robot, const std::string& joint, double effort) {
  check_effort(effort);
  const auto [r, j] = moving_joint(*impl_, robot, joint);
  for (const auto& jt : r->info.model.joints)
    if (jt.name == joint && jt.limits && jt.limits->effort > 0.0)
      effort = std::clamp(effort, -jt.limits->effort, jt.limits->effort);
  physics::add_joint_effort(*r->body, j, effort);
  return effort;
}

void World::set_joint_velocity(const std::string& robot, const std::string& joint, double velocity) {
  if (!std::isfinite(velocity)) throw std::invalid_argument("velocity must be a finite number");
  const auto [r, j] = moving_joint(*impl_, robot, joint);
  r->body->set_joint_velocity(j, velocity);
}

void World::set_link_velocity(const LinkRef& link, const Eigen::Vector3d& linear, const Eigen::Vector3d& angular) {
  if (!linear.allFinite() || !angular.allFinite()) throw std::invalid_argument("velocities must be finite");
  ModelState s = link_state(link);
  // the link frame's origin moves at the centre of mass's velocity plus the turn about it
  s.linear = linear + angular.cross(s.pose.translation() - body_com(link));
  s.angular = angular;
  set_link_state(link, s);
}

void step_worlds(const std::vector<World*>& worlds, uint64_t n) {
  const int count = static_cast<int>(worlds.size());
  // one world on two threads at once would race on its state
  std::map<const World*, int> first;
  for (int i = 0; i < count; ++i) {
    if (!worlds[i]) throw std::invalid_argument("step_worlds: worlds[" + std::to_string(i) + "] is null");
    auto [it, fresh] = first.emplace(worlds[i], i);
    if (!fresh)
      throw std::invalid_argument("step_worlds: worlds[" + std::to_string(i) + "] is worlds[" +
                                  std::to_string(it->second) + "]; a world may appear once");
  }
  // each item's error kept in its slot: which one is raised does not depend on which thread failed first
  std::vector<std::exception_ptr> errors(worlds.size());
  parallel_for(count, [&](int i) {
    try {
      worlds[i]->step(n);
    } catch (...) {
      errors[i] = std::current_exception();
    }
  });
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
}

void check_state(const ModelState& s) {
  if (!s.pose.matrix().allFinite() || !s.linear.allFinite() || !s.angular.allFinite())
    throw std::invalid_argument("pose and twist must be finite numbers");
}

void check_effort(double effort) {
  if (!std::isfinite(effort)) throw std::invalid_argument("effort must be a finite number");
}

void check_physics_properties(const Eigen::Vector3d& gravity, double time_step, double max_update_rate) {
  if (!gravity.allFinite() || !std::isfinite(time_step) || !std::isfinite(max_update_rate) || max_update_rate < 0.0)
    throw std::invalid_argument("gravity, time_step and max_update_rate must be finite (max_update_rate >= 0)");
}

std::optional<uint64_t> steps_until(double now, double t, double dt) {
  if (!std::isfinite(t) || !(t > now)) return std::nullopt;
  // 1e-9 of a step: a time on a step's end, less its rounding, is that step
  return static_cast<uint64_t>(std::ceil((t - now) / dt - 1e-9));
}

}  // namespace car_sim

namespace car_sim {

// ---- users' own plug-ins: ODE's joint motor, gravity mode ----------------------------------------------------

void World::set_joint_motor(const std::string& robot, const std::string& joint, const JointMotor& motor) {
  if (!std::isfinite(motor.velocity) || !std::isfinite(motor.max_effort))
    throw std::invalid_argument("a joint motor's velocity and max effort must be finite numbers");
  if (motor.max_effort < 0.0)
    throw std::invalid_argument("a joint motor's max effort must be >= 0 (got " + std::to_string(motor.max_effort) + ")");
  const auto [r, j] = moving_joint(*impl_, robot, joint);
  r->joint_motors[j] = motor;
  impl_->make_velocity_motor(*r, j, motor);
}

World::JointMotor World::joint_motor(const std::string& robot, const std::string& joint) const {
  const auto [r, j] = moving_joint(*impl_, robot, joint);
  const auto it = r->joint_motors.find(j);
  return it == r->joint_motors.end() ? JointMotor() : it->second;
}

void World::set_link_gravity(const LinkRef& link, bool on) {
  auto* r = impl_->find(link.model);
  if (!r) throw std::invalid_argument("no robot named '" + link.model + "'");
  if (!r->body->has_link(link.link))
    throw std::invalid_argument("model '" + link.model + "' has no link '" + link.link + "'");
  if (on)
    r->weightless.erase(link.link);
  else
    r->weightless.insert(link.link);
}

void World::set_physics_enabled(bool on) { impl_->physics_on = on; }

Wrench World::link_applied_wrench(const LinkRef& link) const {
  auto* r = impl_->find(link.model);
  if (!r) throw std::invalid_argument("no robot named '" + link.model + "'");
  return r->applied_wrench(link.link);
}

bool World::link_gravity(const LinkRef& link) const {
  auto* r = impl_->find(link.model);
  if (!r) throw std::invalid_argument("no robot named '" + link.model + "'");
  if (!r->body->has_link(link.link))
    throw std::invalid_argument("model '" + link.model + "' has no link '" + link.link + "'");
  return r->weightless.count(link.link) == 0;
}

}  // namespace car_sim
