// libgazebo_ros_control.so: transmissions -> joint interfaces, and the controller manager (docs/COMPAT-control.md).
#include "ros_control.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "car_sim/diagnostics.hpp"

namespace car_sim {
namespace control {

ControllerError::ControllerError(const std::string& controller, const std::string& key, const std::string& reason)
    : std::runtime_error("controller '" + controller + "': " + (key.empty() ? "" : key + ": ") + reason),
      key_(key),
      reason_(reason) {}

const char* to_string(Interface i) {
  switch (i) {
    case Interface::Position: return "hardware_interface/PositionJointInterface";
    case Interface::Velocity: return "hardware_interface/VelocityJointInterface";
    case Interface::Effort: return "hardware_interface/EffortJointInterface";
  }
  return "";
}

bool JointIo::has(Interface i) const { return std::find(interfaces.begin(), interfaces.end(), i) != interfaces.end(); }

bool ParamReader::has(const std::string& key) const { return p_.count(key) > 0; }

void ParamReader::fail(const std::string& key, const std::string& reason) const {
  throw ControllerError(name_, key, reason);
}

std::string ParamReader::text(const std::string& key) const {
  const auto it = p_.find(key);
  if (it == p_.end()) fail(key, "missing (required key)");
  if (it->second.size() != 1) fail(key, "expected one value, got a list");
  return it->second[0];
}

std::string ParamReader::text(const std::string& key, const std::string& def) const {
  return has(key) ? text(key) : def;
}

static double to_number(const ParamReader& r, const std::string& key, const std::string& v) {
  try {
    size_t used = 0;
    const double d = std::stod(v, &used);
    if (used != v.size() || !std::isfinite(d)) throw std::invalid_argument(v);
    return d;
  } catch (const std::exception&) {
    r.fail(key, "'" + v + "' is not a finite number");
  }
}

double ParamReader::number(const std::string& key) const { return to_number(*this, key, text(key)); }
double ParamReader::number(const std::string& key, double def) const { return has(key) ? number(key) : def; }

bool ParamReader::flag(const std::string& key, bool def) const {
  if (!has(key)) return def;
  bool v = false;
  if (!parse_flag(text(key), &v)) fail(key, "'" + text(key) + "' is not a boolean");
  return v;
}

std::vector<std::string> ParamReader::list(const std::string& key) const {
  const auto it = p_.find(key);
  if (it == p_.end()) fail(key, "missing (required key)");
  return it->second;
}

std::vector<double> ParamReader::numbers(const std::string& key) const {
  std::vector<double> out;
  for (const auto& v : list(key)) out.push_back(to_number(*this, key, v));
  return out;
}

Pid Pid::from(const ParamReader& r, const std::string& prefix) {
  Pid g;
  g.p = r.number(prefix + "/p");
  g.i = r.number(prefix + "/i", 0.0);
  g.d = r.number(prefix + "/d", 0.0);
  const double clamp = std::abs(r.number(prefix + "/i_clamp", 0.0));
  g.i_max = std::abs(r.number(prefix + "/i_clamp_max", clamp));
  g.i_min = -std::abs(r.number(prefix + "/i_clamp_min", clamp));
  g.antiwindup = r.flag(prefix + "/antiwindup", false);
  return g;
}

// As control_toolbox::Pid::computeCommand(error, error_dot, dt): without antiwindup the term i * sum(error dt) is
// clamped to [i_min, i_max] while the sum goes on; with it (i != 0) the sum itself stays within [i_min, i_max] / i.
double Pid::compute(double error, double error_dot, double dt) {
  d_error = error_dot;
  if (dt == 0.0 || !std::isfinite(error) || !std::isfinite(error_dot)) return 0.0;
  p_term = p * error;
  i_error += dt * error;
  if (antiwindup && i != 0.0) {
    const double a = i_min / i, b = i_max / i;
    i_error = std::clamp(i_error, std::min(a, b), std::max(a, b));
  }
  i_term = i * i_error;
  // i_min <= 0 <= i_max (from() forces the signs)
  if (!antiwindup) i_term = std::clamp(i_term, i_min, i_max);
  d_term = d * error_dot;
  return p_term + i_term + d_term;
}

// As control_toolbox::Pid::computeCommand(error, dt).
double Pid::compute(double error, double dt) {
  if (dt == 0.0 || !std::isfinite(error)) return 0.0;
  double error_dot = d_error;
  if (dt > 0.0) {
    if (valid_last) error_dot = (error - p_error_last) / dt;
    p_error_last = error;
    valid_last = true;
  }
  return compute(error, error_dot, dt);
}

const ControllerType* find_controller_type(const std::string& name) {
  for (const auto& t : controller_types())
    if (t.name == name) return &t;
  return nullptr;
}

}  // namespace control

using control::ControllerError;
using control::Interface;

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType N = ParamType::Number;
constexpr ParamType B = ParamType::Flag;

bool parse_interface(const std::string& s, Interface* i) {
  if (s == "PositionJointInterface") *i = Interface::Position;
  else if (s == "VelocityJointInterface") *i = Interface::Velocity;
  else if (s == "EffortJointInterface") *i = Interface::Effort;
  else return false;
  return true;
}

// Transmissions checked against the model, as gazebo_ros_control's DefaultRobotHWSim: a joint must exist and move;
// its interface must be one car simulates.
// gazebo_ros_control's own hardware sim, the only one car has
const char* const kDefaultSimType = "gazebo_ros_control/DefaultRobotHWSim";

void finish(ResolveContext& ctx) {
  const RobotModel& m = ctx.model();
  if (ctx.config().number("controlPeriod") < 0) ctx.fail("controlPeriod", "must be >= 0");
  // A robotSimType car lacks (franka_gazebo/FrankaHWSim, PAL's): car's default hardware sim drives the standard
  // joint interfaces; the others (franka_hw/FrankaStateInterface, ...) are left out. One warning names the type
  // (docs/COMPAT-control.md).
  const std::string sim_type = ctx.config().text("robotSimType");
  const bool foreign = sim_type != kDefaultSimType;
  if (foreign)
    ctx.warn(Severity::Warning, "robot-sim-type", "robotSimType",
             "'" + sim_type + "' is not simulated by car; car's " + kDefaultSimType +
                 " drives the standard joint interfaces (Position-, Velocity-, EffortJointInterface) the "
                 "transmissions declare, and leaves the others out");
  for (const auto& t : m.transmissions) {
    const std::string where = "transmission[" + t.name + "]";
    if (t.joints.empty()) throw LoadError(m.source, t.line, where, "has no <joint>");
    for (const auto& j : t.joints) {
      const std::string at = where + "/joint[" + j.joint + "]";
      const Joint* joint = m.find_joint(j.joint);
      if (!joint) throw LoadError(m.source, t.line, at, "no joint '" + j.joint + "' in the model");
      if (joint->type == JointType::Fixed)
        throw LoadError(m.source, t.line, at, "joint '" + j.joint + "' is fixed; ros_control cannot drive it");
      if (j.interfaces.empty())
        throw LoadError(m.source, t.line, at + "/hardwareInterface", "no <hardwareInterface> on the joint or actuator");
      for (const auto& s : j.interfaces) {
        Interface i;
        if (!parse_interface(s, &i) && !foreign)
          throw LoadError(m.source, t.line, at + "/hardwareInterface",
                          "'" + s + "' is not simulated by car (Position-, Velocity- or EffortJointInterface)");
      }
    }
  }
}

// The links a joint moves: its child link and every link below it.
std::vector<const Link*> links_below(const RobotModel& m, const Joint& j) {
  std::vector<std::string> names{j.child};
  for (size_t k = 0; k < names.size(); ++k)
    for (const auto& c : m.joints)
      if (c.parent == names[k]) names.push_back(c.child);
  std::vector<const Link*> out;
  for (const auto& n : names)
    for (const auto& l : m.links)
      if (l.name == n && l.inertial && l.inertial->mass > 0) out.push_back(&l);
  return out;
}

// What the joint moves with every other joint locked, at the current pose: the inertia about its axis [kg m^2]
// (revolute, continuous) or the mass [kg] (prismatic). Free joints below (and a free base) only make the
// articulated inertia smaller, so this bounds it from above.
double locked_inertia(const RobotHandle& robot, const Joint& j, const std::vector<const Link*>& links) {
  Eigen::Isometry3d frame;
  try {
    frame = robot.link_pose(j.child);  // the child link's frame is the joint's frame
  } catch (const std::exception&) {
    return 0.0;
  }
  const Eigen::Vector3d axis = frame.linear() * j.axis, at = frame.translation();
  double inertia = 0.0;
  for (const Link* l : links) {
    Eigen::Isometry3d com;
    try {
      com = robot.link_pose(l->name) * l->inertial->origin;
    } catch (const std::exception&) {
      continue;  // a link dropped by the loader
    }
    const double m = l->inertial->mass;
    if (j.type == JointType::Prismatic) {
      inertia += m;
      continue;
    }
    const Eigen::Matrix3d I = com.linear() * l->inertial->inertia * com.linear().transpose();
    inertia += axis.dot(I * axis) + m * (com.translation() - at).cross(axis).squaredNorm();
  }
  return inertia;
}

}  // namespace

RosControlConfig RosControlConfig::from(const PluginConfig& c) {
  RosControlConfig r;
  r.plugin_name = c.name;
  r.robot_namespace = c.text("robotNamespace");
  r.robot_sim_type = c.text("robotSimType");
  r.control_period = c.number("controlPeriod");
  r.legacy_mode_ns = c.flag("legacyModeNS");
  return r;
}

// "/a/b": a and b joined under the root ("" parts left out).
static std::string join_ns(const std::string& a, const std::string& b) { return a.empty() ? "/" + b : "/" + a + "/" + b; }

// <robotNamespace> absent: the model's name, empty: global, as gazebo_ros_control (leading '/' dropped)
static std::string control_ns(const PluginConfig& c, const std::string& robot) {
  std::string ns = plugin_robot_namespace(c, robot);
  while (!ns.empty() && ns.front() == '/') ns.erase(ns.begin());
  return ns;
}

RosControl::RosControl(const PluginConfig& c, const std::string& robot)
    : cfg_(RosControlConfig::from(c)), ns_(control_ns(c, robot)) {}

std::string RosControl::summary() const {
  const size_t t = model_ ? model_->transmissions.size() : 0;
  return std::to_string(t) + (t == 1 ? " transmission, " : " transmissions, ") + std::to_string(joints_.size()) +
         (joints_.size() == 1 ? " joint" : " joints");
}

void RosControl::configure(RobotHandle& robot) {
  model_ = &robot.model();
  for (const auto& t : model_->transmissions) {
    for (const auto& e : t.joints) {
      control::JointIo io;
      io.name = e.joint;
      io.index = robot.joint(e.joint);
      io.joint = model_->find_joint(e.joint);
      for (const auto& s : e.interfaces) {
        Interface i;
        if (parse_interface(s, &i)) io.interfaces.push_back(i);
      }
      if (io.index < 0) continue;  // merged away (a joint of a dropped link)
      if (io.interfaces.empty()) continue;  // only interfaces of a robotSimType car lacks (finish warned)
      auto same = std::find_if(joints_.begin(), joints_.end(), [&](const auto& j) { return j.name == io.name; });
      if (same != joints_.end()) {
        for (auto i : io.interfaces)
          if (!same->has(i)) same->interfaces.push_back(i);
        continue;
      }
      joints_.push_back(io);
    }
  }
  // One motor per joint, capped by <limit effort> (none: unlimited, as Gazebo's SetPosition / SetParam("vel")).
  // Effort-only joints get none: an idle Bullet motor (gains 0) still resists any change of velocity up to its cap.
  for (const auto& j : joints_)
    motors_.push_back(j.has(Interface::Position) || j.has(Interface::Velocity) ? robot.add_motor(j.index, 1e12) : -1);
  for (const auto& j : joints_) subtree_.push_back(j.joint ? links_below(*model_, *j.joint) : std::vector<const Link*>{});
  modes_.assign(joints_.size(), -1);
  pids_.assign(joints_.size(), std::nullopt);
  read(robot);
  for (auto& j : joints_) j.cmd_position = j.position;
}

// A world reset keeps the controllers (running ones keep running, as in Gazebo); commands start again from the
// spawn pose: position commands hold it, velocity and effort commands are 0.
void RosControl::reset() {
  first_ = true;
  now_ = 0.0;
  for (auto& j : joints_) j.cmd_velocity = j.cmd_effort = 0.0;
}

void RosControl::read(const RobotHandle& robot) {
  for (auto& j : joints_) {
    j.position = robot.joint_position(j.index);
    j.velocity = robot.joint_velocity(j.index);
  }
  root_ = robot.root_state();
}

control::ControlTime RosControl::time_at(uint64_t tick, double dt) const {
  control::ControlTime t;
  t.tick = tick;
  t.time = static_cast<double>(tick) * dt;
  t.period = static_cast<double>(tick - last_update_) * dt;
  return t;
}

void RosControl::pre_physics(const StepContext& ctx, RobotHandle& robot) {
  dt_ = ctx.dt;
  if (first_) {
    // the control period in whole steps, as gazebo_ros_control (a period below the step is the step)
    period_ticks_ = cfg_.control_period > 0 ? std::max<uint64_t>(1, std::llround(cfg_.control_period / ctx.dt)) : 1;
    last_update_ = ctx.tick;
    read(robot);
    for (auto& j : joints_) j.cmd_position = j.position;
    first_ = false;
  }
  if (ctx.tick - last_update_ >= period_ticks_) {
    read(robot);
    const control::ControlTime t = time_at(ctx.tick, ctx.dt);
    // the switch's starts first, each from the joints read above (controller_manager's manageSwitch; upstream runs
    // it after the updates, so its first update comes one control period later: docs/COMPAT-control.md)
    for (auto& l : loaded_)
      if (l.starting_due) {
        l.controller->starting(t);
        l.starting_due = false;
        for (const auto& [leaf, value] : l.held) {
          CommandResult ignored;
          l.controller->command(leaf, value, t.time, &ignored);
        }
        l.held.clear();
      }
    for (auto& l : loaded_)
      if (l.running) l.controller->update(t);
    last_update_ = ctx.tick;
  }
  // write: every step (efforts last one step; motor targets stay)
  for (size_t k = 0; k < joints_.size(); ++k) {
    control::JointIo& j = joints_[k];
    const Interface mode = modes_[k] >= 0 ? static_cast<Interface>(modes_[k]) : j.interfaces.front();
    MotorTarget m;
    m.kd = 0.0;
    m.kp = 0.0;
    const double limit = j.joint && j.joint->limits && j.joint->limits->effort > 0 ? j.joint->limits->effort : 0.0;
    // pid_gains: the PID's effort on the error from the joint's state as last read, every step, capped by the
    // effort limit (DefaultRobotHWSim::writeSim, POSITION_PID and VELOCITY_PID); its motor is off
    if (pids_[k] && mode != Interface::Effort) {
      double error = j.cmd_velocity - j.velocity;  // [rad/s] or [m/s]
      if (mode == Interface::Position) {
        error = position_command(k) - j.position;  // [rad] or [m]
        if (j.joint && j.joint->type == JointType::Continuous) error = std::remainder(error, 2.0 * M_PI);
      }
      double f = pids_[k]->compute(error, ctx.dt);  // [N m] or [N]
      if (limit > 0) f = std::clamp(f, -limit, limit);
      robot.add_joint_effort(j.index, f);
      j.effort = f;
      m.enabled = false;
      if (motors_[k] >= 0) robot.set_motor(motors_[k], m);
      continue;
    }
    switch (mode) {
      case Interface::Position: {
        const double p = position_command(k);
        // The motor asks for the error's velocity e / dt (on the command in one step), but no faster than the
        // joint can still stop at the command braking at half its effort cap over its locked inertia I:
        // sqrt(2 a |e|), a = 0.5 * effort / I. Without it the capped motor brakes only within one step's travel
        // and swings around the command. Its velocity target is clamped to <limit velocity> (joint_limits_interface
        // limits a position command's change per period by it, too).
        const double e = p - robot.joint_position(j.index);  // [rad] or [m], now (j.position: last update)
        double v = e / ctx.dt;
        const double inertia = limit > 0 && j.joint ? locked_inertia(robot, *j.joint, subtree_[k]) : 0.0;
        if (inertia > 0) v = std::copysign(std::min(std::abs(v), std::sqrt(2.0 * 0.5 * limit / inertia * std::abs(e))), e);
        m.velocity = v;
        m.kd = 1.0;
        m.kp = 0.0;
        m.position = p;
        j.effort = 0.0;
        break;
      }
      case Interface::Velocity:
        m.velocity = j.cmd_velocity;
        m.kd = 1.0;
        j.effort = 0.0;
        break;
      case Interface::Effort: {
        double e = j.cmd_effort;
        if (limit > 0) e = std::clamp(e, -limit, limit);
        if (!std::isfinite(e)) e = 0.0;
        robot.add_joint_effort(j.index, e);
        j.effort = e;
        m.enabled = false;  // the joint's motor (it offers position or velocity too) lets the effort act alone
        break;
      }
    }
    if (motors_[k] >= 0) robot.set_motor(motors_[k], m);
  }
}

double RosControl::position_command(size_t k) const {
  const control::JointIo& j = joints_[k];
  const double p = j.cmd_position;
  if (j.joint && j.joint->limits && j.joint->type != JointType::Continuous &&
      j.joint->limits->lower < j.joint->limits->upper)
    return std::clamp(p, j.joint->limits->lower, j.joint->limits->upper);
  return p;
}

// As DefaultRobotHWSim::initSim: a joint commanded by position or velocity whose pid_gains has a p is driven by
// that PID from now on; one without p keeps its motor (Gazebo: SetPosition, SetParam("vel")). car says what it
// used, and what it could not.
void RosControl::set_pid_gains(const control::Params& params, CallResponse* r) {
  const std::string at = join_ns(ns_, "gazebo_ros_control/pid_gains");
  std::set<std::string> named;
  for (const auto& kv : params) named.insert(kv.first.substr(0, kv.first.find('/')));
  for (size_t k = 0; k < joints_.size(); ++k) {
    const control::JointIo& j = joints_[k];
    if (!named.erase(j.name)) continue;
    const std::string where = "gazebo_ros_control: " + at + "/" + j.name;
    if (!j.has(Interface::Position) && !j.has(Interface::Velocity)) {
      r->warnings.push_back(where + ": joint '" + j.name + "' offers only an effort interface; its gains are not "
                            "used (as in Gazebo)");
      continue;
    }
    if (!params.count(j.name + "/p")) {
      r->warnings.push_back(where + ": no p (required key); joint '" + j.name + "' keeps its motor (Gazebo says "
                            "'No p gain specified for pid')");
      continue;
    }
    try {
      pids_[k] = control::Pid::from(control::ParamReader("pid_gains", params), j.name);
    } catch (const ControllerError& e) {
      r->ok = false;
      r->errors.push_back("gazebo_ros_control: " + at + "/" + e.key() + ": " + e.reason() + "; joint '" + j.name +
                          "' keeps its motor");
      continue;
    }
    std::ostringstream g;
    g << "p " << pids_[k]->p << ", i " << pids_[k]->i << ", d " << pids_[k]->d;
    r->infos.push_back(where + ": joint '" + j.name + "' follows its position and velocity commands by this PID (" +
                       g.str() + "), its effort capped by the joint's effort limit");
  }
  // Gazebo ignores them too; another plug-in may read them (roboticsgroup's MimicJointPlugin reads its mimic
  // joint's gains there)
  for (const auto& n : named)
    r->infos.push_back("gazebo_ros_control: " + at + "/" + n + ": no transmission joint '" + n +
                       "' in this robot: not gazebo_ros_control's (another plug-in may read them)");
}

void RosControl::post_physics(const StepContext& ctx, const RobotHandle& robot, OutputQueue* out) {
  now_ = ctx.time();
  bool any = false;
  for (const auto& l : loaded_) any = any || l.running;
  if (!any) return;
  read(robot);
  control::ControlTime t;
  t.tick = ctx.tick;
  t.time = ctx.time();
  t.period = ctx.dt;
  for (auto& l : loaded_)
    if (l.running && !l.starting_due) l.controller->publish(t, out);
}

control::JointIo& RosControl::claim(const std::string& controller, const std::string& key, const std::string& joint,
                                    Interface i) {
  for (auto& j : joints_) {
    if (j.name != joint) continue;
    if (!j.has(i))
      throw ControllerError(controller, key,
                            "joint '" + joint + "' has no " + to_string(i) + " in its <transmission>");
    return j;
  }
  if (model_ && model_->find_joint(joint))
    throw ControllerError(controller, key, "joint '" + joint + "' has no <transmission>; ros_control cannot reach it");
  throw ControllerError(controller, key, "no joint '" + joint + "' in the robot");
}

control::Controller* RosControl::controller(const std::string& name) {
  for (auto& l : loaded_)
    if (l.name == name) return l.controller.get();
  return nullptr;
}

void RosControl::load(const std::string& name, const std::string& type, const control::Params& params) {
  if (controller(name)) throw ControllerError(name, "", "a controller of that name is already loaded");
  const control::ControllerType* t = control::find_controller_type(type);
  if (!t) {
    std::string known;
    for (const auto& k : control::controller_types()) known += (known.empty() ? "" : ", ") + k.name;
    throw ControllerError(name, "type", "unknown controller type '" + type + "' (car knows " + known + ")");
  }
  auto c = t->make();
  c->configure(control::ParamReader(name, params), *this);
  loaded_.push_back({name, type, false, false, {}, std::move(c)});
}

void RosControl::unload(const std::string& name) {
  const auto it = std::find_if(loaded_.begin(), loaded_.end(), [&](const Loaded& l) { return l.name == name; });
  if (it == loaded_.end()) throw ControllerError(name, "", "not loaded");
  if (it->running) throw ControllerError(name, "", "still running; stop it first");
  loaded_.erase(it);
}

bool RosControl::switch_controllers(const std::vector<std::string>& start, const std::vector<std::string>& stop,
                                    bool strict, std::string* why) {
  auto find = [&](const std::string& n) -> Loaded* {
    for (auto& l : loaded_)
      if (l.name == n) return &l;
    return nullptr;
  };
  std::vector<Loaded*> to_start, to_stop;
  for (const auto& n : stop) {
    Loaded* l = find(n);
    if (!l || !l->running) {
      const std::string r = "controller '" + n + "': " + (l ? "not running" : "not loaded") + ", cannot stop it";
      if (strict) { *why = r; return false; }
      continue;
    }
    to_stop.push_back(l);
  }
  for (const auto& n : start) {
    Loaded* l = find(n);
    if (!l || (l->running && std::find(to_stop.begin(), to_stop.end(), l) == to_stop.end())) {
      const std::string r = "controller '" + n + "': " + (l ? "already running" : "not loaded") + ", cannot start it";
      if (strict) { *why = r; return false; }
      continue;
    }
    to_start.push_back(l);
  }
  // resource conflicts: a joint may be commanded by one running controller (joint_state_controller claims none)
  std::map<std::string, std::string> owner;
  for (auto& l : loaded_) {
    const bool runs = (l.running && std::find(to_stop.begin(), to_stop.end(), &l) == to_stop.end());
    if (!runs) continue;
    for (const auto& [iface, js] : l.controller->claimed())
      for (const auto& j : js) owner[j] = l.name;
  }
  for (Loaded* l : to_start) {
    for (const auto& [iface, js] : l->controller->claimed())
      for (const auto& j : js)
        if (owner.count(j)) {
          *why = "controller '" + l->name + "': joint '" + j + "' is already claimed by '" + owner[j] + "'";
          return false;
        }
    for (const auto& [iface, js] : l->controller->claimed())
      for (const auto& j : js) owner[j] = l->name;
  }
  const control::ControlTime t = time_at(last_update_, dt_);
  for (Loaded* l : to_stop) {
    // stopped before its first update: it never started
    if (!l->starting_due) l->controller->stopping(t);
    l->running = false;
    l->starting_due = false;
    l->held.clear();
  }
  // running from now on (list_controllers says so, commands reach it); starting() at the next control update
  for (Loaded* l : to_start) {
    l->running = true;
    l->starting_due = true;
  }
  // each joint follows the interface of the running controller that claims it
  for (size_t k = 0; k < joints_.size(); ++k) modes_[k] = -1;
  for (auto& l : loaded_) {
    if (!l.running) continue;
    for (const auto& [iface, js] : l.controller->claimed())
      for (const auto& jn : js)
        for (size_t k = 0; k < joints_.size(); ++k)
          if (joints_[k].name == jn) {
            Interface i = Interface::Effort;
            for (Interface c : {Interface::Position, Interface::Velocity, Interface::Effort})
              if (iface == to_string(c)) i = c;
            modes_[k] = static_cast<int>(i);
          }
  }
  return true;
}

void RosControl::dynamic_ports(std::vector<InputPort>* inputs, std::vector<OutputPort>* outputs) const {
  for (const auto& l : loaded_) l.controller->ports(l.name, ns_, join_ns(ns_, l.name), inputs, outputs);
}

void RosControl::command(const std::string& port, const Command& value, CommandResult* result) {
  // "<controller>/<leaf>"
  const size_t slash = port.rfind('/');
  const std::string name = port.substr(0, slash), leaf = port.substr(slash + 1);
  for (auto& l : loaded_) {
    if (l.name != name) continue;
    // a stopped controller takes no command (its action rejects goals: upstream's isRunning checks)
    if (!l.running) {
      if (std::holds_alternative<TrajectoryGoal>(value) && !std::get<TrajectoryGoal>(value).cancel) {
        result->refused = true;
        result->code = -1;  // INVALID_GOAL
        result->reason = "controller '" + name + "' is not running";
      }
      return;
    }
    // a goal is answered now (the trajectory controller keeps it for its first update); a command waits for it
    if (l.starting_due && !std::holds_alternative<TrajectoryGoal>(value)) {
      l.held.emplace_back(leaf, value);
      return;
    }
    const size_t first = result->notes.size();
    l.controller->command(leaf, value, now_, result);
    for (size_t k = first; k < result->notes.size(); ++k)
      result->notes[k].text = "controller '" + name + "': " + result->notes[k].text;
    return;
  }
}

CallResponse RosControl::call(const std::string& service, const CallRequest& rq) {
  CallResponse r;
  auto fail = [&r](const std::string& why) {
    r.ok = false;
    r.errors.push_back("controller_manager: " + why);
    return r;
  };
  if (service == "pid_gains") {
    set_pid_gains(rq.params, &r);
  } else if (service == "load_controller") {
    const std::string pns = join_ns(ns_, rq.name);
    const auto t = rq.params.find("type");
    if (t == rq.params.end() || t->second.size() != 1)
      return fail("could not load controller '" + rq.name + "': " + pns + "/type: missing (required key)");
    try {
      load(rq.name, t->second[0], rq.params);
    } catch (const std::exception& e) {
      return fail("could not load controller: " + std::string(e.what()) + " (parameters at " + pns + ")");
    }
    r.infos.push_back("controller_manager: loaded '" + rq.name + "' (" + t->second[0] + ")");
    r.ports_changed = true;
  } else if (service == "unload_controller") {
    try {
      unload(rq.name);
    } catch (const std::exception& e) {
      return fail("could not unload: " + std::string(e.what()));
    }
    r.infos.push_back("controller_manager: unloaded '" + rq.name + "'");
    r.ports_changed = true;
  } else if (service == "switch_controller") {
    if (rq.strictness != 1 && rq.strictness != 2)
      return fail("switch_controller: strictness " + std::to_string(rq.strictness) +
                  " is neither BEST_EFFORT (1) nor STRICT (2)");
    std::string why;
    if (!switch_controllers(rq.start, rq.stop, rq.strictness == 2, &why)) return fail("switch_controller refused: " + why);
  } else if (service == "list_controllers") {
    for (const auto& l : loaded_)
      r.controllers.push_back({l.name, l.type, l.running ? "running" : "stopped", l.controller->claimed()});
  } else if (service == "list_controller_types") {
    for (const auto& t : control::controller_types()) r.types.emplace_back(t.name, t.base_class);
  } else if (service == "reload_controller_libraries") {
    // car's controller types are built in: nothing to reload; upstream refuses while controllers are loaded
    if (!loaded_.empty() && !rq.force_kill)
      return fail("reload_controller_libraries: controllers are loaded (force_kill false)");
    std::vector<std::string> names;
    for (const auto& l : loaded_) names.push_back(l.name);
    std::string why;
    switch_controllers({}, names, false, &why);
    for (const auto& n : names) {
      unload(n);
      r.infos.push_back("controller_manager: unloaded '" + n + "'");
    }
    r.ports_changed = !names.empty();
  } else {
    return fail("no service '" + service + "'");
  }
  return r;
}

const PluginKind& ros_control_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "ros_control";
    k.filenames = {"libgazebo_ros_control.so"};
    k.namespace_rule = NamespaceRule::AbsentIsModel;  // gazebo_ros_control_plugin.cpp: absent -> the model's name
    k.schema = {
        {"robotNamespace", T, "", ""},
        {"controlPeriod", N, "0", "s"},
        {"robotSimType", T, kDefaultSimType, ""},
        {"legacyModeNS", B, "true", ""},
    };
    k.ignored = {{"robotParam", "car reads the robot it spawned, not robot_description"},
                 {"eStopTopic", "not simulated"}};
    k.finish = finish;
    // controller_manager's services under <ns>/controller_manager/, and the pid_gains call
    k.services = [](const PluginConfig& c, const std::string& robot) {
      const std::string ns = control_ns(c, robot), cm = join_ns(ns, "controller_manager");
      std::vector<ServicePort> out;
      using C = CallType;
      for (const auto& [name, type] : std::vector<std::pair<std::string, C>>{
               {"load_controller", C::LoadController},
               {"unload_controller", C::UnloadController},
               {"switch_controller", C::SwitchController},
               {"list_controllers", C::ListControllers},
               {"list_controller_types", C::ListControllerTypes},
               {"reload_controller_libraries", C::ReloadControllerLibraries}})
        out.push_back({name, type, cm + "/" + name, ns.empty() ? "" : "/" + ns});
      // DefaultRobotHWSim's gains, read once from <ns>/gazebo_ros_control/pid_gains
      out.push_back({"pid_gains", C::SetParameters, "", join_ns(ns, "gazebo_ros_control/pid_gains")});
      return out;
    };
    k.make = [](const PluginConfig& c, const std::string& robot, uint64_t) -> std::unique_ptr<Plugin> {
      return std::make_unique<RosControl>(c, robot);
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
