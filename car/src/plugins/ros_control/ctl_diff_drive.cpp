// diff_drive_controller/DiffDriveController (ros_controllers Noetic): wheels per side on the velocity interface,
// cmd_vel with a timeout and limits, odometry from the wheel positions (docs/COMPAT-control.md).
#include <algorithm>
#include <cmath>
#include <deque>

#include "controllers.hpp"

namespace car_sim {
namespace control {

void DiffDriveOdometryOutput::samples(SampleList& list) const {
  OdometrySample s;
  s.orientation = Eigen::Quaterniond(std::cos(heading / 2), 0, 0, std::sin(heading / 2));
  s.pose = Eigen::Translation3d(x, y, 0.0) * *s.orientation;
  s.linear = Eigen::Vector3d(linear, 0, 0);
  s.angular = Eigen::Vector3d(0, 0, angular);
  list.add(std::move(s));
}

void DiffDriveOdometryOutput::visit(FieldVisitor& v) const {
  v.text("controller", controller);
  const double p[3] = {x, y, heading};
  v.vector("pose", p, 3);
  v.number("linear", linear);
  v.number("angular", angular);
}

namespace {

// speed_limiter.cpp: clamp a velocity command, its change per period (acceleration) and jerk.
struct Limiter {
  bool has_v = false, has_a = false, has_j = false;
  double min_v = 0, max_v = 0, min_a = 0, max_a = 0, min_j = 0, max_j = 0;
  void read(const ParamReader& r, const std::string& p) {
    has_v = r.flag(p + "/has_velocity_limits", false);
    has_a = r.flag(p + "/has_acceleration_limits", false);
    has_j = r.flag(p + "/has_jerk_limits", false);
    max_v = r.number(p + "/max_velocity", 0.0);
    min_v = r.number(p + "/min_velocity", -max_v);
    max_a = r.number(p + "/max_acceleration", 0.0);
    min_a = r.number(p + "/min_acceleration", -max_a);
    max_j = r.number(p + "/max_jerk", 0.0);
    min_j = r.number(p + "/min_jerk", -max_j);
  }
  // v: command; v0, v1: the last two limited commands; dt [s]
  double limit(double v, double v0, double v1, double dt) const {
    if (has_v) v = std::clamp(v, min_v, max_v);
    if (has_a && dt > 0) v = std::clamp(v, v0 + min_a * dt, v0 + max_a * dt);
    if (has_j && dt > 0) {
      const double dv = v - v0, dv0 = v0 - v1;
      const double dv_j = std::clamp(dv - dv0, min_j * dt * dt, max_j * dt * dt);
      v = v0 + dv0 + dv_j;
    }
    return v;
  }
};

class DiffDriveCtl : public DiffDriveController {
 public:
  void configure(const ParamReader& r, Hardware& hw) override {
    name_ = r.controller();
    left_names_ = r.list("left_wheel");
    right_names_ = r.list("right_wheel");
    if (left_names_.empty()) r.fail("left_wheel", "no wheel joints given");
    if (right_names_.empty()) r.fail("right_wheel", "no wheel joints given");
    for (const auto& n : left_names_) left_.push_back(&hw.claim(name_, "left_wheel", n, Interface::Velocity));
    for (const auto& n : right_names_) right_.push_back(&hw.claim(name_, "right_wheel", n, Interface::Velocity));
    publish_rate_ = r.number("publish_rate", 50.0);
    cmd_vel_timeout_ = r.number("cmd_vel_timeout", 0.5);
    base_frame_ = r.text("base_frame_id", "base_link");
    odom_frame_ = r.text("odom_frame_id", "odom");
    enable_tf_ = r.flag("enable_odom_tf", true);
    open_loop_ = r.flag("open_loop", false);
    window_ = static_cast<size_t>(std::max(1.0, r.number("velocity_rolling_window_size", 10.0)));
    const double ws_mult = r.number("wheel_separation_multiplier", 1.0);
    const double wr_mult = r.number("wheel_radius_multiplier", 1.0);
    const double lr_mult = r.number("left_wheel_radius_multiplier", wr_mult);
    const double rr_mult = r.number("right_wheel_radius_multiplier", wr_mult);
    // wheel_separation and wheel_radius from the URDF when not given (as upstream's setOdomParamsFromUrdf: the
    // lateral distance between the first left and first right wheel joints, the first left wheel's collision
    // cylinder or sphere radius)
    const RobotModel& m = hw.model();
    if (r.has("wheel_separation")) {
      separation_ = r.number("wheel_separation");
    } else {
      const Joint* l = m.find_joint(left_names_[0]);
      const Joint* rr = m.find_joint(right_names_[0]);
      const Eigen::Vector3d pl = m.link_pose_in_root(l->child).translation();
      const Eigen::Vector3d pr = m.link_pose_in_root(rr->child).translation();
      separation_ = std::hypot(pl.x() - pr.x(), pl.y() - pr.y());
    }
    if (r.has("wheel_radius")) {
      radius_ = r.number("wheel_radius");
    } else {
      const Joint* l = m.find_joint(left_names_[0]);
      const Link* link = m.find_link(l->child);
      radius_ = 0;
      if (link)
        for (const auto& s : link->collisions)
          if (s.type == ShapeType::Cylinder || s.type == ShapeType::Sphere) {
            radius_ = s.radius;
            break;
          }
      if (radius_ <= 0)
        r.fail("wheel_radius", "not given and wheel link '" + l->child + "' has no collision cylinder or sphere");
    }
    if (separation_ <= 0) r.fail("wheel_separation", "must be > 0");
    if (radius_ <= 0) r.fail("wheel_radius", "must be > 0");
    separation_ *= ws_mult;
    left_radius_ = radius_ * lr_mult;
    right_radius_ = radius_ * rr_mult;
    linear_.read(r, "linear/x");
    angular_.read(r, "angular/z");
    for (const char* k : {"pose_covariance_diagonal", "twist_covariance_diagonal"}) {
      std::vector<double> c(6, 0.0);
      if (r.has(k)) {
        c = r.numbers(k);
        if (c.size() != 6) r.fail(k, "needs 6 values");
      }
      std::copy(c.begin(), c.end(), std::string(k) == "pose_covariance_diagonal" ? pose_cov_ : twist_cov_);
    }
  }

  void starting(const ControlTime& t) override {
    // as upstream: brake, and restart odometry's timers (the pose is kept)
    lin_cmd_ = ang_cmd_ = 0;
    cmd_time_ = -1e300;
    last_lin_[0] = last_lin_[1] = last_ang_[0] = last_ang_[1] = 0;
    have_wheels_ = false;
    last_pub_ = t.time - (publish_rate_ > 0 ? 1.0 / publish_rate_ : 0.0);
  }

  void stopping(const ControlTime&) override {
    for (JointIo* j : left_) j->cmd_velocity = 0;
    for (JointIo* j : right_) j->cmd_velocity = 0;
  }

  void set_twist(double linear, double angular, double time) override {
    if (!std::isfinite(linear) || !std::isfinite(angular)) return;
    lin_cmd_ = linear;
    ang_cmd_ = angular;
    cmd_time_ = time;
  }

  void update(const ControlTime& t) override {
    // odometry: mean wheel position per side [rad] times its radius [m]
    double lp = 0, rp = 0;
    for (const JointIo* j : left_) lp += j->position;
    for (const JointIo* j : right_) rp += j->position;
    lp = lp / left_.size() * left_radius_;
    rp = rp / right_.size() * right_radius_;
    double lin = last_lin_[0], ang = last_ang_[0];
    if (t.time - cmd_time_ > cmd_vel_timeout_) lin = ang = 0, lin_cmd_ = ang_cmd_ = 0;
    double dt = t.period;
    if (open_loop_) {
      integrate(lin * dt, ang * dt);
      push_velocity(lin * dt, ang * dt, dt);
    } else if (have_wheels_) {
      const double dl = lp - left_pos_, dr = rp - right_pos_;
      const double dlin = (dr + dl) * 0.5, dang = (dr - dl) / separation_;
      integrate(dlin, dang);
      push_velocity(dlin, dang, dt);
    }
    left_pos_ = lp;
    right_pos_ = rp;
    have_wheels_ = true;
    // command: the latest twist (0 after the timeout), limited
    double v = t.time - cmd_time_ > cmd_vel_timeout_ ? 0.0 : lin_cmd_;
    double w = t.time - cmd_time_ > cmd_vel_timeout_ ? 0.0 : ang_cmd_;
    v = linear_.limit(v, last_lin_[0], last_lin_[1], dt);
    w = angular_.limit(w, last_ang_[0], last_ang_[1], dt);
    last_lin_[1] = last_lin_[0];
    last_lin_[0] = v;
    last_ang_[1] = last_ang_[0];
    last_ang_[0] = w;
    // [rad/s] wheel speeds: (v -/+ w * separation / 2) / radius
    const double vl = (v - w * separation_ / 2.0) / left_radius_;
    const double vr = (v + w * separation_ / 2.0) / right_radius_;
    for (JointIo* j : left_) j->cmd_velocity = vl;
    for (JointIo* j : right_) j->cmd_velocity = vr;
  }

  void publish(const ControlTime& t, OutputQueue* out) override {
    if (publish_rate_ <= 0 || t.time < last_pub_ + 1.0 / publish_rate_ - 1e-9) return;
    last_pub_ = t.time;
    auto o = std::make_unique<DiffDriveOdometryOutput>();
    o->controller = name_;
    o->port = name_ + "/odom";
    o->type = "diff_drive_controller/DiffDriveController";
    o->x = x_;
    o->y = y_;
    o->heading = heading_;
    o->linear = vel_lin_;
    o->angular = vel_ang_;
    out->push_back(std::move(o));
  }

  // cmd_vel (linear.x, angular.z), odom (queue 100) with the transform odom -> base after it (enable_odom_tf)
  void ports(const std::string& name, const std::string&, const std::string& ns, std::vector<InputPort>* in,
             std::vector<OutputPort>* out) const override {
    InputPort c = controller_input(name, "cmd_vel", InputType::Twist, ns + "/cmd_vel", 1);
    c.axes = kLinearX | kAngularZ;
    in->push_back(c);
    OutputPort o = controller_output(name, "odom", sample_type<OdometrySample>(), ns + "/odom", 100);
    o.frame = odom_frame_;
    o.child_frame = base_frame_;
    o.tf = enable_tf_ ? TfOrder::After : TfOrder::None;
    std::copy(pose_cov_, pose_cov_ + 6, o.pose_covariance.begin());
    std::copy(twist_cov_, twist_cov_ + 6, o.twist_covariance.begin());
    out->push_back(o);
  }

  std::vector<std::pair<std::string, std::vector<std::string>>> claimed() const override {
    std::vector<std::string> all = left_names_;
    all.insert(all.end(), right_names_.begin(), right_names_.end());
    return {{to_string(Interface::Velocity), all}};
  }

 private:
  // odometry.cpp: second-order Runge-Kutta for small turns, the exact arc otherwise
  void integrate(double dlin, double dang) {
    if (std::abs(dang) < 1e-6) {
      const double h = heading_ + dang * 0.5;
      x_ += dlin * std::cos(h);
      y_ += dlin * std::sin(h);
      heading_ += dang;
    } else {
      const double h0 = heading_, r = dlin / dang;
      heading_ += dang;
      x_ += r * (std::sin(heading_) - std::sin(h0));
      y_ += -r * (std::cos(heading_) - std::cos(h0));
    }
  }
  // velocities: rolling mean over velocity_rolling_window_size updates
  void push_velocity(double dlin, double dang, double dt) {
    if (dt <= 0) return;
    lin_hist_.push_back(dlin / dt);
    ang_hist_.push_back(dang / dt);
    while (lin_hist_.size() > window_) lin_hist_.pop_front(), ang_hist_.pop_front();
    double sl = 0, sa = 0;
    for (double x : lin_hist_) sl += x;
    for (double x : ang_hist_) sa += x;
    vel_lin_ = sl / lin_hist_.size();
    vel_ang_ = sa / ang_hist_.size();
  }

  std::string name_, base_frame_, odom_frame_;
  std::vector<std::string> left_names_, right_names_;
  std::vector<JointIo*> left_, right_;
  double separation_ = 0, radius_ = 0, left_radius_ = 0, right_radius_ = 0;
  double publish_rate_ = 50, cmd_vel_timeout_ = 0.5, last_pub_ = 0;
  bool enable_tf_ = true, open_loop_ = false, have_wheels_ = false;
  size_t window_ = 10;
  Limiter linear_, angular_;
  double lin_cmd_ = 0, ang_cmd_ = 0, cmd_time_ = -1e300;
  double last_lin_[2] = {0, 0}, last_ang_[2] = {0, 0};
  double left_pos_ = 0, right_pos_ = 0;
  double x_ = 0, y_ = 0, heading_ = 0, vel_lin_ = 0, vel_ang_ = 0;
  std::deque<double> lin_hist_, ang_hist_;
  double pose_cov_[6] = {0}, twist_cov_[6] = {0};
};

}  // namespace

std::unique_ptr<Controller> make_diff_drive_controller() { return std::make_unique<DiffDriveCtl>(); }

}  // namespace control
}  // namespace car_sim
