// What every plug-in kind shares: the integer-tick schedule, the noise generators, configuration accessors and
// the resolve context.
#include "car_sim/plugin.hpp"

#include <array>
#include <cctype>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "car_sim/drive.hpp"
#include "xml_util.hpp"

namespace car_sim {

// ---- Schedule -------------------------------------------------------------------------------------------------

namespace {

// The fraction num/den nearest to x with den <= 1e6 (continued fractions), e.g. 181.8181... -> 2000/11.
void rational(double x, uint64_t* num, uint64_t* den) {
  uint64_t h0 = 0, h1 = 1, k0 = 1, k1 = 0;  // convergents h/k
  double r = x;
  for (int i = 0; i < 40; ++i) {
    const double a = std::floor(r);
    const uint64_t ai = static_cast<uint64_t>(a);
    const uint64_t h2 = ai * h1 + h0, k2 = ai * k1 + k0;
    if (k2 > 1000000) break;
    h0 = h1, h1 = h2, k0 = k1, k1 = k2;
    if (std::abs(static_cast<double>(h1) / static_cast<double>(k1) - x) <= 1e-9 * x) break;
    if (r - a < 1e-12) break;
    r = 1.0 / (r - a);
  }
  *num = std::max<uint64_t>(h1, 1);
  *den = std::max<uint64_t>(k1, 1);
}

}  // namespace

Schedule::Schedule(double rate, double dt, uint64_t start_tick) {
  if (rate > 0.0 && dt > 0.0) {
    const double period = 1.0 / (rate * dt);  // [ticks]
    if (period > 1.0) rational(period, &num_, &den_);
  }
  restart(start_tick);
}

Schedule Schedule::absolute(double period, int64_t offset_ns, double dt) {
  Schedule s;
  s.mode_ = Mode::Absolute;
  s.period_ = period;
  s.offset_ns_ = offset_ns;
  s.dt_ = dt;
  return s;
}

bool Schedule::absolute_due(uint64_t tick) const {
  if (period_ == 0.0) return true;
  const double fraction = std::fmod(common_time_double(tick_time_ns(tick, dt_) - offset_ns_) + dt_ / 2.0, period_);
  return fraction >= 0.0 && fraction < dt_;
}

Schedule Schedule::update_clock(double rate, double dt, uint64_t start_tick) {
  Schedule s;
  s.mode_ = Mode::Clock;
  s.clock_ = UpdateClock(rate);
  s.dt_ = dt;
  s.restart(start_tick);
  return s;
}

Schedule Schedule::since_last(double rate, double dt, uint64_t start_tick, bool from_zero) {
  Schedule s;
  s.mode_ = Mode::SinceLast;
  s.period_ = rate > 0 ? 1.0 / rate : 0.0;
  s.dt_ = dt;
  s.from_zero_ = from_zero;
  s.restart(start_tick);
  return s;
}

void Schedule::restart(uint64_t start_tick) {
  if (mode_ == Mode::Clock) clock_.start(start_tick, dt_);
  if (mode_ == Mode::SinceLast) last_ns_ = from_zero_ ? 0 : tick_time_ns(start_tick, dt_);
  start_ = start_tick;
  k_ = 1;
  next_ = start_ + (k_ * num_ + den_ - 1) / den_;
}

void Schedule::advance(uint64_t tick) {
  if (mode_ == Mode::Clock) {
    clock_.since(tick, dt_);
    return;
  }
  if (mode_ == Mode::SinceLast) {
    last_ns_ = tick_time_ns(tick, dt_);
    return;
  }
  ++k_;
  next_ = start_ + (k_ * num_ + den_ - 1) / den_;
  if (next_ <= tick) restart(tick);  // after a pause of the world's stepping: no burst
}

// ---- noise ----------------------------------------------------------------------------------------------------

namespace {

// FNV-1a: a fixed hash, so a plug-in's noise does not depend on the standard library's std::hash.
uint64_t fnv1a(const std::string& s) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace

std::mt19937_64 plugin_rng(uint64_t seed, const std::string& robot, const std::string& name) {
  const uint64_t h = fnv1a(robot + "/" + name);
  std::seed_seq seq{static_cast<uint32_t>(seed), static_cast<uint32_t>(seed >> 32), static_cast<uint32_t>(h),
                    static_cast<uint32_t>(h >> 32)};
  return std::mt19937_64(seq);
}

// ---- PluginConfig ---------------------------------------------------------------------------------------------

const ResolvedParam& PluginConfig::param(const std::string& key) const {
  for (const auto& p : params)
    if (p.key == key) return p;
  throw std::out_of_range("plug-in '" + name + "' has no key '" + key + "'");
}

bool PluginConfig::has(const std::string& key) const {
  for (const auto& p : params)
    if (p.key == key) return true;
  return false;
}

const std::string& PluginConfig::text(const std::string& key) const { return param(key).value; }

double PluginConfig::number(const std::string& key) const {
  const auto v = detail::parse_number(param(key).value);
  if (!v) throw std::invalid_argument("plug-in '" + name + "' key '" + key + "' is not a number");
  return *v;
}

bool PluginConfig::flag(const std::string& key) const {
  bool b = false;
  if (!parse_flag(param(key).value, &b))
    throw std::invalid_argument("plug-in '" + name + "' key '" + key + "' is not a boolean");
  return b;
}

bool parse_flag(const std::string& text, bool* value) {
  std::string t = detail::trim(text);
  for (auto& c : t) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (t == "true" || t == "1") {
    *value = true;
    return true;
  }
  if (t == "false" || t == "0") {
    *value = false;
    return true;
  }
  return false;
}

// ---- ResolveContext -------------------------------------------------------------------------------------------

ResolveContext::ResolveContext(const RobotModel& model, const PluginSpec& spec, const SensorSpec* sensor,
                               PluginConfig* config, std::vector<Diagnostic>* diagnostics)
    : model_(model), spec_(spec), sensor_(sensor), config_(config), diagnostics_(diagnostics) {}

std::string ResolveContext::where(const std::string& key) const {
  const std::string pl = "plugin[" + spec_.name + "]";
  const std::string base = sensor_ ? "sensor[" + sensor_->name + "]/" + pl : "gazebo/" + pl;
  return key.empty() ? base : base + "/" + key;
}

void ResolveContext::fail(const std::string& key, const std::string& reason) const {
  throw LoadError(model_.source, spec_.line, where(key), reason);
}

void ResolveContext::drop(const std::string& key, const std::string& reason) const {
  throw PluginNotLoaded(model_.source, spec_.line, where(key), reason);
}

void ResolveContext::fail_sensor(const std::string& key, const std::string& reason) const {
  const std::string s = sensor_ ? "sensor[" + sensor_->name + "]" : where("");
  throw LoadError(model_.source, sensor_ ? sensor_->line : spec_.line, key.empty() ? s : s + "/" + key, reason);
}

void ResolveContext::warn(Severity severity, const std::string& code, const std::string& key,
                          const std::string& message) {
  diagnostics_->push_back({severity, code, where(key), message, spec_.line});
}

void warn_negative_rate(ResolveContext& ctx, const std::string& key) {
  if (ctx.config().number(key) < 0)
    ctx.warn(Severity::Warning, "key-value", key,
             "<" + key + "> " + ctx.config().text(key) + " is not > 0: the plug-in updates every step, as upstream");
}

void check_offsets(ResolveContext& ctx) {
  const PluginConfig& c = ctx.config();
  for (const char* key : {"xyzOffset", "rpyOffset"})
    if (!detail::parse_numbers(c.text(key), 3)) ctx.fail(key, "'" + c.text(key) + "' is not 3 numbers");
}

Eigen::Matrix3d rpy_offset(const PluginConfig& c) {
  const auto rpy = detail::parse_numbers(c.text("rpyOffset"), 3);
  return detail::rpy_to_matrix((*rpy)[0], (*rpy)[1], (*rpy)[2]);
}

void ResolveContext::set(const std::string& key, const std::string& value) {
  for (auto& p : config_->params)
    if (p.key == key) {
      p.value = value;
      return;
    }
  throw std::out_of_range("plug-in '" + spec_.name + "' has no key '" + key + "'");
}

// ---- OdometryOut ----------------------------------------------------------------------------------------------

void OdometryOut::visit(FieldVisitor& v) const {
  const Eigen::Vector3d p = pose.translation();
  v.vector("position", p.data(), 3);
  const Eigen::Quaterniond q(pose.linear());
  const double quat[4] = {q.x(), q.y(), q.z(), q.w()};
  v.vector("orientation", quat, 4);
  v.number("yaw", std::atan2(pose.linear()(1, 0), pose.linear()(0, 0)));
  v.vector("linear", linear.data(), 3);
  v.vector("angular", angular.data(), 3);
}

}  // namespace car_sim

// ---- ports ----------------------------------------------------------------------------------------------------

namespace car_sim {

bool namespace_rule(const std::string& filename, NamespaceRule* rule) {
  const PluginKind* k = plugin_kind_for_file(filename);
  *rule = NamespaceRule::AsWritten;
  if (!k) return false;
  const auto it = k->file_namespace_rules.find(filename);
  *rule = it == k->file_namespace_rules.end() ? k->namespace_rule : it->second;
  return true;
}

std::string plugin_robot_namespace(const PluginConfig& c, const std::string& model_name) {
  NamespaceRule rule;
  namespace_rule(c.filename, &rule);
  const bool present = c.has("robotNamespace") && !c.param("robotNamespace").from_default;
  std::string ns = present ? c.text("robotNamespace") : "";
  const bool to_model = present ? ns.empty() && (rule == NamespaceRule::ModelName || rule == NamespaceRule::EmptyIsModel)
                                : (rule == NamespaceRule::ModelName || rule == NamespaceRule::AbsentIsModel);
  if (to_model) ns = model_name;
  // "/" and "" are the global namespace; "r1/" is what NodeHandle("r1" + "/") names
  while (!ns.empty() && ns.front() == '/') ns.erase(ns.begin());
  while (!ns.empty() && ns.back() == '/') ns.pop_back();
  return ns;
}

OutputPort odometry_port(const PluginConfig& c, const std::string& robot, const std::string& topic_key, uint32_t queue,
                         TfOrder tf, double cov_x, double cov_y, double cov_yaw) {
  OutputPort p;
  p.name = "odom";
  p.type = sample_type<OdometrySample>();
  p.ns = plugin_robot_namespace(c, robot);
  p.topic = resolve_topic(p.ns, c.text(topic_key));
  p.queue = queue;
  p.frame = c.text("odometryFrame");
  p.child_frame = c.text("robotBaseFrame");
  p.tf = tf;
  p.pose_covariance = {cov_x, cov_y, 1e12, 1e12, 1e12, cov_yaw};
  return p;
}

OutputPort joint_states_port(const PluginConfig& c, const std::string& robot, uint32_t queue) {
  OutputPort p;
  p.name = "joint_states";
  p.type = sample_type<JointStatesSample>();
  p.ns = plugin_robot_namespace(c, robot);
  p.topic = resolve_topic(p.ns, "joint_states");
  p.queue = queue;
  return p;
}

OutputPort wheel_tf_port(const PluginConfig& c, const std::string& robot) {
  OutputPort p;
  p.name = "wheel_tf";
  p.type = sample_type<JointTransformsSample>();
  p.ns = plugin_robot_namespace(c, robot);
  return p;
}

OutputPort sensor_port(const PluginConfig& c, const std::string& robot, const std::string& name, SampleType type,
                       const std::string& topic_key, const std::string& frame, uint32_t queue) {
  OutputPort p;
  p.name = name;
  p.type = type;
  p.ns = plugin_robot_namespace(c, robot);
  p.topic = resolve_topic(p.ns, c.text(topic_key));
  p.queue = queue;
  p.frame = frame;
  p.frame_rule = FrameRule::NoPrefix;
  return p;
}

namespace {

// The sample types that derive from another with nothing of their own (CameraInfoSample from ImageSample): for each
// alternative of Sample, the index of the one it derives from (0: none) and how to make it from that one.
template <size_t To, size_t From>
constexpr bool derives() {
  using T = std::variant_alternative_t<To, Sample>;
  using F = std::variant_alternative_t<From, Sample>;
  if constexpr (To == From || From == 0 || !std::is_class_v<F> || !std::is_class_v<T>) return false;
  else return std::is_base_of_v<F, T> && sizeof(F) == sizeof(T);
}
template <size_t To, size_t... Fs>
constexpr size_t base_of(std::index_sequence<Fs...>) {
  size_t base = 0;
  ((base = base == 0 && derives<To, Fs>() ? Fs : base), ...);
  return base;
}
template <size_t To>
constexpr size_t kBase = base_of<To>(std::make_index_sequence<detail::kSampleTypes>());
template <size_t To>
Sample from_base(const Sample& s) {
  if constexpr (kBase<To> == 0) {
    return {};
  } else {
    std::variant_alternative_t<To, Sample> t;
    static_cast<std::variant_alternative_t<kBase<To>, Sample>&>(t) = std::get<kBase<To>>(s);
    return Sample(std::in_place_index<To>, std::move(t));
  }
}
struct Derived {
  size_t base;                         // 0: none
  Sample (*make)(const Sample& base);  // the sample made from its base's
};
template <size_t... Ts>
constexpr std::array<Derived, sizeof...(Ts)> derived_types(std::index_sequence<Ts...>) {
  return {{{kBase<Ts>, &from_base<Ts>}...}};
}
constexpr auto kDerived = derived_types(std::make_index_sequence<detail::kSampleTypes>());

}  // namespace

Sample SampleList::find(SampleType type, std::string_view port, size_t frame) const {
  const Derived& d = kDerived[type.index];
  const Entry* any = nullptr;
  const Entry* named = nullptr;
  for (const Entry& e : entries_) {
    const size_t i = e.sample.index();
    if (i == 0 || (i != type.index && i != d.base) || e.frame != frame) continue;
    if (e.port.empty()) {
      if (!any) any = &e;
    } else if (e.port == port) {
      named = &e;
      break;
    }
  }
  const Entry* e = named ? named : any;
  if (!e) return {};
  return e->sample.index() == type.index ? e->sample : d.make(e->sample);
}

std::string strip_frame(const std::string& frame) {
  size_t i = 0;
  while (i < frame.size() && frame[i] == '/') ++i;
  return frame.substr(i);
}

std::string resolve_topic(const std::string& ns, const std::string& topic) {
  if (!topic.empty() && topic[0] == '/') return topic;
  return ns.empty() ? "/" + topic : "/" + ns + "/" + topic;
}

std::function<std::vector<InputPort>(const PluginConfig&, const std::string&)> topic_input(
    const std::string& port, InputType type, const std::string& topic_key, uint32_t queue, uint32_t axes) {
  return [=](const PluginConfig& c, const std::string& robot) {
    InputPort p;
    p.name = port;
    p.type = type;
    const std::string topic = c.text(topic_key);
    if (!topic.empty()) p.topic = resolve_topic(plugin_robot_namespace(c, robot), topic);
    p.queue = queue;
    p.axes = axes;
    return std::vector<InputPort>{p};
  };
}

const char* command_noun(InputType type) {
  switch (type) {
    case InputType::Twist: return "cmd_vel";
    case InputType::Wrench: return "wrench";
    case InputType::JointTrajectory: return "trajectory";
    case InputType::Pose: return "pose target";
    case InputType::Trigger: return "trigger";
    case InputType::Float64: return "command";
    case InputType::Float64Array: return "command";
    case InputType::TrajectoryGoal: return "trajectory goal";
  }
  return "command";
}

}  // namespace car_sim
