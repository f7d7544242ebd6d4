// The hector sonar: range = the minimum over the ray grid (range.max when nothing is hit); a reading short of
// range.max becomes range * scaleError + offset + drift + N(0, gaussianNoise), clamped to [min, max], where the
// drift is a first-order Gauss-Markov process (driftFrequency [1/s], stationary stddev drift). Published at
// updateRate (default 10 Hz) or 1 / updatePeriod, not at the sensor's update_rate. Per docs/COMPAT-sensors.md.
#include "hector_sonar.hpp"

#include <algorithm>
#include <cmath>

#include "../common/hector_sensor_model.hpp"
#include "../common/ray_sensor.hpp"
#include "../common/sensor_outputs.hpp"

namespace car_sim {

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType Fr = ParamType::Frame;
constexpr ParamType N = ParamType::Number;

class HectorSonar : public Plugin {
 public:
  HectorSonar(const PluginConfig& c, const std::string& robot, uint64_t seed)
      : link_(c.link), sensor_pose_(c.sensor_pose), grid_(c), timer_(c), rng0_(plugin_rng(seed, robot, c.sensor)) {
    offset_ = c.number("offset");
    drift_ = c.number("drift");
    drift_frequency_ = c.number("driftFrequency");
    noise_ = c.number("gaussianNoise");
    scale_ = c.number("scaleError");
    proto_.sensor = c.sensor;
    proto_.radiation = 0;  // always ULTRASOUND
    // the narrower of the two spans of the grid
    proto_.field_of_view = static_cast<float>(
        std::min(std::abs(c.number("ray/scan/horizontal/max_angle") - c.number("ray/scan/horizontal/min_angle")),
                 std::abs(c.number("ray/scan/vertical/max_angle") - c.number("ray/scan/vertical/min_angle"))));
    proto_.min_range = grid_.range_min();
    proto_.max_range = grid_.range_max();
    reset();
  }

  double update_rate() const override { return timer_.rate(); }
  Schedule schedule(double dt, uint64_t) const override { return timer_.schedule(dt); }

  // SensorModel::reset: the drift starts at N(0, drift)
  void reset() override {
    rng_ = rng0_;
    current_drift_ = gauss(drift_);
    last_.unset();
  }
  void set_active(bool active) override {
    if (active) last_.unset();
  }

  void post_physics(const StepContext& ctx, const RobotHandle& robot, OutputQueue* out) override {
    const double dt = last_.since(ctx);  // [s] since the last update
    const auto& hits = grid_.cast(ctx, robot.link_pose(link_) * sensor_pose_);
    double r = proto_.max_range;
    for (const RayHit& h : hits)
      if (std::isfinite(h.distance)) r = std::min(r, static_cast<double>(h.distance));
    if (r < proto_.max_range) {
      // SensorModel(value, dt): value * scale + offset + drift + noise, the drift advanced by dt
      current_drift_ = std::exp(-dt * drift_frequency_) * current_drift_ +
                       dt * gauss(std::sqrt(2 * drift_frequency_) * drift_);
      r = r * scale_ + offset_ + current_drift_ + gauss(noise_);
      r = std::clamp(r, static_cast<double>(proto_.min_range), static_cast<double>(proto_.max_range));
    }
    auto o = std::make_unique<RangeOut>(proto_);
    o->range = static_cast<float>(r);
    out->push_back(std::move(o));
  }

 private:
  double gauss(double sigma) { return hector::gauss(rng_, sigma); }

  std::string link_;
  Eigen::Isometry3d sensor_pose_;
  RayGrid grid_;
  hector::UpdateTimer timer_;
  double offset_ = 0, drift_ = 0, drift_frequency_ = 0, noise_ = 0, scale_ = 1;
  double current_drift_ = 0;
  hector::LastUpdate last_;
  std::mt19937_64 rng0_, rng_;
  RangeOut proto_;
};

void finish(ResolveContext& ctx) {
  finish_ray(ctx);
  const PluginConfig& c = ctx.config();
  hector::finish_timer(ctx);
  for (const char* k : {"drift", "driftFrequency", "gaussianNoise"}) {
    const double v = c.number(k);
    hector::check_sign(ctx, k, k, &v, 1);
  }
}

}  // namespace

const PluginKind& hector_sonar_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "hector_sonar";
    k.filenames = {"libhector_gazebo_ros_sonar.so"};
    k.model_level = false;
    k.sensor_types = {"ray"};  // its Load throws on a gpu_ray sensor (not a RaySensor)
    k.sensor_schema = ray_sensor_schema();
    k.schema = {
        {"robotNamespace", T, "", ""},
        {"topicName", T, "sonar", ""},
        {"frameId", Fr, "/sonar_link", ""},
        {"offset", N, "0", "m"},
        {"drift", N, "0", "m"},
        {"driftFrequency", N, "0.000277777777777778", "1/s"},
        {"gaussianNoise", N, "0", "m"},
        {"scaleError", N, "1", ""},
    };
    for (const auto& d : hector::timer_schema("10")) k.schema.push_back(d);
    k.ignored = {{"alwaysOn", ""}};
    k.lazy = true;
    k.output_group = "ranges";
    // sensor_msgs/Range (ULTRASOUND) on topicName in frameId, queue 1, at the plug-in's own rate
    k.outputs = [](const PluginConfig& c, const std::string& robot, const Environment&) {
      return std::vector<OutputPort>{
          sensor_port(c, robot, "range", sample_type<RangeSample>(), "topicName", c.text("frameId"), 1)};
    };
    k.finish = finish;
    k.make = [](const PluginConfig& c, const std::string& robot, uint64_t seed) -> std::unique_ptr<Plugin> {
      return std::make_unique<HectorSonar>(c, robot, seed);
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
