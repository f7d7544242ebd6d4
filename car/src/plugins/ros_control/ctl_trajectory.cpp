// {position,velocity,effort}_controllers/JointTrajectoryController (ros_controllers Noetic): splines through the
// points (linear: positions only, cubic: + velocities, quintic: + accelerations), constraints, the goal's end
// (docs/COMPAT-control.md).
#include <algorithm>
#include <cmath>
#include <optional>
#include <tuple>

#include "controllers.hpp"

namespace car_sim {
namespace control {

void TrajectoryStateOutput::visit(FieldVisitor& v) const {
  v.text("controller", controller);
  v.vector("desired_position", desired_position.data(), desired_position.size());
  v.vector("actual_position", actual_position.data(), actual_position.size());
}

void TrajectoryResultOutput::finish() {
  using S = GoalResultSample::Status;
  sample.goal = goal;
  sample.status = error_code == 0 ? S::Succeeded : error_code == -6 ? S::Canceled : S::Aborted;
  sample.error_code = error_code == -6 ? 0 : error_code;
  sample.error_string = error_string;
}

// trajectory_msgs/JointTrajectory (the command topic, an action goal's trajectory) -> a goal
static TrajGoal to_goal(const JointTrajectory& m) {
  TrajGoal g;
  g.joint_names = m.joint_names;
  g.start_time = m.start;
  for (const auto& p : m.points) g.points.push_back({p.positions, p.velocities, p.accelerations, p.time_from_start});
  return g;
}

void TrajectoryController::ports(const std::string& name, const std::string&, const std::string& ns,
                                 std::vector<InputPort>* in, std::vector<OutputPort>* out) const {
  out->push_back(controller_output(name, "state", sample_type<TrajectoryStateSample>(), ns + "/state", 1));
  in->push_back(controller_input(name, "command", InputType::JointTrajectory, ns + "/command", 1));
  // the action under <ns>/follow_joint_trajectory: goals and cancels in, results out
  in->push_back(controller_input(name, "follow_joint_trajectory", InputType::TrajectoryGoal,
                                 ns + "/follow_joint_trajectory", 1));
  out->push_back(controller_output(name, "follow_joint_trajectory", sample_type<GoalResultSample>(),
                                   ns + "/follow_joint_trajectory", 1));
}

void TrajectoryController::command(const std::string& leaf, const Command& value, double now, CommandResult* r) {
  std::string why;
  int code = 0;
  if (const auto* t = std::get_if<JointTrajectory>(&value)) {
    // the command topic: a new trajectory with no goal to answer
    if (!set_trajectory(to_goal(*t), 0, now, &why, &code)) r->notes.push_back({true, "trajectory refused: " + why});
    return;
  }
  const TrajectoryGoal& goal = std::get<TrajectoryGoal>(value);
  if (goal.cancel) {
    cancel(goal.id, now);
    return;
  }
  TrajGoal g = to_goal(goal.trajectory);
  g.path_position = goal.path_position;
  g.goal_position = goal.goal_position;
  g.goal_time_tolerance = goal.goal_time_tolerance;
  // an active goal is replaced: it ends as canceled (upstream: preempted)
  if (!set_trajectory(g, goal.id, now, &why, &code)) {
    r->refused = true;
    r->code = code;
    r->reason = why;
  }
}

void TrajectoryResultOutput::visit(FieldVisitor& v) const {
  v.text("controller", controller);
  v.integer("goal", static_cast<int64_t>(goal));
  v.integer("error_code", error_code);
  v.text("error_string", error_string);
}

namespace {

// One joint's segment between two states (position, velocity, acceleration) over [t0, t1].
struct Segment {
  double t0 = 0, t1 = 0;
  double c[6] = {0};  // position polynomial in (t - t0)
  void make(double t0_, double t1_, double p0, double v0, double a0, double p1, double v1, double a1, int order) {
    t0 = t0_;
    t1 = t1_;
    const double T = t1 - t0;
    std::fill(c, c + 6, 0.0);
    c[0] = p0;
    if (T <= 0) return;
    if (order == 1) {
      c[1] = (p1 - p0) / T;
    } else if (order == 3) {
      c[1] = v0;
      c[2] = (3 * (p1 - p0) - (2 * v0 + v1) * T) / (T * T);
      c[3] = (2 * (p0 - p1) + (v0 + v1) * T) / (T * T * T);
    } else {
      const double T2 = T * T, T3 = T2 * T, T4 = T3 * T, T5 = T4 * T;
      c[1] = v0;
      c[2] = a0 / 2;
      c[3] = (20 * p1 - 20 * p0 - (8 * v1 + 12 * v0) * T - (3 * a0 - a1) * T2) / (2 * T3);
      c[4] = (30 * p0 - 30 * p1 + (14 * v1 + 16 * v0) * T + (3 * a0 - 2 * a1) * T2) / (2 * T4);
      c[5] = (12 * p1 - 12 * p0 - (6 * v1 + 6 * v0) * T - (a0 - a1) * T2) / (2 * T5);
    }
  }
  void sample(double t, double* p, double* v) const {
    double s = std::clamp(t - t0, 0.0, std::max(0.0, t1 - t0));
    *p = c[0] + s * (c[1] + s * (c[2] + s * (c[3] + s * (c[4] + s * c[5]))));
    *v = t > t1 ? 0.0 : c[1] + s * (2 * c[2] + s * (3 * c[3] + s * (4 * c[4] + s * 5 * c[5])));
    if (t > t1 && t1 <= t0) *v = 0.0;
  }
};

class TrajectoryCtl : public TrajectoryController {
 public:
  explicit TrajectoryCtl(Interface i) : iface_(i) {}

  void configure(const ParamReader& r, Hardware& hw) override {
    name_ = r.controller();
    names_ = r.list("joints");
    if (names_.empty()) r.fail("joints", "no joints given");
    for (const auto& n : names_) joints_.push_back(&hw.claim(name_, "joints", n, iface_));
    const size_t n = names_.size();
    goal_time_ = r.number("constraints/goal_time", 0.0);
    stopped_velocity_ = r.number("constraints/stopped_velocity_tolerance", 0.01);
    path_tol_.assign(n, 0.0);
    goal_tol_.assign(n, 0.0);
    for (size_t k = 0; k < n; ++k) {
      path_tol_[k] = r.number("constraints/" + names_[k] + "/trajectory", 0.0);
      goal_tol_[k] = r.number("constraints/" + names_[k] + "/goal", 0.0);
    }
    stop_duration_ = std::max(0.0, r.number("stop_trajectory_duration", 0.0));
    state_rate_ = r.number("state_publish_rate", 50.0);
    allow_partial_ = r.flag("allow_partial_joints_goal", false);
    if (iface_ != Interface::Position) {
      for (const auto& j : names_) {
        if (!r.has("gains/" + j + "/p"))
          r.fail("gains/" + j + "/p", "missing (a velocity or effort trajectory controller needs PID gains per joint)");
        pids_.push_back(Pid::from(r, "gains/" + j));
        ff_.push_back(r.number("velocity_ff/" + j, 0.0));
      }
    }
    segs_.assign(n, Segment());
  }

  void starting(const ControlTime& t) override {
    for (auto& p : pids_) p.reset();
    hold(t.time, false);
    last_state_ = t.time - (state_rate_ > 0 ? 1.0 / state_rate_ : 0.0);
    started_ = true;
    // a goal taken between the switch and this first update (the world paused) runs on its own clock (taken at
    // `at`), from where the joints are here
    if (early_) {
      const auto [g, id, at] = *early_;
      early_.reset();
      goal_ = 0;
      std::string why;
      int code = 0;
      set_trajectory(g, id, at, &why, &code);
    }
  }

  void stopping(const ControlTime& t) override {
    started_ = false;
    if (goal_) finish(TrajectoryResultOutput{}, -6, "controller stopped");  // preempted: the action answers it
  }

  void update(const ControlTime& t) override {
    now_ = t.time;
    const size_t n = joints_.size();
    desired_p_.resize(n);
    desired_v_.resize(n);
    bool path_violated = false;
    std::string which;
    for (size_t k = 0; k < n; ++k) {
      const auto& segs = traj_[k];
      const Segment* s = &segs.back();
      for (const auto& sg : segs)
        if (t.time <= sg.t1) {
          s = &sg;
          break;
        }
      s->sample(t.time, &desired_p_[k], &desired_v_[k]);
      const double err = desired_p_[k] - joints_[k]->position;
      const double err_dot = desired_v_[k] - joints_[k]->velocity;
      const auto po = path_tol_goal_.find(names_[k]);
      const double path_tol = po != path_tol_goal_.end() ? po->second : path_tol_[k];
      if (goal_ && t.time < end_time_ && path_tol > 0 && std::abs(err) > path_tol) {
        path_violated = true;
        which = names_[k];
      }
      switch (iface_) {
        case Interface::Position: joints_[k]->cmd_position = desired_p_[k]; break;
        case Interface::Velocity:
          joints_[k]->cmd_velocity = ff_[k] * desired_v_[k] + pids_[k].compute(err, err_dot, t.period);
          break;
        case Interface::Effort: joints_[k]->cmd_effort = pids_[k].compute(err, err_dot, t.period); break;
      }
    }
    if (!goal_) return;
    if (path_violated) {
      finish_and_hold(t.time, -4, "path tolerance violated at joint '" + which + "'");
      return;
    }
    if (t.time < end_time_) return;
    bool inside = true;
    for (size_t k = 0; k < n; ++k) {
      const double tol = goal_tol_of(k);
      if (tol > 0 && std::abs(desired_p_[k] - joints_[k]->position) > tol) inside = false;
      if (stopped_velocity_ > 0 && std::abs(joints_[k]->velocity) > stopped_velocity_) inside = false;
    }
    if (inside) {
      result(0, "");
    } else if (t.time >= end_time_ + goal_time_of()) {
      finish_and_hold(t.time, -5, "goal tolerance violated " + std::to_string(t.time - end_time_) + " s after the end");
    }
  }

  void publish(const ControlTime& t, OutputQueue* out) override {
    for (auto& r : results_) {
      r.finish();
      out->push_back(std::make_unique<TrajectoryResultOutput>(r));
    }
    results_.clear();
    if (state_rate_ <= 0 || t.time < last_state_ + 1.0 / state_rate_ - 1e-9 || desired_p_.empty()) return;
    last_state_ = t.time;
    auto o = std::make_unique<TrajectoryStateOutput>();
    o->controller = name_;
    o->port = name_ + "/state";
    o->type = type_name();
    o->joints = names_;
    o->desired_position = desired_p_;
    o->desired_velocity = desired_v_;
    for (const JointIo* j : joints_) {
      o->actual_position.push_back(j->position);
      o->actual_velocity.push_back(j->velocity);
    }
    out->push_back(std::move(o));
  }

  bool set_trajectory(const TrajGoal& g, uint64_t goal_id, double now, std::string* why, int* code) override {
    const size_t n = names_.size();
    // joint order of the message -> ours
    std::vector<int> idx(n, -1);
    for (size_t m = 0; m < g.joint_names.size(); ++m) {
      const auto it = std::find(names_.begin(), names_.end(), g.joint_names[m]);
      if (it == names_.end()) {
        *why = "joint '" + g.joint_names[m] + "' is not one of the controller's joints";
        *code = -2;
        return false;
      }
      idx[it - names_.begin()] = static_cast<int>(m);
    }
    if (g.joint_names.size() != n && !allow_partial_) {
      *why = "the goal names " + std::to_string(g.joint_names.size()) + " of " + std::to_string(n) +
             " joints and allow_partial_joints_goal is false";
      *code = -2;
      return false;
    }
    const double start = g.start_time > 0 ? g.start_time : now;
    for (const auto& p : g.points) {
      if (p.positions.size() != g.joint_names.size()) {
        *why = "a point has " + std::to_string(p.positions.size()) + " positions for " +
               std::to_string(g.joint_names.size()) + " joints";
        *code = -1;
        return false;
      }
      for (double x : p.positions)
        if (!std::isfinite(x)) {
          *why = "a point has a non-finite position";
          *code = -1;
          return false;
        }
    }
    if (!started_) {
      // checked and taken; it runs from the first update (starting), from where the joints are then
      if (early_) finish(TrajectoryResultOutput{}, -6, "replaced by a new goal");
      early_ = std::make_tuple(g, goal_id, now);
      goal_ = goal_id;
      return true;
    }
    if (goal_) finish(TrajectoryResultOutput{}, -6, "replaced by a new goal");
    // the current desired state, from which the new trajectory starts
    std::vector<double> p0(n), v0(n, 0.0);
    for (size_t k = 0; k < n; ++k) {
      double p, v;
      if (!desired_p_.empty()) {
        p = desired_p_[k];
        v = desired_v_[k];
      } else {
        p = joints_[k]->position;
        v = 0;
      }
      p0[k] = p;
      v0[k] = v;
    }
    double end = now;
    traj_.resize(n);
    path_tol_goal_.clear();
    for (size_t k = 0; k < n; ++k) {
      std::vector<Segment> segs;
      double tp = now, pp = p0[k], vp = v0[k], ap = 0;
      if (idx[k] >= 0) {
        for (const auto& pt : g.points) {
          const double ti = start + pt.time_from_start;
          if (ti <= now) continue;  // points in the past are skipped
          const int m = idx[k];
          const double p = pt.positions[m];
          const bool hv = pt.velocities.size() == g.joint_names.size();
          const bool ha = hv && pt.accelerations.size() == g.joint_names.size();
          const double v = hv ? pt.velocities[m] : 0.0, a = ha ? pt.accelerations[m] : 0.0;
          Segment s;
          s.make(tp, ti, pp, hv ? vp : 0.0, ha ? ap : 0.0, p, v, a, ha ? 5 : hv ? 3 : 1);
          segs.push_back(s);
          tp = ti;
          pp = p;
          vp = v;
          ap = a;
        }
      }
      if (segs.empty()) {
        Segment s;
        s.make(now, now, p0[k], 0, 0, p0[k], 0, 0, 1);
        segs.push_back(s);
      }
      end = std::max(end, segs.back().t1);
      traj_[k] = segs;
    }
    end_time_ = end;
    goal_ = goal_id;
    goal_tol_override_ = g.goal_position;
    goal_time_override_ = g.goal_time_tolerance;
    for (size_t k = 0; k < n; ++k) {
      const auto it = g.path_position.find(names_[k]);
      if (it != g.path_position.end() && it->second != 0) path_tol_goal_[names_[k]] = it->second;
    }
    return true;
  }

  void cancel(uint64_t goal_id, double now) override {
    if (goal_ != goal_id || goal_id == 0) return;
    goal_ = 0;
    early_.reset();
    hold(now, true);
  }

  std::vector<std::string> joints() const override { return names_; }
  std::vector<std::pair<std::string, std::vector<std::string>>> claimed() const override {
    return {{to_string(iface_), names_}};
  }

 private:
  std::string type_name() const {
    const char* p = iface_ == Interface::Position ? "position" : iface_ == Interface::Velocity ? "velocity" : "effort";
    return std::string(p) + "_controllers/JointTrajectoryController";
  }
  double goal_tol_of(size_t k) const {
    const auto it = goal_tol_override_.find(names_[k]);
    return it != goal_tol_override_.end() && it->second != 0 ? it->second : goal_tol_[k];
  }
  double goal_time_of() const { return goal_time_override_ && *goal_time_override_ > 0 ? *goal_time_override_ : goal_time_; }

  // Holds the current position; with ramp, over stop_trajectory_duration from the current velocity (as upstream's
  // setHoldPosition).
  void hold(double now, bool ramp) {
    traj_.assign(joints_.size(), {});
    for (size_t k = 0; k < joints_.size(); ++k) {
      const double p = joints_[k]->position, v = ramp ? joints_[k]->velocity : 0.0;
      Segment s;
      if (ramp && stop_duration_ > 0)
        s.make(now, now + stop_duration_, p, v, 0, p + v * stop_duration_ / 2, 0, 0, 3);
      else
        s.make(now, now, p, 0, 0, p, 0, 0, 1);
      traj_[k] = {s};
    }
    desired_p_.clear();
    desired_v_.clear();
  }
  void result(int code, const std::string& why) {
    TrajectoryResultOutput r;
    finish(r, code, why);
  }
  void finish(TrajectoryResultOutput r, int code, const std::string& why) {
    r.controller = name_;
    r.port = name_ + "/follow_joint_trajectory";
    r.type = type_name();
    r.goal = goal_;
    r.error_code = code;
    r.error_string = why;
    if (goal_) results_.push_back(r);
    goal_ = 0;
  }
  void finish_and_hold(double now, int code, const std::string& why) {
    result(code, why);
    hold(now, true);
  }

  Interface iface_;
  std::string name_;
  std::vector<std::string> names_;
  std::vector<JointIo*> joints_;
  std::vector<Pid> pids_;
  std::vector<double> ff_, path_tol_, goal_tol_;
  std::map<std::string, double> goal_tol_override_, path_tol_goal_;
  std::optional<double> goal_time_override_;
  double goal_time_ = 0, stopped_velocity_ = 0.01, stop_duration_ = 0, state_rate_ = 50, last_state_ = 0;
  bool allow_partial_ = false;
  std::vector<Segment> segs_;
  std::vector<std::vector<Segment>> traj_;
  std::vector<double> desired_p_, desired_v_;
  uint64_t goal_ = 0;
  bool started_ = false;  // starting() called, stopping() not since
  std::optional<std::tuple<TrajGoal, uint64_t, double>> early_;  // a goal taken before starting(): id, time [s]
  double end_time_ = 0, now_ = 0;
  std::vector<TrajectoryResultOutput> results_;
};

}  // namespace

std::unique_ptr<Controller> make_trajectory_controller(Interface i) { return std::make_unique<TrajectoryCtl>(i); }

}  // namespace control
}  // namespace car_sim
