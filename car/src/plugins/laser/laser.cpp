// The lidar: N·r rays from min_angle to max_angle inclusive in the sensor's x-y plane, starting at range.min;
// REP 117 readings; Gaussian noise on in-range beams, clamped to [min, max]. Behaviour per docs/COMPAT-spec.md.
#include "laser.hpp"
#include "ziggurat.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

namespace car_sim {

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType Fr = ParamType::Frame;
constexpr ParamType N = ParamType::Number;
constexpr ParamType I = ParamType::Integer;
constexpr float kInf = std::numeric_limits<float>::infinity();
class Laser : public Plugin {
 public:
  Laser(const PluginConfig& c, const std::string& robot, uint64_t seed)
      : link_(c.link), sensor_pose_(c.sensor_pose), rate_(c.number("update_rate")),
        rng0_(plugin_rng(seed, robot, c.sensor)), rng_(rng0_) {
    proto_.sensor = c.sensor;
    const int n = static_cast<int>(c.number("ray/scan/horizontal/samples") * c.number("ray/scan/horizontal/resolution"));
    const double a = c.number("ray/scan/horizontal/min_angle"), b = c.number("ray/scan/horizontal/max_angle");
    proto_.angle_min = static_cast<float>(a);
    proto_.angle_max = static_cast<float>(b);
    proto_.angle_increment = n > 1 ? static_cast<float>((b - a) / (n - 1)) : 0.f;
    // one ray looks straight ahead (MultiRayShape::Init); the message keeps angle_min as given
    a_ = n > 1 ? a : 0.0;
    inc_ = n > 1 ? (b - a) / (n - 1) : 0.0;
    proto_.range_min = static_cast<float>(c.number("ray/range/min"));
    proto_.range_max = static_cast<float>(c.number("ray/range/max"));
    gaussian_ = c.text("ray/noise/type") == "gaussian";
    mean_ = c.number("ray/noise/mean");
    stddev_ = c.number("ray/noise/stddev");
    // ray i at a + i (b - a) / (n - 1) (0 for one ray), in the sensor's x-y plane
    dirs_.resize(3 * static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
      const double th = n > 1 ? a + i * (b - a) / (n - 1) : 0.0;
      dirs_[3 * i] = static_cast<float>(std::cos(th));
      dirs_[3 * i + 1] = static_cast<float>(std::sin(th));
      dirs_[3 * i + 2] = 0.f;
    }
    hits_.resize(n);
    // several vertical rows: Gazebo's RaySensor fills its scan with every row (index j * n + i), and
    // gazebo_ros_laser copies all n x n_v ranges into the LaserScan; the angles stay the horizontal ones
    if (c.number("ray/scan/vertical/samples") * c.number("ray/scan/vertical/resolution") >= 2)
      grid_ = std::make_unique<RayGrid>(c);
  }

  double update_rate() const override { return rate_; }
  void reset() override { rng_ = rng0_; }
  // reads the robot's link pose and the ray scene; writes its hits, noise generator and queue
  bool concurrent() const override { return true; }

  void post_physics(const StepContext& ctx, const RobotHandle& robot, OutputQueue* out) override {
    const Eigen::Isometry3d pose = robot.link_pose(link_) * sensor_pose_;
    const RayScene& scene = ctx.world->rays();
    const std::vector<RayHit>* hits = &hits_;
    // its own link seen too, as Gazebo 11's ray and GPU ray sensors (docs/COMPAT-sensors.md)
    if (grid_) {
      hits = &grid_->cast(ctx, pose);
    } else {
      // one row: a planar fan, car's segment sweep (RayScene::cast_fan)
      scene.cast_fan(pose.translation(), pose.linear(), dirs_.data(), static_cast<int>(hits_.size()), a_, inc_,
                     proto_.range_min, proto_.range_max, hits_.data());
    }
    const int n = static_cast<int>(hits->size());
    auto o = std::make_unique<LaserScanOut>(proto_);
    o->ranges.resize(n);
    o->intensities.resize(n);
    // one standard normal sample per in-range beam (ziggurat.hpp: a quarter of std::normal_distribution's cost)
    static const Ziggurat normal;
    for (int i = 0; i < n; ++i) {
      const RayHit& h = (*hits)[i];
      if (!std::isfinite(h.distance)) {
        o->ranges[i] = kInf;  // REP 117: no hit within range_max
        o->intensities[i] = 0.f;
        continue;
      }
      double r = h.distance;
      // noise on in-range readings only, then clamped to [min, max]
      if (gaussian_ && stddev_ > 0)
        r = std::clamp(r + normal(rng_, mean_, stddev_), double(proto_.range_min), double(proto_.range_max));
      else if (gaussian_)
        r = std::clamp(r + mean_, double(proto_.range_min), double(proto_.range_max));
      o->ranges[i] = static_cast<float>(r);
      o->intensities[i] = static_cast<float>(scene.look(h.body).laser_retro);
    }
    out->push_back(std::move(o));
  }

 private:
  std::string link_;
  Eigen::Isometry3d sensor_pose_;
  double rate_;
  std::mt19937_64 rng0_, rng_;  // the noise generator as seeded, and as it runs
  LaserScanOut proto_;  // the fields every scan shares
  bool gaussian_ = false;
  double mean_ = 0, stddev_ = 0;
  double a_ = 0, inc_ = 0;  // [rad] ray i's angle is a_ + i inc_
  std::vector<float> dirs_;
  std::vector<RayHit> hits_;
  std::unique_ptr<RayGrid> grid_;  // several vertical rows: every ray of the grid, rows outer
};

}  // namespace


namespace {

void finish(ResolveContext& ctx) { finish_ray(ctx); }

}  // namespace

void LaserScanOut::visit(FieldVisitor& v) const {
  v.number("angle_min", angle_min);
  v.number("angle_max", angle_max);
  v.number("angle_increment", angle_increment);
  v.number("range_min", range_min);
  v.number("range_max", range_max);
  v.array("ranges", ranges.data(), {ranges.size()});
  v.array("intensities", intensities.data(), {intensities.size()});
}

const PluginKind& laser_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "laser";
    k.filenames = {"libgazebo_ros_laser.so", "libgazebo_ros_gpu_laser.so"};
    k.namespace_rule = NamespaceRule::EmptyIsModel;  // GetRobotNamespace (gazebo_ros_laser.cpp, gazebo_ros_gpu_laser.cpp)
    k.model_level = false;
    k.sensor_types = {"ray", "gpu_ray"};
    // RayPlugin::Load and GpuRayPlugin::Load throw on the other sensor type (a RaySensor, a GpuRaySensor)
    k.file_sensor_types = {{"libgazebo_ros_laser.so", {"ray"}}, {"libgazebo_ros_gpu_laser.so", {"gpu_ray"}}};
    k.sensor_schema = ray_sensor_schema();
    k.schema = {
        {"robotNamespace", T, "", ""},
        {"topicName", T, "/world", ""},
        {"frameName", Fr, "/world", ""},
    };
    k.ignored = {{"alwaysOn", ""}, {"updateRate", ""}, {"gaussianNoise", ""}, {"hokuyoMinIntensity", ""}};
    k.lazy = true;
    k.output_group = "scans";
    // sensor_msgs/LaserScan on topicName in frameName, queue 10; frame_name_ = tf::resolve(tf::getPrefixParam(
    // rosnode_), frameName): tf_prefix searched upwards from the plug-in's namespace
    k.outputs = [](const PluginConfig& c, const std::string& robot, const Environment&) {
      OutputPort p =
          sensor_port(c, robot, "scan", sample_type<LaserScanSample>(), "topicName", c.text("frameName"), 10);
      p.frame_rule = FrameRule::PrefixSearched;
      return std::vector<OutputPort>{p};
    };
    k.finish = finish;
    k.make = [](const PluginConfig& c, const std::string& robot, uint64_t seed) -> std::unique_ptr<Plugin> {
      return std::make_unique<Laser>(c, robot, seed);
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
