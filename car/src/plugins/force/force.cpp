// libgazebo_ros_force.so (gazebo_plugins, Noetic): the last geometry_msgs/Wrench on topicName, added to bodyName
// every step — force at the link's centre of mass and torque, world frame — until the next message.
#include "force.hpp"

namespace car_sim {

Eigen::Vector3d link_com(const RobotHandle& robot, const std::string& link) {
  const Link* l = robot.model().find_link(link);
  const Eigen::Vector3d local = l && l->inertial ? Eigen::Vector3d(l->inertial->origin.translation()) : Eigen::Vector3d::Zero();
  return robot.link_pose(link) * local;
}

namespace {

constexpr ParamType T = ParamType::Text;

class Force : public Plugin, public WrenchCommand {
 public:
  explicit Force(const PluginConfig& c) : link_(c.text("bodyName")) {}
  double update_rate() const override { return 0.0; }
  void set_wrench(const Wrench& w) override { wrench_ = w; }
  void command(const std::string&, const Command& value, CommandResult*) override { set_wrench(std::get<Wrench>(value)); }
  void reset() override { wrench_ = Wrench(); }
  void pre_physics(const StepContext&, RobotHandle& robot) override {
    if (wrench_.force.isZero() && wrench_.torque.isZero()) return;
    robot.apply_wrench(link_, wrench_, link_com(robot, link_), false);
  }

 private:
  std::string link_;
  Wrench wrench_;
};

void finish(ResolveContext& ctx) {
  const PluginConfig& c = ctx.config();
  // upstream's Load logs these and returns: the plug-in is inert, the model loads
  if (c.param("bodyName").from_default) ctx.drop("bodyName", "force plugin missing <bodyName>, cannot proceed");
  if (!ctx.model().find_link(c.text("bodyName")))
    ctx.drop("bodyName", "gazebo_ros_force plugin error: link named: " + c.text("bodyName") + " does not exist");
  if (c.param("topicName").from_default) ctx.drop("topicName", "force plugin missing <topicName>, cannot proceed");
  ctx.config().link = c.text("bodyName");
}

}  // namespace

const PluginKind& force_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "force";
    k.filenames = {"libgazebo_ros_force.so"};
    k.schema = {
        {"robotNamespace", T, "", ""},
        {"bodyName", T, "", ""},
        {"topicName", T, "", ""},
    };
    k.ignored = {{"alwaysOn", ""}, {"updateRate", "force applies its wrench every step"}};
    k.inputs = topic_input("wrench", InputType::Wrench, "topicName", 1);
    k.finish = finish;
    k.make = [](const PluginConfig& c, const std::string&, uint64_t) -> std::unique_ptr<Plugin> {
      return std::make_unique<Force>(c);
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
