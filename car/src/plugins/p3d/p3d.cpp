// gazebo_ros_p3d (Noetic): bodyName and topicName required; frameName "world" (also "/world", "map", "/map": the
// world frame) or a link of the same model; xyzOffset added to the position, rpyOffset rotates the orientation;
// gaussianNoise (stddev) on each twist component; updateRate (0 = every step); published only while listened.
// fix: relative to a link, upstream composes the rotation the wrong way round and rotates the twist by the
// link's rotation instead of its inverse; car expresses pose and twist in the link's frame.
#include "p3d.hpp"

#include "xml_util.hpp"

namespace car_sim {

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType Fr = ParamType::Frame;
constexpr ParamType N = ParamType::Number;

// frameName world or map (a leading '/' already dropped): Gazebo's world frame; an empty one names no link upstream
bool world_frame(const std::string& f) { return f == "world" || f == "map"; }

class P3d : public Plugin {
 public:
  P3d(const PluginConfig& c, const std::string& robot, uint64_t seed)
      : body_(c.text("bodyName")), frame_(c.text("frameName")), rate_(c.number("updateRate")),
        noise_(c.number("gaussianNoise")), rng0_(plugin_rng(seed, robot, c.name)), rng_(rng0_) {
    const auto xyz = detail::parse_numbers(c.text("xyzOffset"), 3);
    offset_xyz_ = Eigen::Vector3d((*xyz)[0], (*xyz)[1], (*xyz)[2]);
    offset_rot_ = rpy_offset(c);
  }

  double update_rate() const override { return rate_; }
  // p3d's rate control: last from the load, set by each publication
  Schedule schedule(double dt, uint64_t start_tick) const override {
    return Schedule::since_last(rate_, dt, start_tick, false);
  }
  void reset() override { rng_ = rng0_; }

  void post_physics(const StepContext&, const RobotHandle& robot, OutputQueue* out) override {
    ModelState s = robot.link_state(body_);
    if (!world_frame(frame_)) {
      const ModelState f = robot.link_state(frame_);
      const Eigen::Matrix3d Rt = f.pose.linear().transpose();
      s.pose = f.pose.inverse() * s.pose;
      s.linear = Rt * (s.linear - f.linear - f.angular.cross(s.pose.translation()));
      s.angular = Rt * (s.angular - f.angular);
    }
    auto o = std::make_unique<P3dOut>();
    o->pose = s.pose;
    o->pose.translation() += offset_xyz_;
    o->pose.linear() = offset_rot_ * s.pose.linear();
    o->linear = s.linear;
    o->angular = s.angular;
    if (noise_ > 0) {
      std::normal_distribution<double> n(0.0, noise_);
      for (int k = 0; k < 3; ++k) o->linear[k] += n(rng_);
      for (int k = 0; k < 3; ++k) o->angular[k] += n(rng_);
    }
    out->push_back(std::move(o));
  }

 private:
  std::string body_, frame_;
  double rate_, noise_;
  std::mt19937_64 rng0_, rng_;  // the noise generator as seeded, and as it runs
  Eigen::Vector3d offset_xyz_;
  Eigen::Matrix3d offset_rot_;
};

void finish(ResolveContext& ctx) {
  const PluginConfig& c = ctx.config();
  // upstream's Load logs these and returns: the plug-in is inert, the model loads
  if (c.param("bodyName").from_default) ctx.drop("bodyName", "p3d plugin missing <bodyName>, cannot proceed");
  if (!ctx.model().find_link(c.text("bodyName")))
    ctx.drop("bodyName", "gazebo_ros_p3d plugin error: bodyName: " + c.text("bodyName") + " does not exist");
  if (c.param("topicName").from_default) ctx.drop("topicName", "p3d plugin missing <topicName>, cannot proceed");
  const std::string& f = c.text("frameName");
  if (!world_frame(f) && !ctx.model().find_link(f))
    ctx.drop("frameName", "gazebo_ros_p3d plugin: frameName: " + f + " does not exist, will not publish pose");
  check_offsets(ctx);
  if (c.number("gaussianNoise") < 0) ctx.fail("gaussianNoise", "must be >= 0");
  warn_negative_rate(ctx, "updateRate");
  ctx.config().link = c.text("bodyName");
}

}  // namespace

void P3dOut::visit(FieldVisitor& v) const {
  const Eigen::Vector3d p = pose.translation();
  v.vector("position", p.data(), 3);
  const Eigen::Quaterniond q(pose.linear());
  const double quat[4] = {q.x(), q.y(), q.z(), q.w()};
  v.vector("orientation", quat, 4);
  v.vector("linear", linear.data(), 3);
  v.vector("angular", angular.data(), 3);
}

const PluginKind& p3d_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "p3d";
    k.filenames = {"libgazebo_ros_p3d.so"};
    k.schema = {
        {"robotNamespace", T, "", ""},
        {"bodyName", T, "", ""},
        {"topicName", T, "", ""},
        {"frameName", Fr, "world", ""},
        {"xyzOffset", T, "0 0 0", "m"},
        {"rpyOffset", T, "0 0 0", "rad"},
        {"gaussianNoise", N, "0", "m/s, rad/s"},
        {"updateRate", N, "0", "Hz"},
    };
    k.ignored = {{"alwaysOn", ""}};
    k.lazy = true;
    k.output_group = "poses";
    // nav_msgs/Odometry on topicName (queue 100): frameName (tf_prefix of the namespace) -> bodyName, gaussianNoise^2 on every diagonal entry
    k.outputs = [](const PluginConfig& c, const std::string& robot, const Environment&) {
      OutputPort p;
      p.name = "odom";
      p.type = sample_type<OdometrySample>();
      p.ns = plugin_robot_namespace(c, robot);
      p.topic = resolve_topic(p.ns, c.text("topicName"));
      p.queue = 100;
      p.frame = c.text("frameName");
      p.child_frame = c.text("bodyName");
      p.frame_rule = FrameRule::PrefixHere;
      const double variance = c.number("gaussianNoise") * c.number("gaussianNoise");
      p.pose_covariance.fill(variance);
      p.twist_covariance.fill(variance);
      return std::vector<OutputPort>{p};
    };
    k.finish = finish;
    k.make = [](const PluginConfig& c, const std::string& robot, uint64_t seed) -> std::unique_ptr<Plugin> {
      return std::make_unique<P3d>(c, robot, seed);
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
