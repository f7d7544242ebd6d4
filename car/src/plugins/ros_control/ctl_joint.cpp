// joint_state_controller, the forward command controllers ({position,velocity,effort}_controllers/Joint*Controller
// and JointGroup*Controller) and the PID ones (effort_controllers/JointPositionController, JointVelocityController).
#include <algorithm>
#include <cmath>

#include "controllers.hpp"

namespace car_sim {
namespace control {

InputPort controller_input(const std::string& name, const std::string& leaf, InputType type, const std::string& topic,
                           uint32_t queue) {
  InputPort p;
  p.name = name + "/" + leaf;
  p.type = type;
  p.topic = topic;
  p.queue = queue;
  return p;
}

OutputPort controller_output(const std::string& name, const std::string& leaf, SampleType type,
                             const std::string& topic, uint32_t queue) {
  OutputPort p;
  p.name = name + "/" + leaf;
  p.type = type;
  p.topic = topic;
  p.queue = queue;
  p.frame_rule = FrameRule::AsWritten;
  return p;
}

void JointStatesOutput::visit(FieldVisitor& v) const {
  std::string n;
  std::vector<double> position, velocity;
  for (const auto& j : joints) {
    n += (n.empty() ? "" : ",") + j.name;
    position.push_back(j.position);
    velocity.push_back(j.velocity);
  }
  v.text("controller", controller);
  v.text("names", n);
  v.vector("position", position.data(), position.size());
  v.vector("velocity", velocity.data(), velocity.size());
  v.vector("effort", effort.data(), effort.size());
}

void CommandController::ports(const std::string& name, const std::string&, const std::string& ns,
                              std::vector<InputPort>* in, std::vector<OutputPort>*) const {
  in->push_back(controller_input(name, "command", group() ? InputType::Float64Array : InputType::Float64,
                                 ns + "/command", 1));
}

void CommandController::command(const std::string&, const Command& value, double, CommandResult* r) {
  const std::vector<double> v =
      std::holds_alternative<Float64>(value) ? std::vector<double>{std::get<Float64>(value).data}
                                             : std::get<Float64Array>(value).data;
  std::string why;
  if (!set_command(v, &why)) r->notes.push_back({true, why});
}

void JointControllerStateOutput::visit(FieldVisitor& v) const {
  v.text("controller", controller);
  v.number("set_point", set_point);
  v.number("process_value", process_value);
  v.number("error", error);
  v.number("command", command);
}

namespace {

// A publish_rate schedule on sim time, as realtime_tools' loops: publish when time >= last + 1/rate.
struct RateGate {
  double rate = 0, last = -1e300;
  bool due(double t) {
    if (rate <= 0) return false;
    if (t < last + 1.0 / rate - 1e-9) return false;
    last = t;
    return true;
  }
};

class JointStateCtl : public Controller {
 public:
  void configure(const ParamReader& r, Hardware& hw) override {
    name_ = r.controller();
    gate_.rate = r.number("publish_rate");
    if (gate_.rate <= 0) r.fail("publish_rate", "must be > 0");
    hw_ = &hw;
    // every joint with a transmission (the JointStateInterface), in model order
    for (const auto& t : hw.model().transmissions)
      for (const auto& e : t.joints) {
        if (std::find(names_.begin(), names_.end(), e.joint) != names_.end()) continue;
        names_.push_back(e.joint);
      }
    for (const auto& n : names_) {
      Interface any = Interface::Position;
      JointIo* j = nullptr;
      for (Interface i : {Interface::Position, Interface::Velocity, Interface::Effort}) {
        try {
          j = &hw.claim(name_, "", n, i);
          any = i;
          break;
        } catch (const ControllerError&) {
        }
      }
      (void)any;
      if (j) joints_.push_back(j);
    }
    if (r.has("extra_joints")) r.fail("extra_joints", "not supported by car (joints without a transmission)");
  }
  void starting(const ControlTime& t) override { gate_.last = t.time - 1.0 / gate_.rate; }
  void update(const ControlTime&) override {}
  void publish(const ControlTime& t, OutputQueue* out) override {
    if (!gate_.due(t.time)) return;
    auto o = std::make_unique<JointStatesOutput>();
    o->controller = name_;
    o->port = name_ + "/joint_states";
    o->type = "joint_state_controller/JointStateController";
    for (const JointIo* j : joints_) {
      o->joints.push_back({j->name, j->position, j->velocity});
      o->effort.push_back(j->effort);
    }
    out->push_back(std::move(o));
  }
  std::vector<std::pair<std::string, std::vector<std::string>>> claimed() const override { return {}; }
  // joint_states in the robot's namespace, queue 10 (as joint_state_controller)
  void ports(const std::string& name, const std::string& robot_ns, const std::string&, std::vector<InputPort>*,
             std::vector<OutputPort>* out) const override {
    OutputPort p = controller_output(name, "joint_states", sample_type<JointStatesSample>(),
                                     robot_ns.empty() ? "/joint_states" : "/" + robot_ns + "/joint_states", 10);
    p.with_effort = true;
    out->push_back(p);
  }

 private:
  std::string name_;
  RateGate gate_;
  Hardware* hw_ = nullptr;
  std::vector<std::string> names_;
  std::vector<JointIo*> joints_;
};

// forward_command_controller: the command goes to the joint unchanged (`joint` or `joints`).
class ForwardCtl : public CommandController {
 public:
  ForwardCtl(Interface i, bool group) : iface_(i), group_(group) {}
  void configure(const ParamReader& r, Hardware& hw) override {
    const std::string key = group_ ? "joints" : "joint";
    names_ = group_ ? r.list(key) : std::vector<std::string>{r.text(key)};
    if (names_.empty()) r.fail(key, "no joints given");
    for (const auto& n : names_) joints_.push_back(&hw.claim(r.controller(), key, n, iface_));
    cmd_.assign(names_.size(), 0.0);
  }
  void starting(const ControlTime&) override {
    // position: hold where the joint is; velocity and effort: 0 (as upstream's starting())
    for (size_t k = 0; k < joints_.size(); ++k) cmd_[k] = iface_ == Interface::Position ? joints_[k]->position : 0.0;
  }
  void update(const ControlTime&) override {
    for (size_t k = 0; k < joints_.size(); ++k) {
      if (iface_ == Interface::Position) joints_[k]->cmd_position = cmd_[k];
      if (iface_ == Interface::Velocity) joints_[k]->cmd_velocity = cmd_[k];
      if (iface_ == Interface::Effort) joints_[k]->cmd_effort = cmd_[k];
    }
  }
  bool set_command(const std::vector<double>& v, std::string* why) override {
    if (v.size() != cmd_.size()) {
      *why = "command has " + std::to_string(v.size()) + " values for " + std::to_string(cmd_.size()) + " joints";
      return false;
    }
    for (double x : v)
      if (!std::isfinite(x)) {
        *why = "command has a non-finite value";
        return false;
      }
    cmd_ = v;
    return true;
  }
  std::vector<std::string> joints() const override { return names_; }
  bool group() const override { return group_; }
  std::vector<std::pair<std::string, std::vector<std::string>>> claimed() const override {
    return {{to_string(iface_), names_}};
  }

 private:
  Interface iface_;
  bool group_;
  std::vector<std::string> names_;
  std::vector<JointIo*> joints_;
  std::vector<double> cmd_;
};

// effort_controllers/JointPositionController (velocity = false) and JointVelocityController: effort = PID.
class PidCtl : public CommandController {
 public:
  explicit PidCtl(bool velocity) : velocity_(velocity) {}
  void configure(const ParamReader& r, Hardware& hw) override {
    name_ = r.controller();
    joint_name_ = r.text("joint");
    joint_ = &hw.claim(name_, "joint", joint_name_, Interface::Effort);
    pid_ = Pid::from(r, "pid");
  }
  void starting(const ControlTime&) override {
    // position: hold the current position (as upstream); velocity: 0
    set_point_ = velocity_ ? 0.0 : joint_->position;
    pid_.reset();
  }
  void update(const ControlTime& t) override {
    double error, error_dot;
    if (velocity_) {
      error = set_point_ - joint_->velocity;
      error_dot = 0.0;
    } else {
      error = set_point_ - joint_->position;
      if (joint_->joint && joint_->joint->type == JointType::Continuous)
        error = std::remainder(error, 2.0 * M_PI);  // shortest angular distance
      error_dot = -joint_->velocity;                // commanded velocity 0
    }
    dt_ = t.period;
    command_ = pid_.compute(error, error_dot, t.period);
    joint_->cmd_effort = command_;
    error_ = error;
    ++loops_;
  }
  void publish(const ControlTime& t, OutputQueue* out) override {
    // upstream publishes its state every 10th update
    if (loops_ == last_published_ || loops_ % 10 != 0) return;
    last_published_ = loops_;
    auto o = std::make_unique<JointControllerStateOutput>();
    o->controller = name_;
    o->port = name_ + "/state";
    o->type = velocity_ ? "effort_controllers/JointVelocityController" : "effort_controllers/JointPositionController";
    o->set_point = set_point_;
    o->process_value = velocity_ ? joint_->velocity : joint_->position;
    o->process_value_dot = joint_->velocity;
    o->error = error_;
    o->time_step = dt_;
    o->command = command_;
    o->p = pid_.p;
    o->i = pid_.i;
    o->d = pid_.d;
    o->i_clamp = pid_.i_max;
    o->antiwindup = pid_.antiwindup;
    out->push_back(std::move(o));
  }
  bool set_command(const std::vector<double>& v, std::string* why) override {
    if (v.size() != 1 || !std::isfinite(v[0])) {
      *why = "command must be one finite value";
      return false;
    }
    set_point_ = v[0];
    if (!velocity_ && joint_->joint && joint_->joint->limits && joint_->joint->type != JointType::Continuous &&
        joint_->joint->limits->lower < joint_->joint->limits->upper)
      set_point_ = std::clamp(set_point_, joint_->joint->limits->lower, joint_->joint->limits->upper);
    return true;
  }
  std::vector<std::string> joints() const override { return {joint_name_}; }
  std::vector<std::pair<std::string, std::vector<std::string>>> claimed() const override {
    return {{to_string(Interface::Effort), {joint_name_}}};
  }
  // command, and its state (control_msgs/JointControllerState, queue 1)
  void ports(const std::string& name, const std::string& robot_ns, const std::string& ns, std::vector<InputPort>* in,
             std::vector<OutputPort>* out) const override {
    CommandController::ports(name, robot_ns, ns, in, out);
    out->push_back(controller_output(name, "state", sample_type<ControllerStateSample>(), ns + "/state", 1));
  }

 private:
  bool velocity_;
  std::string name_, joint_name_;
  JointIo* joint_ = nullptr;
  Pid pid_;
  double set_point_ = 0, command_ = 0, error_ = 0, dt_ = 0;
  uint64_t loops_ = 0, last_published_ = 0;
};

}  // namespace

std::unique_ptr<Controller> make_joint_state_controller() { return std::make_unique<JointStateCtl>(); }
std::unique_ptr<Controller> make_forward_controller(Interface i, bool group) {
  return std::make_unique<ForwardCtl>(i, group);
}
std::unique_ptr<Controller> make_pid_controller(bool velocity) { return std::make_unique<PidCtl>(velocity); }

}  // namespace control
}  // namespace car_sim
