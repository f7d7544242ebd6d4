// libgazebo_ros_diff_drive.so (gazebo_plugins, Noetic): two wheel joints driven as velocity motors capped at
// wheelTorque, the speed target ramped at wheelAcceleration, odometry from the world or the wheel encoders at
// updateRate. Behaviour per docs/COMPAT-spec.md.
#include "diff_drive.hpp"

#include <algorithm>
#include <cmath>

namespace car_sim {

DiffDriveConfig DiffDriveConfig::from(const PluginConfig& c, const std::string& model_name) {
  DiffDriveConfig d;
  d.plugin_name = c.name;
  d.robot_namespace = plugin_robot_namespace(c, model_name);
  d.command_topic = c.text("commandTopic");
  d.odometry_topic = c.text("odometryTopic");
  d.odometry_frame = c.text("odometryFrame");
  d.robot_base_frame = c.text("robotBaseFrame");
  d.wheel_separation = c.number("wheelSeparation");
  d.wheel_diameter = c.number("wheelDiameter");
  d.wheel_torque = c.number("wheelTorque");
  d.wheel_acceleration = c.number("wheelAcceleration");
  d.update_rate = c.number("updateRate");
  d.encoder_odometry = c.text("odometrySource") == "encoder";
  d.publish_tf = c.flag("publishTf");
  d.publish_odom_tf = c.flag("publishOdomTF");
  d.publish_wheel_tf = c.flag("publishWheelTF");
  d.publish_wheel_joint_state = c.flag("publishWheelJointState");
  d.left_joint = c.text("leftJoint");
  d.right_joint = c.text("rightJoint");
  d.ros_debug_level = c.text("rosDebugLevel");
  return d;
}


namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType Fr = ParamType::Frame;
constexpr ParamType N = ParamType::Number;
constexpr ParamType F = ParamType::Flag;

class DiffDrive : public Plugin, public TwistDrive {
 public:
  DiffDrive(const PluginConfig& c, const std::string& robot)
      : cfg_(DiffDriveConfig::from(c, robot)), clock_(cfg_.update_rate) {}

  double update_rate() const override { return cfg_.update_rate; }
  // gazebo_ros's UpdateChild rule (UpdateClock)
  bool restarts_schedule_on_reset_world() const override { return true; }
  Schedule schedule(double dt, uint64_t start_tick) const override {
    return Schedule::update_clock(cfg_.update_rate, dt, start_tick);
  }
  std::vector<std::string> driven_joints() const override { return {cfg_.left_joint, cfg_.right_joint}; }

  void configure(RobotHandle& robot) override {
    joint_[0] = robot.joint(cfg_.left_joint);
    joint_[1] = robot.joint(cfg_.right_joint);
    for (int side = 0; side < 2; ++side) motor_[side] = robot.add_motor(joint_[side], cfg_.wheel_torque);
  }

  void set_twist(const Twist& cmd) override {
    cmd_v_ = cmd.linear.x();
    cmd_w_ = cmd.angular.z();
  }
  void command(const std::string&, const Command& value, CommandResult*) override { set_twist(std::get<Twist>(value)); }

  // car: a reset starts the ramp afresh (upstream keeps its commanded speeds; docs/COMPAT-plugins.md).
  void reset() override {
    cmd_v_ = cmd_w_ = 0.0;
    ramp_ = WheelRamp();
    for (int side = 0; side < 2; ++side) omega_[side] = q_ref_[side] = 0.0;
    encoder_ = EncoderOdometry();
    update_due_ = false;
    clock_.restart();
  }

  // New wheel speed targets after an update, then the motors' anchor (see below).
  void pre_physics(const StepContext& ctx, RobotHandle& robot) override {
    clock_.begin(ctx.tick, ctx.dt);
    if (update_due_) {
      update_due_ = false;
      double target[2], current[2], motor[2];
      wheel_speeds(cmd_v_, cmd_w_, cfg_.wheel_separation, &target[0], &target[1]);
      const double rad = cfg_.wheel_diameter / 2.0;
      for (int side = 0; side < 2; ++side) current[side] = robot.joint_velocity(joint_[side]) * rad;
      ramp_.update(target, current, cfg_.wheel_acceleration, clock_.since(ctx.tick, ctx.dt), motor);
      for (int side = 0; side < 2; ++side) omega_[side] = motor[side] / rad;
    }
    // The wheel motors are velocity motors, as ODE's joint motor that upstream sets (SetParam "vel", "fmax"). Held
    // at a target of 0 they also pull gently toward the angle their target integrates to: an iterative solver
    // leaves a small velocity error each step, which would add up to a creep of about 0.3 mm per 10 s at rest. The
    // anchor stays within kAnchorWindow of the actual angle, so a wheel that slips or is blocked never winds up; it
    // is off while the target is not 0 (it pulled a lagging wheel ahead of upstream's: 2 cm over a 10 s circle).
    constexpr double kAnchorWindow = 0.02;  // [rad]
    constexpr double kAnchorGain = 0.05;    // [-] fraction of the angle error corrected per step
    for (int side = 0; side < 2; ++side) {
      const double q = robot.joint_position(joint_[side]);
      q_ref_[side] = std::clamp(q_ref_[side] + omega_[side] * ctx.dt, q - kAnchorWindow, q + kAnchorWindow);
      robot.set_motor(motor_[side], {omega_[side], 1.0, q_ref_[side], omega_[side] == 0.0 ? kAnchorGain : 0.0});
    }
  }

  void track(const StepContext& ctx, const RobotHandle& robot) override {
    if (!cfg_.encoder_odometry) return;
    const double rad = cfg_.wheel_diameter / 2.0;
    encoder_.integrate(robot.joint_velocity(joint_[0]) * rad * ctx.dt, robot.joint_velocity(joint_[1]) * rad * ctx.dt,
                       cfg_.wheel_separation, ctx.dt);
  }

  // The plug-in's update: odometry out (new motor targets follow in the next pre_physics).
  void post_physics(const StepContext& ctx, const RobotHandle& robot, OutputQueue* out) override {
    update_due_ = true;
    // the wheels' joint states and TF go out whatever publishTf says (the odometry port then sends nothing)
    auto o = std::make_unique<OdometryOut>();
    const char* names[2] = {cfg_.left_joint.c_str(), cfg_.right_joint.c_str()};
    for (int side = 0; side < 2; ++side)
      o->joints.push_back({names[side], robot.joint_position(joint_[side]), robot.joint_velocity(joint_[side])});
    if (cfg_.encoder_odometry) {
      o->pose.translation() = Eigen::Vector3d(encoder_.x, encoder_.y, 0.0);
      o->pose.linear() = Eigen::AngleAxisd(encoder_.theta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      o->linear = Eigen::Vector3d(encoder_.v, 0.0, 0.0);
      o->angular = Eigen::Vector3d(0.0, 0.0, encoder_.w);
    } else {
      const ModelState s = robot.root_state();
      o->pose = s.pose;
      // twist in the base frame, by yaw, as the plug-in does
      const Eigen::Matrix3d Rm = s.pose.linear();
      const double yaw = std::atan2(Rm(1, 0), Rm(0, 0));
      o->linear = Eigen::Vector3d(std::cos(yaw) * s.linear.x() + std::sin(yaw) * s.linear.y(),
                                  std::cos(yaw) * s.linear.y() - std::sin(yaw) * s.linear.x(), 0.0);
      o->angular = Eigen::Vector3d(0.0, 0.0, s.angular.z());
    }
    out->push_back(std::move(o));
  }

 private:
  DiffDriveConfig cfg_;
  int joint_[2] = {-1, -1};
  int motor_[2] = {-1, -1};
  double cmd_v_ = 0.0, cmd_w_ = 0.0;   // [m/s], [rad/s] last command
  UpdateClock clock_;                  // upstream's seconds_since_last_update
  WheelRamp ramp_;                     // upstream's wheel ramp
  double omega_[2] = {0.0, 0.0};       // [rad/s] motor velocity targets
  double q_ref_[2] = {0.0, 0.0};       // [rad] integrated motor targets, anchored near the joint
  EncoderOdometry encoder_;
  bool update_due_ = false;
};

void finish(ResolveContext& ctx) {
  const PluginConfig& c = ctx.config();
  for (const char* key : {"leftJoint", "rightJoint"}) {
    const std::string& jn = c.text(key);
    const Joint* j = ctx.model().find_joint(jn);
    if (!j)
      ctx.fail(key, "joint '" + jn + "' not found in the model (plug-in '" + c.name + "', " + c.filename + ")");
    if (j->type == JointType::Fixed) ctx.fail(key, "joint '" + jn + "' is fixed; a drive wheel needs a continuous joint");
  }
  check_wheel_length(ctx, "wheelSeparation");
  check_wheel_length(ctx, "wheelDiameter");
  if (c.number("wheelTorque") < 0) ctx.fail("wheelTorque", "must be >= 0");
  if (c.number("wheelAcceleration") < 0) ctx.fail("wheelAcceleration", "must be >= 0 (0 = unlimited)");
  warn_negative_rate(ctx, "updateRate");
  const std::string& src = c.text("odometrySource");
  // GazeboRos::getParameter with options: a value not in the map is warned and the default (world) kept
  if (src != "world" && src != "encoder")
    ctx.warn(Severity::Warning, "odometry-source", "odometrySource",
             "<odometrySource> no matching key to " + src + ": world odometry, as upstream");
  if (!c.flag("publishTf"))
    ctx.warn(Severity::Warning, "publish-tf-off", "publishTf",
             "publishTf false: like gazebo_ros, no odometry message and no odometry TF at all");
}

}  // namespace

const PluginKind& diff_drive_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "diff_drive";
    k.filenames = {"libgazebo_ros_diff_drive.so"};
    k.namespace_rule = NamespaceRule::ModelName;  // GazeboRos (gazebo_ros_diff_drive.cpp)
    k.schema = {
        {"robotNamespace", T, "", ""},
        {"commandTopic", T, "cmd_vel", ""},
        {"odometryTopic", T, "odom", ""},
        {"odometryFrame", Fr, "odom", ""},
        {"robotBaseFrame", Fr, "base_footprint", ""},
        {"wheelSeparation", N, "0.34", "m"},
        {"wheelDiameter", N, "0.15", "m"},
        {"wheelTorque", N, "5.0", "N m"},
        {"wheelAcceleration", N, "0", "m/s^2"},
        {"updateRate", N, "100", "Hz"},
        {"odometrySource", T, "world", ""},
        {"publishTf", F, "true", ""},
        {"publishOdomTF", F, "true", ""},
        {"publishWheelTF", F, "false", ""},
        {"publishWheelJointState", F, "false", ""},
        {"leftJoint", T, "left_joint", ""},
        {"rightJoint", T, "right_joint", ""},
        {"rosDebugLevel", T, "na", ""},
    };
    k.ignored = {{"legacyMode", ""}, {"broadcastTF", ""}, {"alwaysOn", ""}};
    k.output_group = "odometry";
    k.inputs = topic_input("cmd_vel", InputType::Twist, "commandTopic", 10, kLinearX | kAngularZ);
    // odom (queue 100; none at all with publishTf false, as upstream) and its TF after it; the wheels on request
    k.outputs = [](const PluginConfig& c, const std::string& robot, const Environment&) {
      std::vector<OutputPort> ports = {
          odometry_port(c, robot, "odometryTopic", 100, c.flag("publishOdomTF") ? TfOrder::After : TfOrder::None)};
      if (!c.flag("publishTf")) {
        ports[0].topic.clear();
        ports[0].tf = TfOrder::None;
      }
      if (c.flag("publishWheelJointState")) ports.push_back(joint_states_port(c, robot, 10));
      if (c.flag("publishWheelTF")) ports.push_back(wheel_tf_port(c, robot));
      return ports;
    };
    k.finish = finish;
    k.make = [](const PluginConfig& c, const std::string& robot, uint64_t) -> std::unique_ptr<Plugin> {
      return std::make_unique<DiffDrive>(c, robot);
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
