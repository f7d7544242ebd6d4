// The Velodyne plug-in: rays with max(range.min, min_range) < r < min(range.max, max_range) and intensity >=
// min_intensity become points (x y z intensity ring), gaussianNoise on the range, a point noise pushes out of the
// band dropped. Behaviour per docs/COMPAT-sensors.md.
#include "velodyne.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "../common/ray_sensor.hpp"

namespace car_sim {

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType Fr = ParamType::Frame;
constexpr ParamType N = ParamType::Number;

class Velodyne : public Plugin {
 public:
  Velodyne(const PluginConfig& c, const std::string& robot, uint64_t seed)
      : link_(c.link), sensor_pose_(c.sensor_pose), rate_(c.number("update_rate")), grid_(c),
        noise_(c.number("gaussianNoise")), rng0_(plugin_rng(seed, robot, c.sensor)), rng_(rng0_) {
    proto_.sensor = c.sensor;
    // [m] the band: the plug-in's limits inside the sensor's
    rmin_ = std::max(c.number("min_range"), static_cast<double>(grid_.range_min()));
    rmax_ = std::min(c.number("max_range"), static_cast<double>(grid_.range_max()));
    min_intensity_ = c.number("min_intensity");
  }

  double update_rate() const override { return rate_; }
  void reset() override { rng_ = rng0_; }

  void post_physics(const StepContext& ctx, const RobotHandle& robot, OutputQueue* out) override {
    const auto& hits = grid_.cast(ctx, robot.link_pose(link_) * sensor_pose_);
    const RayScene& scene = ctx.world->rays();
    auto o = std::make_unique<VelodyneOut>(proto_);
    o->points.reserve(3 * hits.size());
    std::normal_distribution<double> gauss(0.0, noise_ != 0 ? std::abs(noise_) : 1.0);
    for (int i = 0; i < grid_.nh(); ++i) {
      // the plug-in's own angles: min_angle for an axis of one sample (the ray itself looks ahead)
      const double y = grid_.nh() > 1 ? grid_.yaw(i) : grid_.yaw_min();
      for (int j = 0; j < grid_.nv(); ++j) {
        const RayHit& h = hits[i + j * grid_.nh()];
        // no hit reads +inf and falls outside the band
        double r = std::isfinite(h.distance) ? h.distance : std::numeric_limits<double>::infinity();
        const double intensity = std::isfinite(h.distance) ? scene.look(h.body).laser_retro : 0.0;
        if (rmin_ >= r || r >= rmax_ || intensity < min_intensity_) continue;
        if (noise_ != 0.0) r += gauss(rng_);
        if (!(rmin_ < r && r < rmax_)) continue;
        const double p = grid_.nv() > 1 ? grid_.pitch(j) : grid_.pitch_min();
        o->points.push_back(static_cast<float>(r * std::cos(p) * std::cos(y)));
        o->points.push_back(static_cast<float>(r * std::cos(p) * std::sin(y)));
        o->points.push_back(static_cast<float>(r * std::sin(p)));
        o->intensities.push_back(static_cast<float>(intensity));
        o->rings.push_back(static_cast<uint16_t>(j));
      }
    }
    out->push_back(std::move(o));
  }

 private:
  std::string link_;
  Eigen::Isometry3d sensor_pose_;
  double rate_;
  RayGrid grid_;
  double noise_;  // [m] stddev
  double rmin_ = 0, rmax_ = 0, min_intensity_ = 0;
  std::mt19937_64 rng0_, rng_;
  VelodyneOut proto_;
};

void finish(ResolveContext& ctx) {
  finish_ray(ctx);
  const PluginConfig& c = ctx.config();
  // upstream filters every point out then (empty clouds): a warning, not a refusal
  if (c.number("min_range") >= c.number("max_range"))
    ctx.warn(Severity::Warning, "velodyne-band", "min_range",
             "min_range " + c.text("min_range") + " >= max_range " + c.text("max_range") +
                 ": every point is filtered out, as upstream (empty clouds)");
  if (c.number("ray/scan/vertical/samples") * c.number("ray/scan/vertical/resolution") > 65535)
    ctx.fail_sensor("ray/scan/vertical/samples", "more than 65535 rings");
}

}  // namespace

void VelodyneOut::visit(FieldVisitor& v) const {
  const size_t n = intensities.size();
  v.array("points", points.data(), {n, 3});
  v.array("intensity", intensities.data(), {n});
  std::vector<float> ring(rings.begin(), rings.end());
  v.array("ring", ring.data(), {n});
}

const PluginKind& velodyne_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "velodyne";
    k.filenames = {"libgazebo_ros_velodyne_laser.so", "libgazebo_ros_velodyne_gpu_laser.so"};
    // <robotNamespace> as written (AsWritten): absent "/", empty NodeHandle(""): both global
    k.model_level = false;
    k.sensor_types = {"ray", "gpu_ray"};
    // GazeboRosVelodyneLaser's Load throws on the other sensor type ("requires a [Gpu]Ray Sensor as its parent")
    k.file_sensor_types = {{"libgazebo_ros_velodyne_laser.so", {"ray"}},
                           {"libgazebo_ros_velodyne_gpu_laser.so", {"gpu_ray"}}};
    k.sensor_schema = ray_sensor_schema();
    k.schema = {
        {"robotNamespace", T, "/", ""},
        {"frameName", T, "/world", ""},
        {"topicName", T, "/points", ""},
        {"min_range", N, "0", "m"},
        {"max_range", N, "1e308", "m"},  // upstream: +inf
        {"min_intensity", N, "-1.7976931348623157e308", ""},
        {"gaussianNoise", N, "0", "m"},
    };
    k.ignored = {{"alwaysOn", ""},
                 {"staticTopicName", "the lmark1 fork's transformed copy of the cloud is not simulated"},
                 {"staticFrameName", "the lmark1 fork's transformed copy of the cloud is not simulated"}};
    k.lazy = true;
    k.output_group = "velodyne";
    // sensor_msgs/PointCloud2 on topicName, queue 1, frame tf::resolve(robotNamespace, frameName): an absolute frame
    // loses its '/', a relative one goes under the namespace (none for the global one)
    k.outputs = [](const PluginConfig& c, const std::string& robot, const Environment&) {
      const std::string ns = plugin_robot_namespace(c, robot);
      const std::string& f = c.text("frameName");
      const std::string frame = !f.empty() && f[0] == '/' ? f.substr(1) : ns.empty() ? f : ns + "/" + f;
      return std::vector<OutputPort>{
          sensor_port(c, robot, "points", sample_type<LidarCloudSample>(), "topicName", frame, 1)};
    };
    k.finish = finish;
    k.make = [](const PluginConfig& c, const std::string& robot, uint64_t seed) -> std::unique_ptr<Plugin> {
      return std::make_unique<Velodyne>(c, robot, seed);
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
