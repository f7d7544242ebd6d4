// libgazebo_ros_planar_move.so (gazebo_plugins, Noetic): every step the base's velocity is set from the last
// command — linear (x cos yaw − y sin yaw, y cos yaw + x sin yaw, 0) world frame, angular (0, 0, rot) — and
// odometry (the true pose, finite-difference twist) goes out when more than 1/odometryRate has passed since the
// last (upstream's clock: every 51 ms at 20 Hz and 1 ms). Per docs/COMPAT-plugins.md.
#include "planar_move.hpp"

#include <cmath>

namespace car_sim {

Eigen::Vector2d planar_world_velocity(double vx, double vy, double yaw) {
  return Eigen::Vector2d(vx * std::cos(yaw) - vy * std::sin(yaw), vy * std::cos(yaw) + vx * std::sin(yaw));
}

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType Fr = ParamType::Frame;
constexpr ParamType N = ParamType::Number;

double yaw_of(const Eigen::Isometry3d& p) { return std::atan2(p.linear()(1, 0), p.linear()(0, 0)); }

class PlanarMove : public Plugin, public TwistDrive {
 public:
  explicit PlanarMove(const PluginConfig& c)
      : rate_(c.number("odometryRate")), timeout_(c.number("cmdTimeout")) {}

  // every step: the plug-in keeps upstream's odometry clock itself (post_physics)
  double update_rate() const override { return 0.0; }

  void set_twist(const Twist& cmd) override {
    vx_ = cmd.linear.x();
    vy_ = cmd.linear.y();
    rot_ = cmd.angular.z();
    cmd_fresh_ = true;
  }
  void command(const std::string&, const Command& value, CommandResult*) override { set_twist(std::get<Twist>(value)); }

  void reset() override {
    vx_ = vy_ = rot_ = 0.0;
    cmd_fresh_ = false;
    last_cmd_tick_ = 0;
    have_last_ = false;
  }

  void pre_physics(const StepContext& ctx, RobotHandle& robot) override {
    if (cmd_fresh_) {
      last_cmd_tick_ = ctx.tick;
      cmd_fresh_ = false;
    }
    // cmdTimeout [s] of sim time without a command: stop (upstream measures it in ROS time)
    if (timeout_ >= 0 && static_cast<double>(ctx.tick - last_cmd_tick_) * ctx.dt > timeout_) vx_ = vy_ = rot_ = 0.0;
    const ModelState s = robot.root_state();
    if (!have_last_) {
      // the load (or, car, a reset): odometry's clock and finite differences start from here
      last_pose_ = s.pose;
      last_ns_ = tick_time_ns(ctx.tick, ctx.dt);
      have_last_ = true;
    }
    const Eigen::Vector2d v = planar_world_velocity(vx_, vy_, yaw_of(s.pose));
    // Model::SetLinearVel sets each link's centre-of-mass velocity (ODELink: dBodySetLinearVel): the root turns
    // about its centre of mass, so its origin moves at v - w x (com - origin) [m/s], world frame
    const Eigen::Vector3d w(0.0, 0.0, rot_);
    const Link* root = robot.model().find_link(robot.model().root_link);
    const Eigen::Vector3d com_offset =
        s.pose.linear() * (root && root->inertial ? Eigen::Vector3d(root->inertial->origin.translation())
                                                  : Eigen::Vector3d::Zero());
    robot.set_root_velocity(Eigen::Vector3d(v.x(), v.y(), 0.0) - w.cross(com_offset), w);
  }

  // Upstream's UpdateChild at the sim time after this step: odometry when (t - last).Double() > 1 / odometryRate
  // (strictly), then last = t, so a period of whole steps goes out one step late each time (docs/COMPAT-plugins.md).
  void post_physics(const StepContext& ctx, const RobotHandle& robot, OutputQueue* out) override {
    if (rate_ <= 0) return;
    const int64_t t_ns = tick_time_ns(ctx.tick + 1, ctx.dt);
    // [s] upstream's seconds_since_last_update, also the divisor of its finite differences
    const double period = common_time_double(t_ns - last_ns_);
    if (!(period > 1.0 / rate_)) return;
    last_ns_ = t_ns;
    const Eigen::Isometry3d pose = robot.root_state().pose;
    auto o = std::make_unique<OdometryOut>();
    o->pose = pose;
    const Eigen::Vector3d d = (pose.translation() - last_pose_.translation()) / period;
    const double yaw = yaw_of(pose);
    double dyaw = yaw - yaw_of(last_pose_);
    while (dyaw < -M_PI) dyaw += 2 * M_PI;
    while (dyaw > M_PI) dyaw -= 2 * M_PI;
    const double wz = rot_ > M_PI / period ? rot_ : dyaw / period;
    o->linear = Eigen::Vector3d(std::cos(yaw) * d.x() + std::sin(yaw) * d.y(),
                                std::cos(yaw) * d.y() - std::sin(yaw) * d.x(), 0.0);
    o->angular = Eigen::Vector3d(0.0, 0.0, wz);
    out->push_back(std::move(o));
    last_pose_ = pose;
  }

 private:
  double rate_, timeout_;
  double vx_ = 0.0, vy_ = 0.0, rot_ = 0.0;  // [m/s], [m/s], [rad/s] body frame, last command
  bool cmd_fresh_ = false;                  // a command arrived since the last step
  uint64_t last_cmd_tick_ = 0;
  int64_t last_ns_ = 0;  // [ns] upstream's last_odom_publish_time_
  Eigen::Isometry3d last_pose_ = Eigen::Isometry3d::Identity();  // root pose at the last publication
  bool have_last_ = false;
};

void finish(ResolveContext& ctx) {
  const PluginConfig& c = ctx.config();
  if (c.number("odometryRate") < 0)
    ctx.warn(Severity::Warning, "key-value", "odometryRate",
             "<odometryRate> " + c.text("odometryRate") + " is not > 0: no odometry, as upstream");
}

}  // namespace

const PluginKind& planar_move_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "planar_move";
    k.filenames = {"libgazebo_ros_planar_move.so"};
    k.schema = {
        {"robotNamespace", T, "", ""},
        {"commandTopic", T, "cmd_vel", ""},
        {"odometryTopic", T, "odom", ""},
        {"odometryFrame", Fr, "odom", ""},
        {"robotBaseFrame", Fr, "base_footprint", ""},
        {"odometryRate", N, "20", "Hz"},
        {"cmdTimeout", N, "-1", "s"},
    };
    k.ignored = {{"alwaysOn", ""}, {"updateRate", "planar_move reads odometryRate, not updateRate"}};
    k.output_group = "odometry";
    k.finish = finish;
    k.inputs = topic_input("cmd_vel", InputType::Twist, "commandTopic", 1, kLinearX | kLinearY | kAngularZ);
    // odom with its TF sent first
    k.outputs = [](const PluginConfig& c, const std::string& robot, const Environment&) {
      OutputPort odom = odometry_port(c, robot, "odometryTopic", 1, TfOrder::Before);
      odom.planar_position = true;  // publishOdometry fills position x and y only; the TF carries z
      return std::vector<OutputPort>{odom};
    };
    k.make = [](const PluginConfig& c, const std::string&, uint64_t) -> std::unique_ptr<Plugin> {
      return std::make_unique<PlanarMove>(c);
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
