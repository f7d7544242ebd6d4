// libgazebo_ros_tricycle_drive.so (gazebo_plugins, Noetic): at updateRate the actuated wheel's velocity motor
// (capped at wheelTorque) gets the ramped speed target cmd.linear.x / (actuatedWheelDiameter/2) and the steering
// joint is set to cmd.angular.z clamped to +-pi/2 (steeringSpeed 0), or turned at steeringSpeed toward it; the
// steering joint's motor (same cap) holds it in between, as ODE's fmax does. Odometry from the world (default) or
// the encoder wheels. Per docs/COMPAT-plugins.md.
#include "tricycle_drive.hpp"

#include <algorithm>
#include <cmath>

#include "../common/drive.hpp"

namespace car_sim {

double tricycle_wheel_speed(double current, double target, double accel, double decel, double tolerance, double dt) {
  if (accel <= 0) return target;
  const double diff = current - target;
  if (std::fabs(diff) < tolerance) return current;
  if (std::fabs(diff) > accel * dt) return diff > 0 ? current - accel * dt : current + decel * dt;
  return target;
}

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType Fr = ParamType::Frame;
constexpr ParamType N = ParamType::Number;
constexpr ParamType F = ParamType::Flag;

class Tricycle : public Plugin, public TwistDrive {
 public:
  explicit Tricycle(const PluginConfig& c)
      : steer_name_(c.text("steeringJoint")), wheel_name_(c.text("actuatedWheelJoint")),
        left_name_(c.text("encoderWheelLeftJoint")), right_name_(c.text("encoderWheelRightJoint")),
        rate_(c.number("updateRate")), wheel_radius_(c.number("actuatedWheelDiameter") / 2.0),
        encoder_radius_(c.number("encoderWheelDiameter") / 2.0), separation_(c.number("encoderWheelSeparation")),
        torque_(c.number("wheelTorque")), accel_(c.number("wheelAcceleration")),
        decel_(c.param("wheelDeceleration").from_default ? accel_ : c.number("wheelDeceleration")),
        tolerance_(c.number("wheelSpeedTolerance")), steer_speed_(c.number("steeringSpeed")),
        steer_tolerance_(c.number("steeringAngleTolerance")), encoder_(c.text("odometrySource") == "encoder"),
        clock_(rate_) {}

  double update_rate() const override { return rate_; }
  // gazebo_ros's UpdateChild rule (UpdateClock)
  Schedule schedule(double dt, uint64_t start_tick) const override {
    return Schedule::update_clock(rate_, dt, start_tick);
  }
  // deviation: its own clock_ (the ramp's dt) restarts at any reset, so its schedule restarts with it
  bool restarts_schedule_on_reset_world() const override { return true; }
  std::vector<std::string> driven_joints() const override { return {steer_name_, wheel_name_}; }

  void configure(RobotHandle& robot) override {
    steer_ = robot.joint(steer_name_);
    wheel_ = robot.joint(wheel_name_);
    left_ = robot.joint(left_name_);
    right_ = robot.joint(right_name_);
    wheel_motor_ = robot.add_motor(wheel_, torque_);
    steer_motor_ = robot.add_motor(steer_, torque_);
  }

  void set_twist(const Twist& cmd) override {
    speed_ = cmd.linear.x();
    angle_ = cmd.angular.z();
  }
  void command(const std::string&, const Command& value, CommandResult*) override { set_twist(std::get<Twist>(value)); }

  void reset() override {
    speed_ = angle_ = wheel_target_ = steer_rate_ = 0.0;
    odom_ = EncoderOdometry();
    update_due_ = false;
    clock_.restart();
  }

  void pre_physics(const StepContext& ctx, RobotHandle& robot) override {
    clock_.begin(ctx.tick, ctx.dt);
    if (update_due_) {
      update_due_ = false;
      // [s] upstream's seconds_since_last_update (motorController's dt)
      const double dt = clock_.since(ctx.tick, ctx.dt);
      wheel_target_ = tricycle_wheel_speed(robot.joint_velocity(wheel_), speed_ / wheel_radius_, accel_, decel_,
                                           tolerance_, dt);
      const double target = std::clamp(angle_, -M_PI / 2, M_PI / 2);
      const double diff = robot.joint_position(steer_) - target;
      if (steer_speed_ > 0) {
        // fix: upstream compares the angle error with the wheel speed target; car turns toward the target
        steer_rate_ = std::fabs(diff) < steer_tolerance_ ? 0.0 : (diff < 0 ? steer_speed_ : -steer_speed_);
      } else {
        robot.set_joint_position(steer_, target);
        steer_rate_ = 0.0;
      }
    }
    robot.set_motor(wheel_motor_, {wheel_target_, 1.0, 0.0, 0.0});
    robot.set_motor(steer_motor_, {steer_rate_, 1.0, 0.0, 0.0});
  }

  void track(const StepContext& ctx, const RobotHandle& robot) override {
    if (!encoder_) return;
    // fix: upstream turns its encoder heading by (sl - sr) / b, the wrong way round
    odom_.integrate(robot.joint_velocity(left_) * encoder_radius_ * ctx.dt,
                    robot.joint_velocity(right_) * encoder_radius_ * ctx.dt, separation_, ctx.dt);
  }

  void post_physics(const StepContext&, const RobotHandle& robot, OutputQueue* out) override {
    update_due_ = true;
    auto o = std::make_unique<OdometryOut>();
    if (encoder_) {
      o->pose.translation() = Eigen::Vector3d(odom_.x, odom_.y, 0.0);
      o->pose.linear() = Eigen::AngleAxisd(odom_.theta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      o->linear = Eigen::Vector3d(odom_.v, 0.0, 0.0);
      o->angular = Eigen::Vector3d(0.0, 0.0, odom_.w);
    } else {
      const ModelState s = robot.root_state();
      o->pose = s.pose;
      const double yaw = std::atan2(s.pose.linear()(1, 0), s.pose.linear()(0, 0));
      o->linear = Eigen::Vector3d(std::cos(yaw) * s.linear.x() + std::sin(yaw) * s.linear.y(),
                                  std::cos(yaw) * s.linear.y() - std::sin(yaw) * s.linear.x(), 0.0);
      o->angular = Eigen::Vector3d(0.0, 0.0, s.angular.z());
    }
    const std::string* names[4] = {&steer_name_, &wheel_name_, &left_name_, &right_name_};
    const int joints[4] = {steer_, wheel_, left_, right_};
    for (int i = 0; i < 4; ++i)
      o->joints.push_back({*names[i], robot.joint_position(joints[i]), robot.joint_velocity(joints[i])});
    // upstream's effort is each joint's GetForce(0): the force SetForce applied this step, none here (the two
    // driven joints are velocity motors, the encoder wheels passive)
    o->efforts.assign(4, 0.0);
    out->push_back(std::move(o));
  }

 private:
  std::string steer_name_, wheel_name_, left_name_, right_name_;
  double rate_, wheel_radius_, encoder_radius_, separation_, torque_, accel_, decel_, tolerance_, steer_speed_,
      steer_tolerance_;
  bool encoder_;
  int steer_ = -1, wheel_ = -1, left_ = -1, right_ = -1, wheel_motor_ = -1, steer_motor_ = -1;
  double speed_ = 0.0, angle_ = 0.0;  // [m/s] wheel surface speed, [rad] steering angle: the last command
  double wheel_target_ = 0.0;         // [rad/s]
  double steer_rate_ = 0.0;           // [rad/s]
  EncoderOdometry odom_;
  bool update_due_ = false;
  UpdateClock clock_;  // upstream's seconds_since_last_update
};

void finish(ResolveContext& ctx) {
  const PluginConfig& c = ctx.config();
  for (const char* key : {"steeringJoint", "actuatedWheelJoint", "encoderWheelLeftJoint", "encoderWheelRightJoint"}) {
    const std::string& jn = c.text(key);
    const Joint* j = ctx.model().find_joint(jn);
    if (!j) ctx.fail(key, "joint '" + jn + "' not found in the model (plug-in '" + c.name + "', " + c.filename + ")");
    if (j->type == JointType::Fixed) ctx.fail(key, "joint '" + jn + "' is fixed; it must move");
  }
  for (const char* key : {"actuatedWheelDiameter", "encoderWheelDiameter", "encoderWheelSeparation"})
    check_wheel_length(ctx, key);
  for (const char* key : {"wheelTorque", "wheelAcceleration", "wheelSpeedTolerance", "steeringSpeed",
                          "steeringAngleTolerance"})
    if (c.number(key) < 0) ctx.fail(key, "must be >= 0");
  warn_negative_rate(ctx, "updateRate");
  const std::string& src = c.text("odometrySource");
  // GazeboRos::getParameter with options: a value not in the map is warned and the default (world) kept
  if (src != "world" && src != "encoder")
    ctx.warn(Severity::Warning, "odometry-source", "odometrySource",
             "<odometrySource> no matching key to " + src + ": world odometry, as upstream");
}

}  // namespace

const PluginKind& tricycle_drive_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "tricycle_drive";
    k.filenames = {"libgazebo_ros_tricycle_drive.so"};
    k.namespace_rule = NamespaceRule::ModelName;  // GazeboRos (gazebo_ros_tricycle_drive.cpp)
    k.schema = {
        {"robotNamespace", T, "", ""},
        {"actuatedWheelDiameter", N, "0.15", "m"},
        {"encoderWheelDiameter", N, "0.15", "m"},
        {"wheelTorque", N, "5.0", "N m"},
        {"commandTopic", T, "cmd_vel", ""},
        {"odometryTopic", T, "odom", ""},
        {"odometryFrame", Fr, "odom", ""},
        {"robotBaseFrame", Fr, "base_link", ""},
        {"updateRate", N, "100", "Hz"},
        {"wheelAcceleration", N, "0", "rad/s^2"},
        {"wheelDeceleration", N, "0", "rad/s^2"},
        {"wheelSpeedTolerance", N, "0.01", "rad/s"},
        {"steeringSpeed", N, "0", "rad/s"},
        {"steeringAngleTolerance", N, "0.01", "rad"},
        {"encoderWheelSeparation", N, "0.5", "m"},
        {"publishWheelTF", F, "false", ""},
        {"publishWheelJointState", F, "false", ""},
        {"steeringJoint", T, "front_steering_joint", ""},
        {"actuatedWheelJoint", T, "front_wheel_joint", ""},
        {"encoderWheelLeftJoint", T, "left_wheel_joint", ""},
        {"encoderWheelRightJoint", T, "right_wheel_joint", ""},
        {"odometrySource", T, "world", ""},
    };
    k.ignored = {{"alwaysOn", ""}, {"rosDebugLevel", ""}, {"publishTf", ""}};
    k.output_group = "odometry";
    k.finish = finish;
    // angular.z is the steering angle [rad]
    k.inputs = topic_input("cmd_vel", InputType::Twist, "commandTopic", 1, kLinearX | kAngularZ);
    // odom with its TF sent first; the wheels on request (joint states with queue 1000, as upstream)
    k.outputs = [](const PluginConfig& c, const std::string& robot, const Environment&) {
      std::vector<OutputPort> ports = {odometry_port(c, robot, "odometryTopic", 1, TfOrder::Before)};
      if (c.flag("publishWheelJointState")) {
        OutputPort js = joint_states_port(c, robot, 1000);
        js.with_effort = true;  // name, position, velocity and effort, as publishWheelJointState fills them
        ports.push_back(js);
      }
      if (c.flag("publishWheelTF")) ports.push_back(wheel_tf_port(c, robot));
      return ports;
    };
    k.make = [](const PluginConfig& c, const std::string&, uint64_t) -> std::unique_ptr<Plugin> {
      return std::make_unique<Tricycle>(c);
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
