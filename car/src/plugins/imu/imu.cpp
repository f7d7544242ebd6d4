// The IMU: orientation from the true pose; angular velocity and linear acceleration (gravity included) by finite
// differences of the sensor frame's last three poses; the sensor's <noise> (per axis: mean, stddev, a bias drawn
// once), then gaussianNoise as stddev on each component.
#include "imu.hpp"

#include <algorithm>
#include <cmath>

namespace car_sim {

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType Fr = ParamType::Frame;
constexpr ParamType N = ParamType::Number;

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

class Imu : public Plugin {
 public:
  Imu(const PluginConfig& c, const std::string& robot, uint64_t seed)
      : link_(c.link), sensor_pose_(c.sensor_pose),
        rate_(c.sensor.empty() ? c.number("updateRate") : c.number("update_rate")), model_plugin_(c.sensor.empty()),
        stddev_(c.number("gaussianNoise")),
        rng0_(plugin_rng(seed, robot, c.sensor.empty() ? c.name : c.sensor)), rng_(rng0_) {
    proto_.sensor = c.sensor.empty() ? c.name : c.sensor;
    if (!c.sensor.empty()) {
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
  }

  double update_rate() const override { return rate_; }
  // the model plug-in (libgazebo_ros_imu.so): its rate control, last from the load, set by each publication; the
  // sensor's own update_rate otherwise
  Schedule schedule(double dt, uint64_t start_tick) const override {
    return model_plugin_ ? Schedule::since_last(rate_, dt, start_tick, false) : Schedule(rate_, dt, start_tick);
  }
  void reset() override {
    rng_ = rng0_;
    count_ = 0;
  }
  void set_active(bool active) override {
    if (active) count_ = 0;
  }

  // the sensor frame's last three poses, for finite differences
  void track(const StepContext&, const RobotHandle& robot) override {
    history_[0] = history_[1];
    history_[1] = history_[2];
    history_[2] = robot.link_pose(link_) * sensor_pose_;
    count_ = std::min(3, count_ + 1);
  }

  void post_physics(const StepContext& ctx, const RobotHandle&, OutputQueue* out) override {
    if (count_ < 3) return;
    const Eigen::Isometry3d* p = history_;  // p[0] oldest, p[2] now
    const double dt = ctx.dt;
    const Eigen::Matrix3d Rt = p[2].linear().transpose();
    // angular velocity from the last rotation step, in the sensor frame
    const Eigen::AngleAxisd step(p[1].linear().transpose() * p[2].linear());
    Eigen::Vector3d w = step.axis() * step.angle() / dt;
    // acceleration from the last two velocities, minus gravity: at rest it reads +g up
    const Eigen::Vector3d v1 = (p[1].translation() - p[0].translation()) / dt;
    const Eigen::Vector3d v2 = (p[2].translation() - p[1].translation()) / dt;
    Eigen::Vector3d a = Rt * ((v2 - v1) / dt - ctx.world->environment().gravity);
    // the sensor's noise (SDF <noise>): N(mean, stddev) + bias per axis
    for (int k = 0; k < 3; ++k) {
      w[k] += sample(noise_[0][k]);
      a[k] += sample(noise_[1][k]);
    }
    if (stddev_ > 0) {
      std::normal_distribution<double> noise(0.0, stddev_);
      for (int k = 0; k < 3; ++k) w[k] += noise(rng_);
      for (int k = 0; k < 3; ++k) a[k] += noise(rng_);
    }
    auto o = std::make_unique<ImuOut>(proto_);
    o->orientation = Eigen::Quaterniond(p[2].linear());
    o->angular_velocity = w;
    o->linear_acceleration = a;
    out->push_back(std::move(o));
  }

 private:
  std::string link_;
  Eigen::Isometry3d sensor_pose_;
  double rate_;
  bool model_plugin_;  // libgazebo_ros_imu.so (no <sensor>)
  double stddev_;
  std::mt19937_64 rng0_, rng_;  // the noise generator as seeded, and as it runs
  ImuOut proto_;
  AxisNoise noise_[2][3];  // [angular velocity, linear acceleration][x, y, z]
  Eigen::Isometry3d history_[3];

  double sample(const AxisNoise& n) {
    if (!n.on) return 0.0;
    double e = n.mean + n.bias;
    if (n.stddev > 0) e += std::normal_distribution<double>(0.0, n.stddev)(rng_);
    return e;
  }
  int count_ = 0;
};

void finish(ResolveContext& ctx) {
  PluginConfig& c = ctx.config();
  if (ctx.sensor()) {
    for (const ParamDef& d : imu_sensor_schema())
      if (std::string(d.key).find("stddev") != std::string::npos && c.number(d.key) < 0)
        ctx.fail_sensor(d.key, "stddev must be >= 0");
    const std::string& t = c.text("imu/noise/type");
    if (t != "none" && t != "gaussian") ctx.fail_sensor("imu/noise/type", "unknown noise type '" + t + "'");
    for (const char* key : {"frameName", "bodyName"})
      if (c.text(key).empty()) ctx.set(key, ctx.sensor()->link);
    return;
  }
  const std::string body = c.text("bodyName");
  if (!ctx.model().find_link(body)) ctx.fail("bodyName", "link '" + body + "' not found in the model");
  c.link = body;
  if (c.text("frameName").empty()) ctx.set("frameName", body);
}

}  // namespace

void ImuOut::visit(FieldVisitor& v) const {
  const double q[4] = {orientation.x(), orientation.y(), orientation.z(), orientation.w()};
  v.vector("orientation", q, 4);
  v.vector("angular_velocity", angular_velocity.data(), 3);
  v.vector("linear_acceleration", linear_acceleration.data(), 3);
}

const PluginKind& imu_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "imu";
    k.filenames = {"libgazebo_ros_imu_sensor.so", "libgazebo_ros_imu.so"};
    // gazebo_ros_imu_sensor.cpp: absent -> the model's name; the model plug-in gazebo_ros_imu.cpp: as written
    k.namespace_rule = NamespaceRule::AbsentIsModel;
    k.file_namespace_rules = {{"libgazebo_ros_imu.so", NamespaceRule::AsWritten}};
    k.model_level = true;
    k.sensor_types = {"imu"};
    k.sensor_schema = imu_sensor_schema();
    k.schema = {
        {"robotNamespace", T, "", ""},
        {"bodyName", T, "", ""},
        {"topicName", T, "imu", ""},
        {"frameName", Fr, "", ""},
        {"gaussianNoise", N, "0", ""},
        {"updateRate", N, "0", "Hz"},
        {"xyzOffset", T, "0 0 0", "m"},
        {"rpyOffset", T, "0 0 0", "rad"},
    };
    k.ignored = {{"alwaysOn", ""}, {"serviceName", ""}};
    k.lazy = true;
    k.output_group = "imus";
    // sensor_msgs/Imu on topicName in frameName, queue 10, gaussianNoise^2 on the three covariances' diagonals
    k.outputs = [](const PluginConfig& c, const std::string& robot, const Environment&) {
      OutputPort p = sensor_port(c, robot, "imu", SampleType::Imu, "topicName", c.text("frameName"), 10);
      const double variance = std::pow(c.number("gaussianNoise"), 2);
      p.orientation_covariance.fill(variance);
      p.angular_velocity_covariance.fill(variance);
      p.linear_acceleration_covariance.fill(variance);
      return std::vector<OutputPort>{p};
    };
    k.finish = finish;
    k.make = [](const PluginConfig& c, const std::string& robot, uint64_t seed) -> std::unique_ptr<Plugin> {
      return std::make_unique<Imu>(c, robot, seed);
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
