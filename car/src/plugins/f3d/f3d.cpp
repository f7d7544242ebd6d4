// libgazebo_ros_f3d.so (gazebo_plugins, Noetic): bodyName's WorldForce and WorldTorque — the force and torque
// added to it by plug-ins and services during the step, world frame, torque about its body's centre of mass —
// every step while subscribed. frameName is only the header's frame (upstream: "not used").
#include "f3d.hpp"

namespace car_sim {

void WrenchOut::visit(FieldVisitor& v) const {
  v.vector("force", wrench.force.data(), 3);
  v.vector("torque", wrench.torque.data(), 3);
}

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType Fr = ParamType::Frame;

class F3d : public Plugin {
 public:
  explicit F3d(const PluginConfig& c) : link_(c.text("bodyName")) {}
  double update_rate() const override { return 0.0; }
  void post_physics(const StepContext&, const RobotHandle& robot, OutputQueue* out) override {
    auto o = std::make_unique<WrenchOut>();
    o->wrench = robot.applied_wrench(link_);
    out->push_back(std::move(o));
  }

 private:
  std::string link_;
};

void finish(ResolveContext& ctx) {
  const PluginConfig& c = ctx.config();
  // upstream's Load logs these and returns: the plug-in is inert, the model loads
  if (c.param("bodyName").from_default) ctx.drop("bodyName", "f3d plugin missing <bodyName>, cannot proceed");
  if (!ctx.model().find_link(c.text("bodyName")))
    ctx.drop("bodyName", "gazebo_ros_f3d plugin error: bodyName: " + c.text("bodyName") + " does not exist");
  if (c.param("topicName").from_default) ctx.drop("topicName", "f3d plugin missing <topicName>, cannot proceed");
  ctx.config().link = c.text("bodyName");
}

}  // namespace

const PluginKind& f3d_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "f3d";
    k.filenames = {"libgazebo_ros_f3d.so"};
    k.schema = {
        {"robotNamespace", T, "", ""},
        {"bodyName", T, "", ""},
        {"topicName", T, "", ""},
        {"frameName", Fr, "world", ""},
    };
    k.ignored = {{"alwaysOn", ""}, {"updateRate", "f3d publishes every step while subscribed"}};
    k.lazy = true;
    k.output_group = "wrenches";
    // geometry_msgs/WrenchStamped on topicName, header frame frameName, queue 1
    k.outputs = [](const PluginConfig& c, const std::string& robot, const Environment&) {
      OutputPort p = sensor_port(c, robot, "wrench", sample_type<WrenchSample>(), "topicName", c.text("frameName"), 1);
      p.frame_rule = FrameRule::PrefixHere;  // frame_name_ = tf::resolve(getParam("tf_prefix"), frameName)
      return std::vector<OutputPort>{p};
    };
    k.finish = finish;
    k.make = [](const PluginConfig& c, const std::string&, uint64_t) -> std::unique_ptr<Plugin> {
      return std::make_unique<F3d>(c);
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
