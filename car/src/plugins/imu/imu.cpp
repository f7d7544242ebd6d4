// libgazebo_ros_imu.so, as gazebo_ros_imu.cpp's UpdateChild computes it: at each message (p3d's rate control) the
// body's velocity change since the last message over its time, without gravity, and its angular velocity, both
// world vectors turned by rot = rpyOffset * the body's rotation (not by its inverse), gaussianNoise added before
// the turn; the orientation is rot. docs/COMPAT-sensors.md "The two IMU plug-ins".
#include "imu.hpp"

#include <cmath>


namespace car_sim {

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType Fr = ParamType::Frame;
constexpr ParamType N = ParamType::Number;

class Imu : public Plugin {
 public:
  Imu(const PluginConfig& c, const std::string& robot, uint64_t seed)
      : link_(c.link), rate_(c.number("updateRate")), stddev_(std::abs(c.number("gaussianNoise"))),
        rng0_(plugin_rng(seed, robot, c.name)), rng_(rng0_) {
    proto_.sensor = c.name;
    offset_ = Eigen::Quaterniond(rpy_offset(c));
  }

  double update_rate() const override { return rate_; }
  // p3d's rate control: last from the load, set by each message
  Schedule schedule(double dt, uint64_t start_tick) const override {
    return Schedule::since_last(rate_, dt, start_tick, false);
  }
  // last = the load's tick, or 0 when time goes back (car restarts the rate grid there, COMPAT-plugins p3d);
  // v_last stays (0 at the load: a robot is spawned at rest)
  void start_clock(uint64_t tick) override { last_tick_ = tick; }
  // the noise generator restarts (car's replay); last and v_last stay, as upstream has no Reset
  void reset() override { rng_ = rng0_; }

  // car's rate grid runs while nobody subscribes, and last follows it (docs/COMPAT-plugins.md p3d "When")
  void idle(const StepContext& ctx, const RobotHandle& robot) override { difference(ctx, robot.link_state(link_)); }

  void post_physics(const StepContext& ctx, const RobotHandle& robot, OutputQueue* out) override {
    const ModelState s = robot.link_state(link_);
    difference(ctx, s);
    Eigen::Quaterniond rot = offset_ * Eigen::Quaterniond(s.pose.linear());
    rot.normalize();
    Eigen::Vector3d w = s.angular, a = acceleration_;
    if (stddev_ > 0) {
      std::normal_distribution<double> noise(0.0, stddev_);
      for (int k = 0; k < 3; ++k) w[k] += noise(rng_);
      for (int k = 0; k < 3; ++k) a[k] += noise(rng_);
    }
    auto o = std::make_unique<ImuOut>(proto_);
    o->orientation = rot;
    // upstream's rot.RotateVector: the world vectors turned by the body's rotation
    o->angular_velocity = rot * w;
    o->linear_acceleration = rot * a;
    out->push_back(std::move(o));
  }

 private:
  std::string link_;
  double rate_;    // [Hz] updateRate, 0 = every step
  double stddev_;  // gaussianNoise; upstream's Box-Muller gives a negative one the same spread
  Eigen::Quaterniond offset_;
  std::mt19937_64 rng0_, rng_;  // the noise generator as seeded, and as it runs
  ImuOut proto_;
  uint64_t last_tick_ = 0;                                     // the last message's (or the load's)
  Eigen::Vector3d last_velocity_ = Eigen::Vector3d::Zero();   // [m/s] world frame, the body's origin then
  Eigen::Vector3d acceleration_ = Eigen::Vector3d::Zero();    // [m/s^2] world frame, no gravity

  // tmp_dt = last - t as doubles; when not 0, a = (v_last - v) / tmp_dt, v_last = v; last = t
  void difference(const StepContext& ctx, const ModelState& s) {
    const double tmp_dt = common_time_double(tick_time_ns(last_tick_, ctx.dt)) -
                          common_time_double(tick_time_ns(ctx.tick, ctx.dt));
    if (tmp_dt != 0) {
      acceleration_ = (last_velocity_ - s.linear) / tmp_dt;
      last_velocity_ = s.linear;
    }
    last_tick_ = ctx.tick;
  }
};

void finish(ResolveContext& ctx) {
  PluginConfig& c = ctx.config();
  if (c.param("bodyName").from_default) ctx.drop("bodyName", "imu plugin missing <bodyName>, cannot proceed");
  const std::string body = c.text("bodyName");
  if (!ctx.model().find_link(body))
    ctx.drop("bodyName", "gazebo_ros_imu plugin error: bodyName: " + body + " does not exist");
  check_offsets(ctx);
  warn_negative_rate(ctx, "updateRate");
  c.link = body;
  if (c.param("frameName").from_default) ctx.set("frameName", body);
}

}  // namespace


const PluginKind& imu_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "imu";
    k.filenames = {"libgazebo_ros_imu.so"};
    // gazebo_ros_imu.cpp LoadThread: robotNamespace as written
    k.namespace_rule = NamespaceRule::AsWritten;
    k.model_level = true;
    k.schema = {
        {"robotNamespace", T, "", ""},
        {"bodyName", T, "", ""},
        {"topicName", T, "/default_imu", ""},
        {"frameName", Fr, "", ""},
        {"gaussianNoise", N, "0", ""},
        {"updateRate", N, "0", "Hz"},
        {"xyzOffset", T, "0 0 0", "m"},
        {"rpyOffset", T, "0 0 0", "rad"},
    };
    k.ignored = {{"alwaysOn", ""},
                 {"serviceName", "the calibration service (std_srvs/Empty, always succeeds) is not advertised"}};
    k.lazy = true;
    k.output_group = "imus";
    k.outputs = imu_ports;
    k.finish = finish;
    k.make = [](const PluginConfig& c, const std::string& robot, uint64_t seed) -> std::unique_ptr<Plugin> {
      return std::make_unique<Imu>(c, robot, seed);
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
