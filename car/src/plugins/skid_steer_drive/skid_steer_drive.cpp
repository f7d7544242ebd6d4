// libgazebo_ros_skid_steer_drive.so (gazebo_plugins, Noetic): at updateRate the wheel speed targets follow the
// last command (right = v + w sep/2, left = v − w sep/2, front and rear alike), each joint a velocity motor
// capped at `torque`; odometry (always the world pose and twist) at the same rate. Per docs/COMPAT-plugins.md.
#include "skid_steer_drive.hpp"

#include <algorithm>
#include <cmath>

#include "../common/drive.hpp"

namespace car_sim {

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType Fr = ParamType::Frame;
constexpr ParamType N = ParamType::Number;
constexpr ParamType F = ParamType::Flag;

// order of the wheels: left front, right front, left rear, right rear
const char* const kJointKeys[4] = {"leftFrontJoint", "rightFrontJoint", "leftRearJoint", "rightRearJoint"};

class SkidSteer : public Plugin, public TwistDrive {
 public:
  explicit SkidSteer(const PluginConfig& c)
      : rate_(c.number("updateRate")), separation_(c.number("wheelSeparation")),
        radius_(c.number("wheelDiameter") / 2.0), torque_(c.number("torque")) {
    for (int i = 0; i < 4; ++i) names_[i] = c.text(kJointKeys[i]);
  }

  double update_rate() const override { return rate_; }
  // gazebo_ros's UpdateChild rule (UpdateClock)
  Schedule schedule(double dt, uint64_t start_tick) const override {
    return Schedule::update_clock(rate_, dt, start_tick);
  }
  std::vector<std::string> driven_joints() const override { return {names_, names_ + 4}; }

  void configure(RobotHandle& robot) override {
    for (int i = 0; i < 4; ++i) {
      joint_[i] = robot.joint(names_[i]);
      motor_[i] = robot.add_motor(joint_[i], torque_);
    }
  }

  void set_twist(const Twist& cmd) override {
    cmd_v_ = cmd.linear.x();
    cmd_w_ = cmd.angular.z();
  }
  void command(const std::string&, const Command& value, CommandResult*) override { set_twist(std::get<Twist>(value)); }

  void reset() override {
    cmd_v_ = cmd_w_ = 0.0;
    for (int i = 0; i < 4; ++i) omega_[i] = q_ref_[i] = 0.0;
    update_due_ = false;
  }

  void pre_physics(const StepContext& ctx, RobotHandle& robot) override {
    if (update_due_) {
      update_due_ = false;
      double left = 0, right = 0;
      wheel_speeds(cmd_v_, cmd_w_, separation_, &left, &right);
      for (int i = 0; i < 4; ++i) omega_[i] = (i % 2 == 0 ? left : right) / radius_;
    }
    // velocity motors (ODE's, as upstream sets them) with the diff drive's anchor toward the integrated target angle
    // while the target is 0 (no creep at rest)
    constexpr double kAnchorWindow = 0.02;  // [rad]
    constexpr double kAnchorGain = 0.05;    // [-] fraction of the angle error corrected per step
    for (int i = 0; i < 4; ++i) {
      const double q = robot.joint_position(joint_[i]);
      q_ref_[i] = std::clamp(q_ref_[i] + omega_[i] * ctx.dt, q - kAnchorWindow, q + kAnchorWindow);
      robot.set_motor(motor_[i], {omega_[i], 1.0, q_ref_[i], omega_[i] == 0.0 ? kAnchorGain : 0.0});
    }
  }

  // Odometry from the world, as upstream: pose, twist rotated into the base by yaw, angular z.
  void post_physics(const StepContext&, const RobotHandle& robot, OutputQueue* out) override {
    update_due_ = true;
    const ModelState s = robot.root_state();
    auto o = std::make_unique<OdometryOut>();
    o->pose = s.pose;
    const double yaw = std::atan2(s.pose.linear()(1, 0), s.pose.linear()(0, 0));
    o->linear = Eigen::Vector3d(std::cos(yaw) * s.linear.x() + std::sin(yaw) * s.linear.y(),
                                std::cos(yaw) * s.linear.y() - std::sin(yaw) * s.linear.x(), 0.0);
    o->angular = Eigen::Vector3d(0.0, 0.0, s.angular.z());
    for (int i = 0; i < 4; ++i)
      o->joints.push_back({names_[i], robot.joint_position(joint_[i]), robot.joint_velocity(joint_[i])});
    out->push_back(std::move(o));
  }

 private:
  double rate_, separation_, radius_, torque_;
  std::string names_[4];
  int joint_[4] = {-1, -1, -1, -1};
  int motor_[4] = {-1, -1, -1, -1};
  double cmd_v_ = 0.0, cmd_w_ = 0.0;  // [m/s], [rad/s] last command
  double omega_[4] = {0, 0, 0, 0};    // [rad/s] motor targets
  double q_ref_[4] = {0, 0, 0, 0};    // [rad] integrated targets, anchored near the joints
  bool update_due_ = false;
};

void finish(ResolveContext& ctx) {
  const PluginConfig& c = ctx.config();
  for (const char* key : kJointKeys) {
    const std::string& jn = c.text(key);
    const Joint* j = ctx.model().find_joint(jn);
    if (!j) ctx.fail(key, "joint '" + jn + "' not found in the model (plug-in '" + c.name + "', " + c.filename + ")");
    if (j->type == JointType::Fixed) ctx.fail(key, "joint '" + jn + "' is fixed; a drive wheel needs a continuous joint");
  }
  check_wheel_length(ctx, "wheelSeparation");
  check_wheel_length(ctx, "wheelDiameter");
  if (c.number("torque") < 0) ctx.fail("torque", "must be >= 0");
  warn_negative_rate(ctx, "updateRate");
}

}  // namespace

const PluginKind& skid_steer_drive_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "skid_steer_drive";
    k.filenames = {"libgazebo_ros_skid_steer_drive.so"};
    k.schema = {
        {"robotNamespace", T, "", ""},
        {"broadcastTF", F, "false", ""},
        {"leftFrontJoint", T, "left_front_joint", ""},
        {"rightFrontJoint", T, "right_front_joint", ""},
        {"leftRearJoint", T, "left_rear_joint", ""},
        {"rightRearJoint", T, "right_rear_joint", ""},
        {"wheelSeparation", N, "0.4", "m"},
        {"wheelDiameter", N, "0.15", "m"},
        {"torque", N, "5", "N m"},
        {"commandTopic", T, "cmd_vel", ""},
        {"odometryTopic", T, "odom", ""},
        {"odometryFrame", Fr, "odom", ""},
        {"robotBaseFrame", Fr, "base_footprint", ""},
        {"updateRate", N, "100", "Hz"},
        {"covariance_x", N, "0.0001", ""},
        {"covariance_y", N, "0.0001", ""},
        {"covariance_yaw", N, "0.01", ""},
    };
    k.ignored = {{"alwaysOn", ""}};
    k.output_group = "odometry";
    k.finish = finish;
    k.inputs = topic_input("cmd_vel", InputType::Twist, "commandTopic", 1, kLinearX | kAngularZ);
    // odom with covariance_x/_y/_yaw on pose and twist; its TF, sent first, only with broadcastTF
    k.outputs = [](const PluginConfig& c, const std::string& robot, const Environment&) {
      OutputPort odom = odometry_port(c, robot, "odometryTopic", 1, c.flag("broadcastTF") ? TfOrder::Before : TfOrder::None,
                                      c.number("covariance_x"), c.number("covariance_y"), c.number("covariance_yaw"));
      odom.twist_covariance = odom.pose_covariance;
      odom.planar_position = true;  // publishOdometry fills position x and y only; the TF carries z
      return std::vector<OutputPort>{odom};
    };
    k.make = [](const PluginConfig& c, const std::string&, uint64_t) -> std::unique_ptr<Plugin> {
      return std::make_unique<SkidSteer>(c);
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
