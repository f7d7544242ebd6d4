// The block laser: one point per ray of the grid, rows of vertical samples; a ray without a hit lies at
// range.max; gaussianNoise on the coordinates of points short of range.max and on every intensity.
// Behaviour per docs/COMPAT-sensors.md (fix: each point on its own ray, not half a step over).
#include "block_laser.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "../common/ray_sensor.hpp"

namespace car_sim {

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType Fr = ParamType::Frame;
constexpr ParamType N = ParamType::Number;

class BlockLaser : public Plugin {
 public:
  BlockLaser(const PluginConfig& c, const std::string& robot, uint64_t seed)
      : link_(c.link), sensor_pose_(c.sensor_pose), rate_(c.number("update_rate")), grid_(c),
        noise_(c.number("gaussianNoise")), rng0_(plugin_rng(seed, robot, c.sensor)), rng_(rng0_) {
    proto_.sensor = c.sensor;
    proto_.rows = grid_.nv();
    proto_.cols = grid_.nh();
  }

  double update_rate() const override { return rate_; }
  void reset() override { rng_ = rng0_; }

  void post_physics(const StepContext& ctx, const RobotHandle& robot, OutputQueue* out) override {
    const auto& hits = grid_.cast(ctx, robot.link_pose(link_) * sensor_pose_);
    const RayScene& scene = ctx.world->rays();
    auto o = std::make_unique<BlockLaserOut>(proto_);
    const int n = grid_.size();
    o->points.resize(3 * static_cast<size_t>(n));
    o->intensities.resize(n);
    std::normal_distribution<double> gauss(0.0, noise_ > 0 ? noise_ : 1.0);
    const double rmax = grid_.range_max();
    // each ray's retro (0 without a hit, as Gazebo's GetRetro)
    retro_.resize(n);
    for (int k = 0; k < n; ++k) retro_[k] = std::isfinite(hits[k].distance) ? scene.look(hits[k].body).laser_retro : 0.0;
    for (int j = 0; j < grid_.nv(); ++j) {
      const double v = grid_.pitch(j);
      for (int i = 0; i < grid_.nh(); ++i) {
        const int k = i + j * grid_.nh();
        const RayHit& h = hits[k];
        // [m] a ray without a hit reads range.max, as Gazebo's ray shape does
        const bool hit = std::isfinite(h.distance);
        const double r = hit ? h.distance : rmax;
        const double y = grid_.yaw(i);
        double p[3] = {r * std::cos(v) * std::cos(y), r * std::cos(v) * std::sin(y), r * std::sin(v)};
        // upstream averages the retro of the ray and its next neighbours (clamped at the last): (i, j), (i+1, j),
        // (i, j+1), (i+1, j+1)
        const int i1 = std::min(i + 1, grid_.nh() - 1), j1 = std::min(j + 1, grid_.nv() - 1);
        double intensity = 0.25 * (retro_[i + j * grid_.nh()] + retro_[i1 + j * grid_.nh()] +
                                   retro_[i + j1 * grid_.nh()] + retro_[i1 + j1 * grid_.nh()]);
        if (noise_ > 0) {
          if (std::abs(rmax - r) > 1e-6)
            for (double& x : p) x += gauss(rng_);
          intensity += gauss(rng_);
        }
        for (int a = 0; a < 3; ++a) o->points[3 * k + a] = static_cast<float>(p[a]);
        o->intensities[k] = static_cast<float>(intensity);
      }
    }
    out->push_back(std::move(o));
  }

 private:
  std::string link_;
  Eigen::Isometry3d sensor_pose_;
  double rate_;
  RayGrid grid_;
  std::vector<double> retro_;  // per ray, this scan
  double noise_;  // [m] stddev
  std::mt19937_64 rng0_, rng_;
  BlockLaserOut proto_;
};

void finish(ResolveContext& ctx) {
  finish_ray(ctx);
  if (ctx.config().number("gaussianNoise") < 0) ctx.fail("gaussianNoise", "must be >= 0");
}

}  // namespace

void BlockLaserOut::visit(FieldVisitor& v) const {
  v.array("points", points.data(), {static_cast<size_t>(rows), static_cast<size_t>(cols), 3});
  v.array("intensities", intensities.data(), {static_cast<size_t>(rows), static_cast<size_t>(cols)});
}

const PluginKind& block_laser_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "block_laser";
    k.filenames = {"libgazebo_ros_block_laser.so"};
    k.model_level = false;
    k.sensor_types = {"ray"};  // a RayPlugin: its Load throws on a gpu_ray sensor (not a RaySensor)
    k.sensor_schema = ray_sensor_schema();
    k.schema = {
        {"robotNamespace", T, "", ""},
        {"frameName", Fr, "/world", ""},
        {"topicName", T, "/world", ""},
        {"gaussianNoise", N, "0", "m"},
        {"hokuyoMinIntensity", N, "101", ""},
        {"updateRate", N, "0", "Hz"},
    };
    k.ignored = {{"alwaysOn", ""}};
    k.lazy = true;
    k.output_group = "clouds";
    // sensor_msgs/PointCloud on topicName in frameName, queue 1; frame_name_ = tf::resolve(getParam("tf_prefix"),
    // frameName): tf_prefix of the plug-in's own namespace
    k.outputs = [](const PluginConfig& c, const std::string& robot, const Environment&) {
      OutputPort p =
          sensor_port(c, robot, "cloud", sample_type<PointCloudSample>(), "topicName", c.text("frameName"), 1);
      p.frame_rule = FrameRule::PrefixHere;
      return std::vector<OutputPort>{p};
    };
    k.finish = finish;
    k.make = [](const PluginConfig& c, const std::string& robot, uint64_t seed) -> std::unique_ptr<Plugin> {
      return std::make_unique<BlockLaser>(c, robot, seed);
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
