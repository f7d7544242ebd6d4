// libgazebo_ros_ft_sensor.so (gazebo_plugins, Noetic): jointName's GetForceTorque(0) body2Force/body2Torque — the
// wrench on the child link, child link frame — plus gaussianNoise (stddev) on each component, at updateRate
// (0 = every step) while subscribed. car measures it with Bullet's joint feedback (moving joints only: fixed
// joints are merged into one body). Per docs/COMPAT-plugins.md.
#include "ft_sensor.hpp"

namespace car_sim {

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType N = ParamType::Number;

class FtSensor : public Plugin {
 public:
  FtSensor(const PluginConfig& c, const std::string& robot, uint64_t seed)
      : joint_name_(c.text("jointName")), rate_(c.number("updateRate")), noise_(c.number("gaussianNoise")),
        rng0_(plugin_rng(seed, robot, c.name)), rng_(rng0_) {}

  double update_rate() const override { return rate_; }
  // ft_sensor's rate control: last_time_ starts at 0 (never set at the load), set by each publication
  Schedule schedule(double dt, uint64_t start_tick) const override {
    return Schedule::since_last(rate_, dt, start_tick, true);
  }
  void configure(RobotHandle& robot) override {
    joint_ = robot.joint(joint_name_);
    robot.enable_joint_wrench(joint_);
  }
  void reset() override { rng_ = rng0_; }

  void post_physics(const StepContext&, const RobotHandle& robot, OutputQueue* out) override {
    auto o = std::make_unique<WrenchOut>();
    o->wrench = robot.joint_wrench(joint_);
    if (noise_ > 0) {
      std::normal_distribution<double> n(0.0, noise_);
      for (int k = 0; k < 3; ++k) o->wrench.force[k] += n(rng_);
      for (int k = 0; k < 3; ++k) o->wrench.torque[k] += n(rng_);
    }
    out->push_back(std::move(o));
  }

 private:
  std::string joint_name_;
  double rate_, noise_;
  int joint_ = -1;
  std::mt19937_64 rng0_, rng_;
};

void finish(ResolveContext& ctx) {
  const PluginConfig& c = ctx.config();
  // upstream's Load logs these and returns: the plug-in is inert, the model loads
  if (c.param("jointName").from_default) ctx.drop("jointName", "ft_sensor plugin missing <jointName>, cannot proceed");
  const Joint* j = ctx.model().find_joint(c.text("jointName"));
  if (!j)
    ctx.drop("jointName", "gazebo_ros_ft_sensor plugin error: jointName: " + c.text("jointName") + " does not exist");
  // (Gazebo's URDF reader lumps a fixed joint away, so upstream finds no such joint either)
  if (j->type == JointType::Fixed)
    ctx.drop("jointName", "joint '" + j->name + "' is fixed: car merges the links of a fixed joint into one body, "
                          "so it has no reaction to measure (make it a revolute joint with zero limits)");
  if (c.param("topicName").from_default) ctx.drop("topicName", "ft_sensor plugin missing <topicName>, cannot proceed");
  if (c.number("gaussianNoise") < 0) ctx.fail("gaussianNoise", "must be >= 0");
  warn_negative_rate(ctx, "updateRate");
  ctx.config().link = j->child;
}

}  // namespace

const PluginKind& ft_sensor_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "ft_sensor";
    k.filenames = {"libgazebo_ros_ft_sensor.so"};
    k.schema = {
        {"robotNamespace", T, "", ""},
        {"jointName", T, "", ""},
        {"topicName", T, "", ""},
        {"gaussianNoise", N, "0", "N, N m"},
        {"updateRate", N, "0", "Hz"},
    };
    k.ignored = {{"alwaysOn", ""}};
    k.lazy = true;
    k.output_group = "wrenches";
    // geometry_msgs/WrenchStamped on topicName, header frame the joint's child link, queue 1
    k.outputs = [](const PluginConfig& c, const std::string& robot, const Environment&) {
      OutputPort p = sensor_port(c, robot, "wrench", sample_type<WrenchSample>(), "topicName", c.link, 1);
      p.frame_rule = FrameRule::PrefixHere;  // frame_name_ = tf::resolve(getParam("tf_prefix"), the child link)
      return std::vector<OutputPort>{p};
    };
    k.finish = finish;
    k.make = [](const PluginConfig& c, const std::string& robot, uint64_t seed) -> std::unique_ptr<Plugin> {
      return std::make_unique<FtSensor>(c, robot, seed);
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
