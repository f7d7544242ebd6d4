// libgazebo_ros_hand_of_god.so (gazebo_plugins, Noetic): linkName pulled toward TF world -> <frameId>_desired with
// kl, ka and dampings cl = 2 sqrt(kl m), ca = 2 sqrt(ka Ixx); its gravity off; its pose out every step (TF
// world -> <frameId>_actual). Per docs/COMPAT-plugins.md.
#include "hand_of_god.hpp"

#include <cmath>

namespace car_sim {

void PoseOut::visit(FieldVisitor& v) const {
  const Eigen::Vector3d p = pose.translation();
  v.vector("position", p.data(), 3);
  const Eigen::Quaterniond q(pose.linear());
  const double quat[4] = {q.x(), q.y(), q.z(), q.w()};
  v.vector("orientation", quat, 4);
}

Wrench hand_of_god_wrench(const Eigen::Isometry3d& pose, const Eigen::Vector3d& v, const Eigen::Vector3d& w_link,
                          const Eigen::Isometry3d& target, double kl, double ka, double cl, double ca) {
  Wrench w;
  w.force = kl * (target.translation() - pose.translation()) - cl * v;
  Eigen::Quaterniond err(pose.linear().transpose() * target.linear());
  if (err.w() < 0) err.coeffs() *= -1.0;  // the shorter way round
  const Eigen::AngleAxisd aa(err);
  const Eigen::Vector3d log_q = aa.axis() * (aa.angle() / 2.0);  // [rad] half the rotation vector
  w.torque = ka * log_q - ca * w_link;
  return w;
}

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType Fr = ParamType::Frame;
constexpr ParamType N = ParamType::Number;

class HandOfGod : public Plugin, public PoseTarget {
 public:
  explicit HandOfGod(const PluginConfig& c)
      : link_(c.text("linkName")), kl_(c.number("kl")), ka_(c.number("ka")) {}

  double update_rate() const override { return 0.0; }

  void configure(RobotHandle& robot) override {
    const Link* l = robot.model().find_link(link_);
    mass_ = l->inertial ? l->inertial->mass : 0.0;
    const double ixx = l->inertial ? l->inertial->inertia(0, 0) : 0.0;
    cl_ = 2.0 * std::sqrt(kl_ * mass_);
    ca_ = 2.0 * std::sqrt(ka_ * ixx);
  }

  void set_target(const Eigen::Isometry3d& p) override {
    target_ = p;
    has_target_ = true;
  }
  void reset() override { has_target_ = false; }
  // a failed lookup: upstream's UpdateChild returns before its force and its TF, for that update
  void command(const std::string&, const Command& value, CommandResult*) override {
    const PoseCommand& c = std::get<PoseCommand>(value);
    if (c.found) set_target(c.pose);
    else has_target_ = false;
  }

  void pre_physics(const StepContext& ctx, RobotHandle& robot) override {
    // the link's gravity off: an equal and opposite force at its centre of mass [N], world frame
    const Link* l = robot.model().find_link(link_);
    const Eigen::Isometry3d pose = robot.link_pose(link_);
    const Eigen::Vector3d com = pose * (l->inertial ? Eigen::Vector3d(l->inertial->origin.translation()) : Eigen::Vector3d::Zero());
    Wrench g;
    g.force = -mass_ * ctx.world->environment().gravity;
    robot.apply_wrench(link_, g, com, false);
    if (!has_target_) return;
    const ModelState s = robot.link_state(link_);
    const Eigen::Vector3d w_link = s.pose.linear().transpose() * s.angular;
    const Wrench w = hand_of_god_wrench(s.pose, s.linear, w_link, target_, kl_, ka_, cl_, ca_);
    // force at the centre of mass (upstream AddForce), torque in the link frame (AddRelativeTorque)
    Wrench f;
    f.force = w.force;
    robot.apply_wrench(link_, f, com, false);
    Wrench t;
    t.torque = w.torque;
    robot.apply_wrench(link_, t, Eigen::Vector3d::Zero(), true);
  }

  // <frameId>_actual goes out only after a lookup that found the target, as upstream
  void post_physics(const StepContext&, const RobotHandle& robot, OutputQueue* out) override {
    if (!has_target_) return;
    auto o = std::make_unique<PoseOut>();
    o->pose = robot.link_pose(link_);
    out->push_back(std::move(o));
  }

 private:
  std::string link_;
  double kl_, ka_, cl_ = 0.0, ca_ = 0.0, mass_ = 0.0;
  Eigen::Isometry3d target_ = Eigen::Isometry3d::Identity();
  bool has_target_ = false;
};

void finish(ResolveContext& ctx) {
  const PluginConfig& c = ctx.config();
  // upstream's Load logs these and returns: the plug-in is inert, the model loads
  if (c.param("linkName").from_default) ctx.drop("linkName", "The hand-of-god plugin requires a `linkName` parameter tag");
  if (!ctx.model().find_link(c.text("linkName"))) ctx.drop("linkName", "Floating link not found");
  if (c.number("kl") < 0) ctx.fail("kl", "must be >= 0");
  if (c.number("ka") < 0) ctx.fail("ka", "must be >= 0");
  ctx.config().link = c.text("linkName");
}

}  // namespace

const PluginKind& hand_of_god_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "hand_of_god";
    k.filenames = {"libgazebo_ros_hand_of_god.so"};
    k.schema = {
        {"robotNamespace", T, "", ""},
        {"frameId", Fr, "hog", ""},
        {"kl", N, "200", "N/m"},
        {"ka", N, "200", "N m/rad"},
        {"linkName", T, "", ""},
    };
    k.ignored = {{"alwaysOn", ""}, {"updateRate", ""}};
    // its pushes run every step regardless; only the actual-pose output is lazy (TF has no subscriber count: a
    // Transform port is always listened)
    k.lazy = true;
    k.output_group = "poses";
    // the target is read from TF: world -> <frameId>_desired
    k.inputs = [](const PluginConfig& c, const std::string&) {
      std::string f = c.text("frameId");
      while (!f.empty() && f.front() == '/') f.erase(f.begin());
      InputPort p;
      p.name = "target";
      p.type = InputType::Pose;
      p.frame = f + "_desired";
      p.parent_frame = "world";
      return std::vector<InputPort>{p};
    };
    // the link's pose on TF: world -> <frameId>_actual
    k.outputs = [](const PluginConfig& c, const std::string&, const Environment&) {
      OutputPort p;
      p.name = "actual";
      p.type = sample_type<TransformSample>();
      p.frame = "world";
      p.child_frame = strip_frame(c.text("frameId")) + "_actual";
      p.frame_rule = FrameRule::NoPrefix;
      return std::vector<OutputPort>{p};
    };
    k.finish = finish;
    k.make = [](const PluginConfig& c, const std::string&, uint64_t) -> std::unique_ptr<Plugin> {
      return std::make_unique<HandOfGod>(c);
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
