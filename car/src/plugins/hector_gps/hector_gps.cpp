// The hector GPS: the link origin's world position and velocity through two SensorModels (position; velocity,
// whose drift also integrates into the position's), mapped to latitude/longitude on the WGS84 ellipsoid's local
// radii at referenceLatitude, rotated by referenceHeading; 4 Hz by default. Per docs/COMPAT-sensors.md.
#include "hector_gps.hpp"

#include <cmath>

#include "../common/hector_sensor_model.hpp"

namespace car_sim {

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType Fr = ParamType::Frame;
constexpr ParamType N = ParamType::Number;
constexpr ParamType I = ParamType::Integer;
constexpr ParamType F = ParamType::Flag;
constexpr double kDeg = M_PI / 180.0;
// WGS84
constexpr double kEquatorialRadius = 6378137.0;          // [m]
constexpr double kFlattening = 1.0 / 298.257223563;
constexpr double kExcentricity2 = 2 * kFlattening - kFlattening * kFlattening;

class HectorGps : public Plugin {
 public:
  HectorGps(const PluginConfig& c, const std::string& robot, uint64_t seed)
      : link_(c.text("bodyName")), timer_(c), rng0_(plugin_rng(seed, robot, c.name)) {
    lat0_ = c.number("referenceLatitude");
    lon0_ = c.number("referenceLongitude");
    heading_ = c.number("referenceHeading") * kDeg;
    alt0_ = c.number("referenceAltitude");
    proto_.status = static_cast<int>(c.number("status"));
    proto_.service = static_cast<int>(c.number("service"));
    position_.load(c, "");
    velocity_.load(c, "velocity");
    // [m] radii of curvature at the reference latitude
    const double s = std::sin(lat0_ * kDeg);
    const double temp = 1.0 / (1.0 - kExcentricity2 * s * s);
    const double prime_vertical = kEquatorialRadius * std::sqrt(temp);
    radius_north_ = prime_vertical * (1 - kExcentricity2) * temp;
    radius_east_ = prime_vertical * std::cos(lat0_ * kDeg);
    for (int i = 0; i < 3; ++i)
      proto_.position_variance[i] = position_.drift[i] * position_.drift[i] +
                                    position_.gaussian_noise[i] * position_.gaussian_noise[i];
    reset();
  }

  double update_rate() const override { return timer_.rate(); }
  Schedule schedule(double dt, uint64_t) const override { return timer_.schedule(dt); }
  void reset() override {
    rng_ = rng0_;
    position_.reset(rng_);
    velocity_.reset(rng_);
    last_.unset();
  }
  void set_active(bool active) override {
    if (active) last_.unset();
  }

  void post_physics(const StepContext& ctx, const RobotHandle& robot, OutputQueue* out) override {
    const double dt = last_.since(ctx);  // [s] since the last update
    const ModelState s = robot.link_state(link_);
    const Eigen::Vector3d v = velocity_(s.linear, dt, rng_);
    const Eigen::Vector3d p = position_(s.pose.translation(), dt, rng_);
    position_.set_drift(position_.drift_now() + dt * velocity_.drift_now());
    const double ch = std::cos(heading_), sh = std::sin(heading_);
    auto o = std::make_unique<GpsOut>(proto_);
    o->latitude = lat0_ + (ch * p.x() + sh * p.y()) / radius_north_ / kDeg;
    o->longitude = lon0_ - (-sh * p.x() + ch * p.y()) / radius_east_ / kDeg;
    o->altitude = alt0_ + p.z();
    o->velocity = Eigen::Vector3d(ch * v.x() + sh * v.y(), -sh * v.x() + ch * v.y(), v.z());
    out->push_back(std::move(o));
  }

 private:
  std::string link_;
  hector::UpdateTimer timer_;
  double lat0_ = 0, lon0_ = 0, heading_ = 0, alt0_ = 0, radius_north_ = 0, radius_east_ = 0;
  hector::SensorModel<3> position_, velocity_;
  std::mt19937_64 rng0_, rng_;
  GpsOut proto_;
  hector::LastUpdate last_;
};

void finish(ResolveContext& ctx) {
  PluginConfig& c = ctx.config();
  if (c.text("bodyName").empty()) ctx.set("bodyName", ctx.model().root_link);
  const std::string body = c.text("bodyName");
  // upstream's Load logs this and returns: the plug-in is inert, the model loads
  if (!ctx.model().find_link(body)) ctx.drop("bodyName", "GazeboRosGps plugin error: bodyName: " + body + " does not exist");
  c.link = body;
  if (std::abs(c.number("referenceLatitude")) >= 90) ctx.fail("referenceLatitude", "must be inside (-90, 90) deg");
  hector::finish_timer(ctx);
  hector::finish_model(ctx, "", 3);
  hector::finish_model(ctx, "velocity", 3);
  if (c.flag("useWorldSphericalCoordinates"))
    ctx.warn(Severity::Warning, "key-unsupported", "useWorldSphericalCoordinates",
             "car does not read the world's <spherical_coordinates>: the reference* keys are used");
}

}  // namespace

void GpsOut::visit(FieldVisitor& v) const {
  v.number("latitude", latitude);
  v.number("longitude", longitude);
  v.number("altitude", altitude);
  v.integer("status", status);
  v.integer("service", service);
  v.vector("position_variance", position_variance.data(), 3);
  v.vector("velocity", velocity.data(), 3);
}

const PluginKind& hector_gps_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "hector_gps";
    k.filenames = {"libhector_gazebo_ros_gps.so"};
    k.model_level = true;
    k.schema = {
        {"robotNamespace", T, "", ""},
        {"bodyName", T, "", ""},
        {"frameId", Fr, "/world", ""},
        {"topicName", T, "fix", ""},
        {"velocityTopicName", T, "fix_velocity", ""},
        {"referenceLatitude", N, "49.9", "deg"},
        {"referenceLongitude", N, "8.9", "deg"},
        {"referenceHeading", N, "0", "deg"},
        {"referenceAltitude", N, "0", "m"},
        {"status", I, "0", ""},
        {"service", I, "0", ""},
        {"useWorldSphericalCoordinates", F, "false", ""},
    };
    for (const auto& d : hector::timer_schema("4")) k.schema.push_back(d);
    for (const auto& d : hector::model_schema("", "m")) k.schema.push_back(d);
    for (const auto& d : hector::model_schema("velocity", "m/s")) k.schema.push_back(d);
    k.ignored = {{"alwaysOn", ""}};
    k.lazy = true;
    k.output_group = "gps";
    // sensor_msgs/NavSatFix on topicName, then geometry_msgs/Vector3Stamped on velocityTopicName, queue 10, frameId
    k.outputs = [](const PluginConfig& c, const std::string& robot, const Environment&) {
      return std::vector<OutputPort>{
          sensor_port(c, robot, "fix", sample_type<NavSatFixSample>(), "topicName", c.text("frameId"), 10),
          sensor_port(c, robot, "velocity", sample_type<Vector3Sample>(), "velocityTopicName", c.text("frameId"), 10)};
    };
    k.finish = finish;
    k.make = [](const PluginConfig& c, const std::string& robot, uint64_t seed) -> std::unique_ptr<Plugin> {
      return std::make_unique<HectorGps>(c, robot, seed);
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
