// The range sensor: the minimum over the ray sensor's grid (its horizontal x vertical samples), a ray that hits
// nothing reading range.max as in Gazebo; gaussianNoise on in-range readings, capped at range.max.
// Behaviour per docs/COMPAT-sensors.md.
#include "range.hpp"

#include <algorithm>
#include <cmath>

#include "../common/ray_sensor.hpp"

namespace car_sim {

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType Fr = ParamType::Frame;
constexpr ParamType N = ParamType::Number;

class Range : public Plugin {
 public:
  Range(const PluginConfig& c, const std::string& robot, uint64_t seed)
      : link_(c.link), sensor_pose_(c.sensor_pose), rate_(c.number("update_rate")), grid_(c),
        noise_(c.number("gaussianNoise")), rng0_(plugin_rng(seed, robot, c.sensor)), rng_(rng0_) {
    proto_.sensor = c.sensor;
    proto_.radiation = c.text("radiation") == "ultrasound" ? 0 : 1;
    proto_.field_of_view = static_cast<float>(c.number("fov"));
    proto_.min_range = grid_.range_min();
    proto_.max_range = grid_.range_max();
  }

  double update_rate() const override { return rate_; }
  void reset() override { rng_ = rng0_; }

  void post_physics(const StepContext& ctx, const RobotHandle& robot, OutputQueue* out) override {
    const auto& hits = grid_.cast(ctx, robot.link_pose(link_) * sensor_pose_);
    // [m] the nearest hit; a ray without a hit reads range.max
    double r = proto_.max_range;
    for (const RayHit& h : hits)
      if (std::isfinite(h.distance)) r = std::min(r, static_cast<double>(h.distance));
    if (r < proto_.max_range && noise_ > 0) {
      std::normal_distribution<double> n(0.0, noise_);
      r = std::min(r + n(rng_), static_cast<double>(proto_.max_range));
    }
    auto o = std::make_unique<RangeOut>(proto_);
    o->range = static_cast<float>(r);
    out->push_back(std::move(o));
  }

 private:
  std::string link_;
  Eigen::Isometry3d sensor_pose_;
  double rate_;
  RayGrid grid_;
  double noise_;  // [m] stddev
  std::mt19937_64 rng0_, rng_;
  RangeOut proto_;
};

void finish(ResolveContext& ctx) {
  finish_ray(ctx);
  const PluginConfig& c = ctx.config();
  if (c.number("gaussianNoise") < 0) ctx.fail("gaussianNoise", "must be >= 0");
  if (c.number("fov") < 0) ctx.fail("fov", "must be >= 0");
}

}  // namespace


const PluginKind& range_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "range";
    k.filenames = {"libgazebo_ros_range.so"};
    k.model_level = false;
    k.sensor_types = {"ray"};  // a RayPlugin: its Load throws on a gpu_ray sensor (not a RaySensor)
    k.sensor_schema = ray_sensor_schema();
    k.schema = {
        {"robotNamespace", T, "", ""},
        {"frameName", Fr, "/world", ""},
        {"topicName", T, "/range", ""},
        {"radiation", T, "ultrasound", ""},
        {"fov", N, "0.05", "rad"},
        {"gaussianNoise", N, "0", "m"},
        {"updateRate", N, "0", "Hz"},
    };
    k.ignored = {{"alwaysOn", ""}};
    k.lazy = true;
    k.output_group = "ranges";
    // sensor_msgs/Range on topicName in frameName, queue 1, at most updateRate per second of sim time (0 = every
    // sensor update)
    k.outputs = [](const PluginConfig& c, const std::string& robot, const Environment&) {
      OutputPort p = sensor_port(c, robot, "range", sample_type<RangeSample>(), "topicName", c.text("frameName"), 1);
      // frame_name_ = tf::resolve(getParam("tf_prefix"), frameName): tf_prefix of the plug-in's own namespace
      p.frame_rule = FrameRule::PrefixHere;
      const double r = c.number("updateRate");
      p.min_period = r > 0 ? 1.0 / r : 0.0;
      return std::vector<OutputPort>{p};
    };
    k.finish = finish;
    k.make = [](const PluginConfig& c, const std::string& robot, uint64_t seed) -> std::unique_ptr<Plugin> {
      return std::make_unique<Range>(c, robot, seed);
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
