// The IMU: orientation from the true pose; angular velocity and linear acceleration (gravity included) by finite
// differences of the sensor frame's last three poses; gaussianNoise as stddev on each component.
#include "imu.hpp"

#include <algorithm>

namespace car_sim {

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType Fr = ParamType::Frame;
constexpr ParamType N = ParamType::Number;

class Imu : public Plugin {
 public:
  Imu(const PluginConfig& c, const std::string& robot, uint64_t seed)
      : link_(c.link), sensor_pose_(c.sensor_pose),
        rate_(c.sensor.empty() ? c.number("updateRate") : c.number("update_rate")),
        stddev_(c.number("gaussianNoise")),
        rng0_(plugin_rng(seed, robot, c.sensor.empty() ? c.name : c.sensor)), rng_(rng0_) {
    proto_.sensor = c.sensor.empty() ? c.name : c.sensor;
  }

  double update_rate() const override { return rate_; }
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
  double rate_, stddev_;
  std::mt19937_64 rng0_, rng_;  // the noise generator as seeded, and as it runs
  ImuOut proto_;
  Eigen::Isometry3d history_[3];
  int count_ = 0;
};

void finish(ResolveContext& ctx) {
  PluginConfig& c = ctx.config();
  if (ctx.sensor()) {
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
    k.model_level = true;
    k.sensor_types = {"imu"};
    k.sensor_schema = {{"update_rate", N, "0", "Hz"}};
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
    k.finish = finish;
    k.make = [](const PluginConfig& c, const std::string& robot, uint64_t seed) -> std::unique_ptr<Plugin> {
      return std::make_unique<Imu>(c, robot, seed);
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
