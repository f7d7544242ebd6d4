// libgazebo_ros_joint_state_publisher.so (gazebo_plugins, Noetic): jointName (comma separated) at updateRate
// (100 Hz; 0 = every step). Per docs/COMPAT-plugins.md.
#include "joint_state_publisher.hpp"

namespace car_sim {

std::vector<std::string> split_joint_names(const std::string& text) {
  std::string s;
  for (char c : text)
    if (c != ' ') s += c;
  std::vector<std::string> out(1);
  for (char c : s) {
    if (c == ',')
      out.emplace_back();
    else
      out.back() += c;
  }
  return out;
}

void JointStatesOut::visit(FieldVisitor& v) const {
  std::string names;
  std::vector<double> pos, vel;
  for (const auto& j : joints) {
    names += (names.empty() ? "" : ",") + j.name;
    pos.push_back(j.position);
    vel.push_back(j.velocity);
  }
  v.text("names", names);
  v.vector("position", pos.data(), pos.size());
  v.vector("velocity", vel.data(), vel.size());
}

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType N = ParamType::Number;

class JointStatePublisher : public Plugin {
 public:
  explicit JointStatePublisher(const PluginConfig& c)
      : names_(c.param("jointName").from_default ? std::vector<std::string>{} : split_joint_names(c.text("jointName"))),
        rate_(c.number("updateRate")) {}

  double update_rate() const override { return rate_; }
  // gazebo_ros's UpdateChild rule (UpdateClock)
  Schedule schedule(double dt, uint64_t start_tick) const override {
    return Schedule::update_clock(rate_, dt, start_tick);
  }

  void configure(RobotHandle& robot) override {
    for (const auto& n : names_) joints_.push_back(robot.joint(n));
  }

  void post_physics(const StepContext&, const RobotHandle& robot, OutputQueue* out) override {
    auto o = std::make_unique<JointStatesOut>();
    for (size_t i = 0; i < names_.size(); ++i)
      o->joints.push_back({names_[i], robot.joint_position(joints_[i]), robot.joint_velocity(joints_[i])});
    out->push_back(std::move(o));
  }

 private:
  std::vector<std::string> names_;
  double rate_;
  std::vector<int> joints_;
};

void finish(ResolveContext& ctx) {
  const PluginConfig& c = ctx.config();
  // without <jointName> upstream's ROS_ASSERT (of a string literal) passes: it publishes empty joint states
  if (c.param("jointName").from_default)
    ctx.warn(Severity::Warning, "jsp-no-joints", "jointName",
             "GazeboRosJointStatePublisher Plugin missing jointNames: it publishes empty joint states");
  else
    for (const auto& n : split_joint_names(c.text("jointName"))) {
      const Joint* j = ctx.model().find_joint(n);
      if (!j) ctx.fail("jointName", "joint '" + n + "' not found in the model");
      if (j->type == JointType::Fixed) ctx.fail("jointName", "joint '" + n + "' is fixed; it has no state");
    }
  warn_negative_rate(ctx, "updateRate");
}

}  // namespace

const PluginKind& joint_state_publisher_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "joint_state_publisher";
    k.filenames = {"libgazebo_ros_joint_state_publisher.so"};
    k.namespace_rule = NamespaceRule::ModelName;  // GazeboRos (gazebo_ros_joint_state_publisher.cpp)
    k.schema = {
        {"robotNamespace", T, "", ""},
        {"jointName", T, "", ""},
        {"updateRate", N, "100", "Hz"},
    };
    k.ignored = {{"alwaysOn", ""}};
    k.lazy = true;
    k.output_group = "joint_states";
    // sensor_msgs/JointState on <namespace>/joint_states, queue 1000 as upstream
    k.outputs = [](const PluginConfig& c, const std::string& robot, const Environment&) {
      return std::vector<OutputPort>{joint_states_port(c, robot, 1000)};
    };
    k.finish = finish;
    k.make = [](const PluginConfig& c, const std::string&, uint64_t) -> std::unique_ptr<Plugin> {
      return std::make_unique<JointStatePublisher>(c);
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
