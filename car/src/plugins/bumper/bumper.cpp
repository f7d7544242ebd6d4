// libgazebo_ros_bumper.so (gazebo_plugins, Noetic) in <sensor type="contact">: on each sensor update while
// subscribed, every contact of the watched collision, grouped by the other body; positions and normals world
// frame, wrenches the force on this body. Per docs/COMPAT-plugins.md.
#include "bumper.hpp"

#include <map>

namespace car_sim {

std::string link_of_collision(const RobotModel& model, const std::string& collision) {
  std::string s = collision;
  const std::string lump = "_fixed_joint_lump__";
  const auto at = s.rfind(lump);
  if (at != std::string::npos) s = s.substr(at + lump.size());
  // "LINK_collision" or "LINK_collision_N"
  const auto c = s.rfind("_collision");
  if (c != std::string::npos) s = s.substr(0, c);
  if (model.find_link(s)) return s;
  // a named <collision name="N"> of a lumped link is "PARENT_fixed_joint_lump__N_collision" (Kobuki's bumper's
  // base_footprint_fixed_joint_lump__base_collision): car keeps no collision names, and a contact sensor watches
  // its link's body, which is PARENT's
  if (at != std::string::npos && model.find_link(collision.substr(0, at))) return collision.substr(0, at);
  return "";
}

void ContactsOut::visit(FieldVisitor& v) const {
  v.integer("count", static_cast<int64_t>(states.size()));
  std::string names;
  std::vector<float> rows;  // per point: position xyz, normal xyz, depth, force xyz
  for (const auto& s : states) {
    names += (names.empty() ? "" : ";") + s.collision1 + "," + s.collision2;
    for (size_t k = 0; k < s.positions.size(); ++k) {
      for (int i = 0; i < 3; ++i) rows.push_back(static_cast<float>(s.positions[k][i]));
      for (int i = 0; i < 3; ++i) rows.push_back(static_cast<float>(s.normals[k][i]));
      rows.push_back(static_cast<float>(s.depths[k]));
      for (int i = 0; i < 3; ++i) rows.push_back(static_cast<float>(s.wrenches[k].force[i]));
    }
  }
  v.text("pairs", names);
  v.array("points", rows.data(), {rows.size() / 10, 10});
}

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType Fr = ParamType::Frame;
constexpr ParamType N = ParamType::Number;

class Bumper : public Plugin {
 public:
  Bumper(const PluginConfig& c, const std::string& robot)
      : rate_(c.number("update_rate")), link_(c.link) {
    const std::string& col = c.text("contact/collision");
    collision1_ = robot + "::" + link_ + "::" + (col.empty() ? link_ + "_collision" : col);
  }

  double update_rate() const override { return rate_; }

  void post_physics(const StepContext&, const RobotHandle& robot, OutputQueue* out) override {
    auto o = std::make_unique<ContactsOut>();
    std::map<std::string, size_t> by_other;
    for (const LinkContact& c : robot.link_contacts(link_)) {
      auto it = by_other.find(c.other);
      if (it == by_other.end()) {
        it = by_other.emplace(c.other, o->states.size()).first;
        o->states.emplace_back();
        o->states.back().collision1 = collision1_;
        o->states.back().collision2 = c.other;
      }
      ContactPair& p = o->states[it->second];
      Wrench w;
      w.force = c.normal * c.normal_force;
      p.wrenches.push_back(w);
      p.total.force += w.force;
      p.positions.push_back(c.position);
      p.normals.push_back(c.normal);
      p.depths.push_back(c.depth);
    }
    out->push_back(std::move(o));
  }

 private:
  double rate_;
  std::string link_, collision1_;
};

void finish(ResolveContext& ctx) {
  const std::string& col = ctx.config().text("contact/collision");
  if (col.empty()) {
    ctx.warn(Severity::Warning, "contact-no-collision", "",
             "the contact sensor names no <contact><collision>; car watches its link '" + ctx.config().link + "'");
    return;
  }
  const std::string link = link_of_collision(ctx.model(), col);
  if (link.empty())
    ctx.fail_sensor("contact/collision", "'" + col + "' is not a collision of the model (Gazebo names them LINK_collision)");
  ctx.config().link = link;
}

}  // namespace

const PluginKind& bumper_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "bumper";
    k.filenames = {"libgazebo_ros_bumper.so"};
    k.model_level = false;
    k.sensor_types = {"contact"};
    k.sensor_schema = {
        {"update_rate", N, "0", "Hz"},
        {"contact/collision", T, "", ""},
        {"contact/topic", T, "__default_topic__", ""},
    };
    k.schema = {
        {"robotNamespace", T, "", ""},
        {"bumperTopicName", T, "bumper_states", ""},
        {"frameName", Fr, "world", ""},
    };
    k.ignored = {{"alwaysOn", ""}, {"updateRate", "the contact sensor's <update_rate> sets the rate"}};
    k.lazy = true;
    k.output_group = "contacts";
    // gazebo_msgs/ContactsState on bumperTopicName, header frame frameName, queue 1
    // frame_name_ = tf::resolve(getParam("tf_prefix"), frameName): tf_prefix of the plug-in's own namespace
    k.outputs = [](const PluginConfig& c, const std::string& robot, const Environment&) {
      OutputPort p = sensor_port(c, robot, "contacts", sample_type<ContactsSample>(), "bumperTopicName",
                                 c.text("frameName"), 1);
      p.frame_rule = FrameRule::PrefixHere;
      return std::vector<OutputPort>{p};
    };
    k.finish = finish;
    k.make = [](const PluginConfig& c, const std::string& robot, uint64_t) -> std::unique_ptr<Plugin> {
      return std::make_unique<Bumper>(c, robot);
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
