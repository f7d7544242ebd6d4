// The world: the const description, the physics, and the robots' plug-in instances on their schedules. A step
// runs every plug-in's pre_physics, one physics step, then every plug-in's track and, when due, post_physics.
// No kind is named here: kinds come from the registry, drives are reached through TwistDrive.
#include "car_sim/world.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "car_sim/mesh.hpp"
#include "guard.hpp"
#include "physics.hpp"

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
    Eigen::Isometry3d link_pose(const std::string& l) const override { return body->link_pose(l); }
    ModelState link_state(const std::string& l) const override { return body->link_state(l); }
    ModelState root_state() const override { return body->root_state(); }

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
    void set_root_pose(const Eigen::Isometry3d& pose) override {
      ModelState s = body->root_state();
      s.pose = pose;
      body->set_root_state(s);
    }
    void set_joint_position(int j, double position) override { body->set_joint_position(j, position); }
    std::vector<int> wrench_claims;  // joints with a reaction sensor, re-made after a rebuild
    void enable_joint_wrench(int j) override {
      body->enable_joint_wrench(j);
      wrench_claims.push_back(j);
    }
    Wrench joint_wrench(int j) const override { return body->joint_wrench(j); }
    std::vector<LinkContact> link_contacts(const std::string& l) const override { return body->link_contacts(l); }
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
    return i;
  }

  void configure(RobotRt& r, Instance& i, uint64_t tick) {
    i.plugin->configure(r);
    i.schedule = Schedule(i.info.rate, desc.step_size, tick);
  }

  // A fresh physics from the description; robots rebuilt where they were spawned, their motors re-made in id
  // order, every plug-in reset onto a schedule from `tick`.
  void rebuild(const std::set<std::string>& removed, uint64_t tick) {
    for (auto& r : robots) r->body = nullptr;
    phys.reset();
    phys = std::make_unique<physics::Physics>(desc, physics_options(), removed);
    for (auto& r : robots) {
      r->body = &phys->add_robot(r->info.model, r->info.name, r->info.spawn_pose, r->driven);
      for (const auto& [joint, effort] : r->motor_claims) r->body->add_motor(joint, effort);
      for (int j : r->wrench_claims) r->body->enable_joint_wrench(j);
      for (auto& i : r->plugins) {
        i.plugin->reset();
        i.queue.clear();
        i.schedule.restart(tick);
        if (i.active) i.plugin->set_active(true);
      }
    }
  }

  const WorldDescription& desc;
  WorldOptions options;
  Environment env;
  std::unique_ptr<physics::Physics> phys;
  std::vector<std::unique_ptr<RobotRt>> robots;
};

// ---- World ----------------------------------------------------------------------------------------------------

World::World(WorldDescription desc, WorldOptions options) : desc_(std::move(desc)), options_(options) {
  impl_ = std::make_unique<Impl>(desc_, options_);
  impl_->phys = std::make_unique<physics::Physics>(desc_, impl_->physics_options(), removed_);
}

World::~World() = default;

void World::spawn(const RobotModel& model, const std::string& name, const Eigen::Isometry3d& pose,
                  const std::string& robot_namespace) {
  if (name.empty()) throw std::invalid_argument("a model needs a name");
  if (has_model(name)) throw std::invalid_argument("model '" + name + "' exists already");
  if (!pose.matrix().allFinite()) throw std::invalid_argument("the pose to spawn '" + name + "' at is not finite");
  auto r = std::make_unique<Impl::RobotRt>();
  r->info.name = name;
  r->info.robot_namespace = robot_namespace;
  r->info.model = model;
  r->info.spawn_pose = pose;
  // gazebo_ros's spawn: plug-ins without <robotNamespace> get the spawn namespace (docs/COMPAT-spawn.md)
  apply_robot_namespace(&r->info.model, robot_namespace, name);
  load_meshes(&r->info.model, source_dir(model.source));
  r->info.config = resolve_plugins(r->info.model);
  for (const auto& c : r->info.config.plugins) r->plugins.push_back(impl_->make_instance(*r, c));
  for (const auto& i : r->plugins)
    for (const auto& j : i.plugin->driven_joints()) r->driven.insert(j);
  r->body = &impl_->phys->add_robot(r->info.model, name, pose, r->driven);
  for (auto& i : r->plugins) impl_->configure(*r, i, tick_);
  impl_->robots.push_back(std::move(r));
}

void World::attach_plugin(const std::string& robot, const PluginSpec& spec) {
  Impl::RobotRt& r = impl_->robot(robot);
  if (impl_->instance(robot, spec.name))
    throw std::invalid_argument("robot '" + robot + "' has a plug-in named '" + spec.name + "' already");
  PluginConfig c = resolve_plugin(r.info.model, spec, &r.info.config.diagnostics);
  r.info.config.plugins.push_back(c);
  r.plugins.push_back(impl_->make_instance(r, c));
  impl_->configure(r, r.plugins.back(), tick_);
}

void World::remove(const std::string& name) {
  auto& robots = impl_->robots;
  for (auto it = robots.begin(); it != robots.end(); ++it) {
    if ((*it)->info.name != name) continue;
    impl_->phys->remove_robot(name);
    robots.erase(it);
    return;
  }
  if (!desc_.find_model(name) || removed_.count(name)) throw std::invalid_argument("no model named '" + name + "'");
  // A world model stays out, also after a reset (as in Gazebo); the description itself does not change.
  removed_.insert(name);
  impl_->phys->remove_world_model(name);
}

void World::step(uint64_t n) {
  const double dt = desc_.step_size;
  StepContext ctx;
  ctx.dt = dt;
  ctx.world = impl_.get();
  for (uint64_t s = 0; s < n; ++s) {
    ctx.tick = tick_;
    for (auto& r : impl_->robots) r->applied.clear();
    for (auto& r : impl_->robots)
      for (auto& i : r->plugins) i.plugin->pre_physics(ctx, *r);
    try {
      impl_->phys->step(dt);
    } catch (const physics::NonFiniteState& e) {
      ++tick_;
      throw SimulationError("t = " + std::to_string(time()) + " s: " + e.what() +
                            " is not finite; the world stops here (reset it, or delete the model)");
    }
    ctx.tick = ++tick_;
    for (auto& r : impl_->robots) {
      for (auto& i : r->plugins) {
        const bool on = !i.info.lazy || i.active;
        if (on) i.plugin->track(ctx, *r);
        if (!i.schedule.due(tick_)) continue;
        i.schedule.advance(tick_);
        if (!on) continue;
        const size_t before = i.queue.size();
        i.plugin->post_physics(ctx, *r, &i.queue);
        for (size_t k = before; k < i.queue.size(); ++k) {
          i.queue[k]->robot = r->info.name;
          i.queue[k]->plugin = i.info.config.name;
          i.queue[k]->tick = tick_;
        }
      }
    }
  }
}

void World::reset() {
  // time first: the plug-ins' schedules restart from it
  tick_ = 0;
  reset_poses();
}

void World::reset_poses() { impl_->rebuild(removed_, tick_); }

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
  if (auto* r = impl_->find(name)) return r->body->root_state();
  if (auto s = impl_->phys->world_model_state(name)) return *s;
  if (has_model(name)) {
    ModelState s;
    s.pose = desc_.find_model(name)->pose;
    return s;
  }
  throw std::invalid_argument("no model named '" + name + "'");
}

void World::set_model_state(const std::string& name, const ModelState& st) {
  if (!st.pose.matrix().allFinite() || !st.linear.allFinite() || !st.angular.allFinite())
    throw std::invalid_argument("the state to set for '" + name + "' is not finite");
  if (auto* r = impl_->find(name)) {
    r->body->set_root_state(st);
  } else if (!impl_->phys->set_world_model_state(name, st)) {
    if (has_model(name)) throw std::invalid_argument("model '" + name + "' is static");
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
  Instance* i = impl_->instance(robot, plugin);
  if (!i) throw std::invalid_argument("robot '" + robot + "' has no plug-in '" + plugin + "'");
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
    if (auto* d = dynamic_cast<TwistDrive*>(i.plugin.get())) d->set_twist(cmd);
}

std::vector<Contact> World::contacts() const { return impl_->contacts(); }

}  // namespace car_sim
