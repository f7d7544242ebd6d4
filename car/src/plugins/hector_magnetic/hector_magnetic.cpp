// The hector magnetometer: field_world = magnitude (cos i cos(h - d), cos i sin(h - d), -sin i) with
// inclination i, declination d and referenceHeading h [deg in the file]; the reading is the field in bodyName's
// frame through the SensorModel, at updateRate (default every step). Per docs/COMPAT-sensors.md.
#include "hector_magnetic.hpp"

#include <cmath>

#include "../common/hector_sensor_model.hpp"

namespace car_sim {

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType Fr = ParamType::Frame;
constexpr ParamType N = ParamType::Number;
constexpr ParamType F = ParamType::Flag;
constexpr double kDeg = M_PI / 180.0;

class HectorMagnetic : public Plugin {
 public:
  HectorMagnetic(const PluginConfig& c, const std::string& robot, uint64_t seed)
      : link_(c.text("bodyName")), timer_(c), rng0_(plugin_rng(seed, robot, c.name)) {
    const double m = c.number("magnitude"), h = c.number("referenceHeading") * kDeg,
                 d = c.number("declination") * kDeg, i = c.number("inclination") * kDeg;
    field_world_ = m * Eigen::Vector3d(std::cos(i) * std::cos(h - d), std::cos(i) * std::sin(h - d), -std::sin(i));
    model_.load(c, "");
    reset();
  }

  double update_rate() const override { return timer_.rate(); }
  Schedule schedule(double dt, uint64_t) const override { return timer_.schedule(dt); }
  void reset() override {
    rng_ = rng0_;
    model_.reset(rng_);
    last_.unset();
  }
  void set_active(bool active) override {
    if (active) last_.unset();
  }

  void post_physics(const StepContext& ctx, const RobotHandle& robot, OutputQueue* out) override {
    const double dt = last_.since(ctx);  // [s] since the last update
    const Eigen::Isometry3d pose = robot.link_pose(link_);
    auto o = std::make_unique<MagneticOut>();
    o->field = model_(pose.linear().transpose() * field_world_, dt, rng_);
    out->push_back(std::move(o));
  }

 private:
  std::string link_;
  hector::UpdateTimer timer_;
  Eigen::Vector3d field_world_;
  hector::SensorModel<3> model_;
  std::mt19937_64 rng0_, rng_;
  hector::LastUpdate last_;
};

void finish(ResolveContext& ctx) {
  PluginConfig& c = ctx.config();
  if (c.text("bodyName").empty()) ctx.set("bodyName", ctx.model().root_link);
  const std::string body = c.text("bodyName");
  // upstream's Load logs this and returns: the plug-in is inert, the model loads
  if (!ctx.model().find_link(body)) ctx.drop("bodyName", "GazeboRosMagnetic plugin error: bodyName: " + body + " does not exist");
  c.link = body;
  if (c.text("frameId").empty()) ctx.set("frameId", body);
  hector::finish_timer(ctx);
  hector::finish_model(ctx, "", 3);
  if (c.flag("useWorldSphericalCoordinates"))
    ctx.warn(Severity::Warning, "key-unsupported", "useWorldSphericalCoordinates",
             "car does not read the world's <spherical_coordinates>: referenceHeading is used");
}

}  // namespace

void MagneticOut::visit(FieldVisitor& v) const { v.vector("magnetic_field", field.data(), 3); }

const PluginKind& hector_magnetic_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "hector_magnetic";
    k.filenames = {"libhector_gazebo_ros_magnetic.so"};
    k.model_level = true;
    k.schema = {
        {"robotNamespace", T, "", ""},
        {"topicName", T, "magnetic", ""},
        {"bodyName", T, "", ""},
        {"frameId", Fr, "", ""},
        {"magnitude", N, "1.0", ""},
        {"referenceHeading", N, "0", "deg"},
        {"declination", N, "0", "deg"},
        {"inclination", N, "60", "deg"},
        {"useMagneticFieldMsgs", F, "false", ""},
        {"useWorldSphericalCoordinates", F, "false", ""},
    };
    for (const auto& d : hector::timer_schema("0")) k.schema.push_back(d);
    for (const auto& d : hector::model_schema("", "")) k.schema.push_back(d);
    k.ignored = {{"alwaysOn", ""}};
    k.lazy = true;
    k.output_group = "magnetic";
    // geometry_msgs/Vector3Stamped, or sensor_msgs/MagneticField with useMagneticFieldMsgs, on topicName in frameId,
    // queue 1
    k.outputs = [](const PluginConfig& c, const std::string& robot, const Environment&) {
      const SampleType type =
          c.flag("useMagneticFieldMsgs") ? sample_type<MagneticFieldSample>() : sample_type<Vector3Sample>();
      return std::vector<OutputPort>{sensor_port(c, robot, "magnetic", type, "topicName", c.text("frameId"), 1)};
    };
    k.finish = finish;
    k.make = [](const PluginConfig& c, const std::string& robot, uint64_t seed) -> std::unique_ptr<Plugin> {
      return std::make_unique<HectorMagnetic>(c, robot, seed);
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
