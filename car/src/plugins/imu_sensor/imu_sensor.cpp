// The imu sensor with libgazebo_ros_imu_sensor.so. The sensor (Gazebo's ImuSensor::UpdateImpl), at each update of
// its <update_rate>: the link's angular velocity, and the acceleration of the sensor point from its velocity
// change since the last update, gravity included, both in the sensor frame; then the sensor's <noise> (per axis:
// mean, stddev, a bias drawn once). The plug-in (gazebo_ros_imu_sensor.cpp): publishes at most updateRateHZ
// (default 1 Hz), rpyOffset on the orientation, gaussianNoise on orientation, acceleration and rates.
#include "imu_sensor.hpp"

#include <cmath>

#include "../common/sensor_outputs.hpp"

namespace car_sim {

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType Fr = ParamType::Frame;
constexpr ParamType N = ParamType::Number;
constexpr ParamType F = ParamType::Flag;

// One axis of the sensor's <noise>: [rad/s] for rates, [m/s^2] for accelerations.
struct AxisNoise {
  bool on = false;
  double mean = 0, stddev = 0, bias_mean = 0, bias_stddev = 0;
  double bias = 0;  // drawn once
};

const char* const kQuantity[2] = {"angular_velocity", "linear_acceleration"};
const char* const kOldQuantity[2] = {"rate", "accel"};
const char* const kAxis[3] = {"x", "y", "z"};
const char* const kNoiseKey[4] = {"mean", "stddev", "bias_mean", "bias_stddev"};

// An axis's noise: the SDF 1.5+ per-axis block imu/<quantity>/<axis>/noise/..., else the old form
// imu/noise/<rate|accel>/... (with imu/noise/type) for all three axes. The per-axis block's type is an XML
// attribute car's sensor reader does not keep: a block with any non-zero value is Gaussian.
AxisNoise axis_noise(const PluginConfig& c, int q, int k) {
  AxisNoise n;
  double v[4];
  bool given = false;
  for (int i = 0; i < 4; ++i) {
    const std::string key = std::string("imu/") + kQuantity[q] + "/" + kAxis[k] + "/noise/" + kNoiseKey[i];
    v[i] = c.number(key);
    given = given || !c.param(key).from_default;
  }
  if (!given) {
    if (c.text("imu/noise/type") != "gaussian") return n;
    for (int i = 0; i < 4; ++i) v[i] = c.number(std::string("imu/noise/") + kOldQuantity[q] + "/" + kNoiseKey[i]);
  }
  n.mean = v[0];
  n.stddev = v[1];
  n.bias_mean = v[2];
  n.bias_stddev = v[3];
  n.on = v[0] != 0 || v[1] != 0 || v[2] != 0 || v[3] != 0;
  return n;
}

// The sensor keys: update_rate and every noise key, defaults 0 (no noise).
const std::vector<ParamDef>& imu_sensor_schema() {
  static const std::vector<std::string> keys = [] {
    std::vector<std::string> ks;
    for (int q = 0; q < 2; ++q)
      for (int k = 0; k < 3; ++k)
        for (int i = 0; i < 4; ++i)
          ks.push_back(std::string("imu/") + kQuantity[q] + "/" + kAxis[k] + "/noise/" + kNoiseKey[i]);
    for (int q = 0; q < 2; ++q)
      for (int i = 0; i < 4; ++i) ks.push_back(std::string("imu/noise/") + kOldQuantity[q] + "/" + kNoiseKey[i]);
    return ks;
  }();
  static const std::vector<ParamDef> s = [] {
    std::vector<ParamDef> d = {{"update_rate", N, "0", "Hz"}, {"imu/noise/type", T, "none", ""}};
    for (const auto& k : keys)
      d.push_back({k.c_str(), N, "0", k.find("angular_velocity") != std::string::npos || k.find("/rate/") != std::string::npos ? "rad/s" : "m/s^2"});
    return d;
  }();
  return s;
}

class ImuSensor : public Plugin {
 public:
  ImuSensor(const PluginConfig& c, const std::string& robot, uint64_t seed)
      : link_(c.link), sensor_pose_(c.sensor_pose), rate_(c.number("update_rate")),
        publish_rate_(c.number("updateRateHZ")), stddev_(std::abs(c.number("gaussianNoise"))),
        offset_(Eigen::Quaterniond(rpy_offset(c))), initial_reference_(c.flag("initialOrientationAsReference")),
        rng0_(plugin_rng(seed, robot, c.sensor)), rng_(rng0_) {
    proto_.sensor = c.sensor;
    // the sensor's <noise>: per axis; each bias drawn once, N(bias_mean, bias_stddev) with a random sign, from
    // the instance's generator (so the same seed gives the same biases, also after a reset)
    std::mt19937_64 g = rng0_;
    for (int q = 0; q < 2; ++q)
      for (int k = 0; k < 3; ++k) {
        AxisNoise& n = noise_[q][k];
        n = axis_noise(c, q, k);
        if (n.bias_stddev > 0 || n.bias_mean != 0) {
          std::normal_distribution<double> b(n.bias_mean, n.bias_stddev > 0 ? n.bias_stddev : 1.0);
          n.bias = n.bias_stddev > 0 ? b(g) : n.bias_mean;
          if (std::uniform_real_distribution<double>(0.0, 1.0)(g) < 0.5) n.bias = -n.bias;
        }
      }
    rng0_ = g;
    rng_ = rng0_;
  }

  double update_rate() const override { return rate_; }

  // Gazebo's default reference: the sensor's world orientation at the load; the plug-in makes it the world's
  // (REP 145) unless initialOrientationAsReference
  void configure(RobotHandle& robot) override {
    if (initial_reference_) reference_ = Eigen::Quaterniond((robot.link_pose(link_) * sensor_pose_).linear());
  }
  // lastMeasurementTime and the plug-in's last are 0 at the load and when time goes back; the point's last
  // velocity stays (upstream resets it nowhere)
  void start_clock(uint64_t) override {
    last_measurement_ns_ = 0;
    last_publication_ns_ = 0;
  }
  // the noise generator restarts (car's replay); the sensor's state stays, as upstream's over reset_world
  void reset() override { rng_ = rng0_; }

  void idle(const StepContext& ctx, const RobotHandle& robot) override {
    ImuSample s;
    if (measure(ctx, robot, &s)) gate(ctx);
  }

  void post_physics(const StepContext& ctx, const RobotHandle& robot, OutputQueue* out) override {
    ImuSample s;
    if (!measure(ctx, robot, &s) || !gate(ctx)) return;
    // the sensor's noise (its generator is car's: its draws need not match upstream's)
    for (int k = 0; k < 3; ++k) {
      s.angular_velocity[k] += sample(noise_[0][k]);
      s.linear_acceleration[k] += sample(noise_[1][k]);
    }
    // the plug-in: rpyOffset, then gaussianNoise on the quaternion's x, y, z, w, the acceleration, the rates
    Eigen::Quaterniond q = offset_ * s.orientation;
    if (stddev_ > 0) {
      std::normal_distribution<double> noise(0.0, stddev_);
      for (int k = 0; k < 4; ++k) q.coeffs()[k] += noise(rng_);
      for (int k = 0; k < 3; ++k) s.linear_acceleration[k] += noise(rng_);
      for (int k = 0; k < 3; ++k) s.angular_velocity[k] += noise(rng_);
    }
    auto o = std::make_unique<ImuOut>(proto_);
    o->orientation = q;
    o->angular_velocity = s.angular_velocity;
    o->linear_acceleration = s.linear_acceleration;
    out->push_back(std::move(o));
  }

 private:
  std::string link_;
  Eigen::Isometry3d sensor_pose_;  // on the link
  double rate_;                    // [Hz] the sensor's <update_rate>
  double publish_rate_;            // [Hz] updateRateHZ
  double stddev_;  // gaussianNoise; upstream's Box-Muller gives a negative one the same spread
  Eigen::Quaterniond offset_;
  bool initial_reference_;
  Eigen::Quaterniond reference_ = Eigen::Quaterniond::Identity();  // world -> the orientation's reference
  std::mt19937_64 rng0_, rng_;  // the noise generator as seeded, and as it runs
  ImuOut proto_;
  AxisNoise noise_[2][3];  // [angular velocity, linear acceleration][x, y, z]
  Eigen::Vector3d last_velocity_ = Eigen::Vector3d::Zero();  // [m/s] world frame, of the sensor point
  int64_t last_measurement_ns_ = 0, last_publication_ns_ = 0;

  double sample(const AxisNoise& n) {
    if (!n.on) return 0.0;
    double e = n.mean + n.bias;
    if (n.stddev > 0) e += std::normal_distribution<double>(0.0, n.stddev)(rng_);
    return e;
  }

  // ImuSensor::UpdateImpl at this tick, before its noise: false while no time passed since the last measurement
  bool measure(const StepContext& ctx, const RobotHandle& robot, ImuSample* s) {
    const int64_t now = tick_time_ns(ctx.tick, ctx.dt);
    const double dt = common_time_double(now - last_measurement_ns_);  // [s]
    last_measurement_ns_ = now;
    if (!(dt > 0.0)) return false;
    const ModelState link = robot.link_state(link_);
    const Eigen::Isometry3d pose = link.pose * sensor_pose_;
    const Eigen::Matrix3d Rt = pose.linear().transpose();
    s->angular_velocity = Rt * link.angular;
    // [m/s] world frame: the sensor point's velocity on the turning link
    const Eigen::Vector3d u = link.linear + link.angular.cross(pose.translation() - link.pose.translation());
    s->linear_acceleration = Rt * ((u - last_velocity_) / dt - ctx.world->environment().gravity);
    last_velocity_ = u;
    s->orientation = reference_.conjugate() * Eigen::Quaterniond(pose.linear());
    return true;
  }

  // the plug-in's rate control at a measurement: false while less than 1 / updateRateHZ passed since the last
  // publication (seconds as doubles, as upstream)
  bool gate(const StepContext& ctx) {
    const int64_t now = tick_time_ns(ctx.tick, ctx.dt);
    if (publish_rate_ > 0 && common_time_double(now - last_publication_ns_) < 1.0 / publish_rate_) return false;
    last_publication_ns_ = now;
    return true;
  }

};

void finish(ResolveContext& ctx) {
  PluginConfig& c = ctx.config();
  for (const ParamDef& d : imu_sensor_schema())
    if (std::string(d.key).find("stddev") != std::string::npos && c.number(d.key) < 0)
      ctx.fail_sensor(d.key, "stddev must be >= 0");
  const std::string& t = c.text("imu/noise/type");
  if (t != "none" && t != "gaussian") ctx.fail_sensor("imu/noise/type", "unknown noise type '" + t + "'");
  check_offsets(ctx);
  warn_negative_rate(ctx, "updateRateHZ");
  if (c.param("frameName").from_default) ctx.drop("frameName", "missing <frameName>, cannot proceed");
  // upstream's ROS_WARN, kept: the default surprises (a 100 Hz sensor publishes once a second)
  if (c.param("updateRateHZ").from_default)
    ctx.warn(Severity::Warning, "imu-rate-default", "updateRateHZ",
             "missing <updateRateHZ>, set to default: 1 (the plug-in publishes once a second)");
  if (c.flag("initialOrientationAsReference"))
    ctx.warn(Severity::Warning, "deprecated", "initialOrientationAsReference",
             "<initialOrientationAsReference> set to true, this behavior is deprecated as it does not comply with "
             "REP 145.");
}

}  // namespace

const PluginKind& imu_sensor_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "imu_sensor";
    k.filenames = {"libgazebo_ros_imu_sensor.so"};
    // gazebo_ros_imu_sensor.cpp LoadParameters: absent -> "/" + the model's name + "/"
    k.namespace_rule = NamespaceRule::AbsentIsModel;
    k.model_level = false;
    k.sensor_types = {"imu"};
    k.sensor_schema = imu_sensor_schema();
    k.schema = {
        {"robotNamespace", T, "", ""},
        {"topicName", T, "imu_data", ""},
        {"frameName", Fr, "", ""},
        {"updateRateHZ", N, "1", "Hz"},
        {"gaussianNoise", N, "0", ""},
        {"xyzOffset", T, "0 0 0", "m"},
        {"rpyOffset", T, "0 0 0", "rad"},
        {"initialOrientationAsReference", F, "false", ""},
    };
    k.ignored = {{"alwaysOn", ""}, {"bodyName", ""}};
    k.lazy = true;
    k.output_group = "imus";
    k.outputs = imu_ports;
    k.finish = finish;
    k.make = [](const PluginConfig& c, const std::string& robot, uint64_t seed) -> std::unique_ptr<Plugin> {
      return std::make_unique<ImuSensor>(c, robot, seed);
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
