// The hector IMU: at each update (updateRate, default every step) rot = rpyOffset * link rotation; acceleration
// = rot^-1 ((v - v_last) / dt - g) and rate = rpyOffset^-1 (rotation from the last orientation / dt), each through
// its SensorModel; the orientation carries the yaw model's bias and the roll/pitch an accelerometer bias implies.
// Per docs/COMPAT-sensors.md.
#include "hector_imu.hpp"

#include <algorithm>
#include <cmath>

#include "../common/hector_sensor_model.hpp"

namespace car_sim {

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType Fr = ParamType::Frame;
constexpr ParamType N = ParamType::Number;

bool parse3(const std::string& t, Eigen::Vector3d* v) {
  double x[3];
  if (!hector::parse_n(t, 3, x)) return false;
  *v = Eigen::Vector3d(x[0], x[1], x[2]);
  return true;
}

class HectorImu : public Plugin {
 public:
  HectorImu(const PluginConfig& c, const std::string& robot, uint64_t seed)
      : link_(c.text("bodyName")), timer_(c), rng0_(plugin_rng(seed, robot, c.name)) {
    accel_.load(c, "accel");
    rate_model_.load(c, "rate");
    yaw_.load(c, "yaw");
    // a non-zero gaussianNoise replaces accelGaussianNoise and rateGaussianNoise on every axis
    const double g = c.number("gaussianNoise");
    if (g != 0.0) {
      accel_.gaussian_noise.setConstant(g);
      rate_model_.gaussian_noise.setConstant(g);
    }
    Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
    parse3(c.text("rpyOffset"), &rpy);
    offset_ = Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
              Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX());
    reset();
  }

  double update_rate() const override { return timer_.rate(); }
  Schedule schedule(double dt, uint64_t) const override { return timer_.schedule(dt); }
  void reset() override {
    rng_ = rng0_;
    orientation_ = Eigen::Quaterniond::Identity();
    velocity_.setZero();
    accel_value_.setZero();
    // the rate stays: upstream's Reset zeroes orientation, velocity and accel only, so the first message after a
    // reset (dt 0) carries the last rate through the rate model
    accel_.reset(rng_);
    rate_model_.reset(rng_);
    yaw_.reset(rng_);
    last_.unset();
  }
  void set_active(bool active) override {
    if (active) last_.unset();
  }

  void post_physics(const StepContext& ctx, const RobotHandle& robot, OutputQueue* out) override {
    const double dt = last_.since(ctx);  // [s] since the last update
    const ModelState s = robot.link_state(link_);
    const Eigen::Quaterniond link_rot(s.pose.linear());
    Eigen::Quaterniond rot = (offset_ * link_rot).normalized();
    const Eigen::Vector3d gravity = ctx.world->environment().gravity;
    const double g = gravity.norm();
    // [m/s^2] specific force in the sensor frame, from the link origin's velocity
    if (dt > 0.0) accel_value_ = rot.inverse() * ((s.linear - velocity_) / dt - gravity);
    velocity_ = s.linear;
    // [rad/s] from the rotation since the last update (quaternion axis-angle, as upstream)
    const Eigen::Quaterniond delta = orientation_.inverse() * rot;
    orientation_ = rot;
    if (dt > 0.0) {
      const Eigen::Vector3d axis(delta.x(), delta.y(), delta.z());
      const double angle = 2.0 * std::acos(std::clamp(delta.w(), -1.0, 1.0));
      rate_value_ = offset_.inverse() * (axis.norm() > 0 ? Eigen::Vector3d(angle * axis.normalized() / dt)
                                                         : Eigen::Vector3d::Zero());
    }
    const Eigen::Vector3d a = accel_(accel_value_, dt, rng_);
    const Eigen::Vector3d w = rate_model_(rate_value_, dt, rng_);
    accel_value_ = a;
    rate_value_ = w;
    yaw_.update(dt, rng_);
    // the orientation error: the yaw bias, and the roll/pitch an accelerometer bias (in the world) implies
    const Eigen::Vector3d accel_drift = link_rot * accel_.bias();
    const double yaw_error = yaw_.bias()[0];
    Eigen::Quaterniond err = Eigen::Quaterniond(std::cos(yaw_error / 2), 0, 0, std::sin(yaw_error / 2)) *
                             Eigen::Quaterniond(1.0, 0.5 * accel_drift.y() / g, 0.5 * -accel_drift.x() / g, 0.0);
    err.normalize();
    auto o = std::make_unique<HectorImuOut>();
    o->orientation = err * rot;
    o->angular_velocity = w;
    o->linear_acceleration = a;
    o->orientation_error = err;
    o->rate_bias = rate_model_.bias();
    o->accel_bias = accel_.bias();
    out->push_back(std::move(o));
  }

 private:
  std::string link_;
  hector::UpdateTimer timer_;
  Eigen::Quaterniond offset_;
  hector::SensorModel<3> accel_, rate_model_;
  hector::SensorModel<1> yaw_;
  std::mt19937_64 rng0_, rng_;
  Eigen::Quaterniond orientation_;
  Eigen::Vector3d velocity_, accel_value_;
  Eigen::Vector3d rate_value_ = Eigen::Vector3d::Zero();  // [rad/s] kept over a reset, as upstream
  hector::LastUpdate last_;
};

void finish(ResolveContext& ctx) {
  PluginConfig& c = ctx.config();
  if (c.text("bodyName").empty()) ctx.set("bodyName", ctx.model().root_link);
  const std::string body = c.text("bodyName");
  // upstream's Load logs this and returns: the plug-in is inert, the model loads
  if (!ctx.model().find_link(body)) ctx.drop("bodyName", "GazeboRosIMU plugin error: bodyName: " + body + " does not exist");
  c.link = body;
  if (c.text("frameId").empty()) ctx.set("frameId", body);
  if (c.param("biasTopicName").from_default && !c.text("topicName").empty())
    ctx.set("biasTopicName", c.text("topicName") + "/bias");
  hector::finish_timer(ctx);
  hector::finish_model(ctx, "accel", 3);
  hector::finish_model(ctx, "rate", 3);
  hector::finish_model(ctx, "yaw", 1);
  for (const char* k : {"xyzOffset", "rpyOffset"}) {
    Eigen::Vector3d v;
    if (!parse3(c.text(k), &v)) ctx.fail(k, "'" + c.text(k) + "' is not three numbers");
  }
}

// sensor_msgs/Imu on topicName and the biases on biasTopicName (each only when named), queue 10, in frameId.
// Covariances of the measurement as upstream: rate and accel noise squared (a non-zero gaussianNoise replaces
// both), orientation roll/pitch accel noise^2 / g^2 (-1 without gravity), yaw the yaw noise squared; the biases
// carry none.
std::vector<OutputPort> outputs(const PluginConfig& c, const std::string& robot, const Environment& env) {
  hector::SensorModel<3> accel, rate;
  hector::SensorModel<1> yaw;
  accel.load(c, "accel");
  rate.load(c, "rate");
  yaw.load(c, "yaw");
  if (c.number("gaussianNoise") != 0.0) {
    accel.gaussian_noise.setConstant(c.number("gaussianNoise"));
    rate.gaussian_noise.setConstant(c.number("gaussianNoise"));
  }
  const Eigen::Vector3d a = accel.gaussian_noise, w = rate.gaussian_noise;
  const double g = env.gravity.norm();  // [m/s^2]
  std::vector<OutputPort> ports;
  if (!c.text("topicName").empty()) {
    OutputPort p = sensor_port(c, robot, "imu", sample_type<ImuSample>(), "topicName", c.text("frameId"), 10);
    for (int i = 0; i < 3; ++i) {
      p.angular_velocity_covariance[i] = w[i] * w[i];
      p.linear_acceleration_covariance[i] = a[i] * a[i];
    }
    p.orientation_covariance[0] = g > 0 ? a.x() * a.x() / (g * g) : -1;
    p.orientation_covariance[1] = g > 0 ? a.y() * a.y() / (g * g) : -1;
    p.orientation_covariance[2] = yaw.gaussian_noise[0] * yaw.gaussian_noise[0];
    ports.push_back(p);
  }
  if (!c.text("biasTopicName").empty())
    ports.push_back(sensor_port(c, robot, "bias", sample_type<ImuSample>(), "biasTopicName", c.text("frameId"), 10));
  return ports;
}

}  // namespace

void HectorImuOut::visit(FieldVisitor& v) const {
  ImuOut::visit(v);
  const double q[4] = {orientation_error.x(), orientation_error.y(), orientation_error.z(), orientation_error.w()};
  v.vector("orientation_error", q, 4);
  v.vector("rate_bias", rate_bias.data(), 3);
  v.vector("accel_bias", accel_bias.data(), 3);
}

const PluginKind& hector_imu_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "hector_imu";
    k.filenames = {"libhector_gazebo_ros_imu.so"};
    k.model_level = true;
    k.schema = {
        {"robotNamespace", T, "", ""},
        {"bodyName", T, "", ""},
        {"frameId", Fr, "", ""},
        {"topicName", T, "imu", ""},
        {"biasTopicName", T, "", ""},  // default: topicName + "/bias", filled in by finish
        {"gaussianNoise", N, "0", ""},
        {"xyzOffset", T, "0 0 0", "m"},
        {"rpyOffset", T, "0 0 0", "rad"},
    };
    for (const auto& d : hector::timer_schema("0")) k.schema.push_back(d);
    for (const auto& d : hector::model_schema("accel", "m/s^2")) k.schema.push_back(d);
    for (const auto& d : hector::model_schema("rate", "rad/s")) k.schema.push_back(d);
    for (const auto& d : hector::model_schema("yaw", "rad")) k.schema.push_back(d);
    k.ignored = {{"alwaysOn", ""},
                 {"serviceName", "the calibrate and set_*_bias services are not provided"}};
    k.lazy = true;
    k.output_group = "imus";
    k.outputs = outputs;
    k.finish = finish;
    k.make = [](const PluginConfig& c, const std::string& robot, uint64_t seed) -> std::unique_ptr<Plugin> {
      return std::make_unique<HectorImu>(c, robot, seed);
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
