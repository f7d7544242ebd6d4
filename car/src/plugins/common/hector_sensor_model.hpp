// hector_gazebo_plugins' SensorModel (sensor_model.h) and UpdateTimer keys, shared by car's hector kinds:
// measurement = value * scaleError + offset + drift + N(0, gaussianNoise), the drift a first-order Gauss-Markov
// process: drift = exp(-dt f) drift + dt N(0, sqrt(2 f) drift_stddev), reset to N(0, drift_stddev).
// Random numbers come from the instance's seeded generator. Behaviour per docs/COMPAT-sensors.md.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <random>
#include <cctype>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "car_sim/plugin.hpp"

namespace car_sim {
namespace hector {

// A key name with static storage, for ParamDef.
inline const char* intern(const std::string& s) {
  static std::set<std::string> pool;
  return pool.insert(s).first->c_str();
}

// "offset" / "drift" / ... with a prefix: "accelOffset", "accelDrift", ...
inline std::string key(const std::string& prefix, const char* name) {
  if (prefix.empty()) return name;
  std::string n = name;
  n[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(n[0])));
  return prefix + n;
}

// The model's keys (Text: a number, or "x y z" for a vector model).
inline std::vector<ParamDef> model_schema(const std::string& prefix, const char* unit) {
  return {
      {intern(key(prefix, "offset")), ParamType::Text, "0", unit},
      {intern(key(prefix, "drift")), ParamType::Text, "0", unit},
      {intern(key(prefix, "driftFrequency")), ParamType::Text, "0.000277777777777778", "1/s"},
      {intern(key(prefix, "gaussianNoise")), ParamType::Text, "0", unit},
      {intern(key(prefix, "scaleError")), ParamType::Text, "1", ""},
  };
}

// hector's UpdateTimer keys (update_timer.h; docs/COMPAT-sensors.md "When, exactly"): updateRate [Hz] (default per
// plug-in), and updatePeriod and updateOffset as sdf::Time "SEC NSEC".
inline std::vector<ParamDef> timer_schema(const char* default_rate) {
  return {{"updateRate", ParamType::Number, default_rate, "Hz"},
          {"updatePeriod", ParamType::Text, "0", "SEC NSEC"},
          {"updateOffset", ParamType::Text, "0", "SEC NSEC"}};
}

// sdf::Time's stream read, as sdformat 9's Param::Get gives it a plug-in's string element: `in >> sec >> nsec`
// into int32, where a read that fails leaves 0 and ends the reading ("0.25" is 0 s 0 ns).
struct SdfTime {
  int32_t sec = 0, nsec = 0;
  explicit SdfTime(const std::string& text) {
    std::istringstream in(text);
    in >> sec >> nsec;
  }
  int64_t ns() const { return static_cast<int64_t>(sec) * 1000000000 + nsec; }
  // common::Time::Double() of the Time as read (not normalised): sec + nsec * 1e-9
  double seconds() const { return static_cast<double>(sec) + static_cast<double>(nsec) * 1e-9; }
  // The text is one or two integers (each an int32) and nothing else: what the read takes it to mean.
  static bool whole(const std::string& text) {
    std::istringstream in(text);
    int64_t v = 0;
    for (int i = 0; i < 2; ++i) {
      if (!(in >> v) || v != static_cast<int32_t>(v)) return false;
      if ((in >> std::ws).eof()) return true;
    }
    return false;
  }
};

// The timer of one hector plug-in: the period [s] as UpdateTimer's update_period_.Double(), the offset [ns].
struct UpdateTimer {
  double period = 0.0;
  int64_t offset_ns = 0;

  explicit UpdateTimer(const PluginConfig& c) {
    // common::Time(1 / rate), whole nanoseconds; a rate <= 0 gives 0
    const double rate = c.number("updateRate");
    if (rate > 0) period = common_time_double(common_time_ns(1.0 / rate));
    if (!c.param("updatePeriod").from_default) period = SdfTime(c.text("updatePeriod")).seconds();
    if (!c.param("updateOffset").from_default) offset_ns = SdfTime(c.text("updateOffset")).ns();
  }
  double rate() const { return period > 0 ? 1.0 / period : 0.0; }
  Schedule schedule(double dt) const { return Schedule::absolute(period, offset_ns, dt); }
};

// getTimeSinceLastUpdate: [s] since the last update in whole nanoseconds, 0 at the first (and after unset()).
class LastUpdate {
 public:
  double since(const StepContext& ctx) {
    const int64_t now = tick_time_ns(ctx.tick, ctx.dt);
    const double dt = last_ns_ < 0 ? 0.0 : common_time_double(now - last_ns_);
    last_ns_ = now;
    return dt;
  }
  void unset() { last_ns_ = -1; }

 private:
  int64_t last_ns_ = -1;
};

// Warns where upstream's reading differs from what the text seems to say: a rate < 0 (every step), and a period or
// offset that is not "SEC NSEC" integers (sdf::Time reads "0.25" as 0 s).
inline void finish_timer(ResolveContext& ctx) {
  const PluginConfig& c = ctx.config();
  warn_negative_rate(ctx, "updateRate");
  for (const char* k : {"updatePeriod", "updateOffset"}) {
    if (c.param(k).from_default) continue;
    const std::string& t = c.text(k);
    if (SdfTime::whole(t)) continue;
    const SdfTime as_read(t);
    const int64_t ns = as_read.ns();
    char read[64];
    std::snprintf(read, sizeof read, "%g s", as_read.seconds());
    std::string m = "<" + std::string(k) + "> '" + t + "' is read as sdf::Time 'SEC NSEC' by hector's UpdateTimer: " + read;
    const bool period = std::string(k) == "updatePeriod";
    if (period && ns == 0) m += ", so the plug-in updates every step";
    // what a number of seconds would be written as
    std::istringstream in(t);
    double x = 0;
    if ((in >> x) && (in >> std::ws).eof() && std::isfinite(x) && x > 0) {
      const int64_t x_ns = common_time_ns(x);
      char fix[128];
      if (period)
        std::snprintf(fix, sizeof fix, "; write <updateRate>%g</updateRate> or '%lld %lld'", 1.0 / x,
                      static_cast<long long>(x_ns / 1000000000), static_cast<long long>(x_ns % 1000000000));
      else
        std::snprintf(fix, sizeof fix, "; write '%lld %lld'", static_cast<long long>(x_ns / 1000000000),
                      static_cast<long long>(x_ns % 1000000000));
      m += fix;
    }
    ctx.warn(Severity::Warning, "key-value", k, m);
  }
}

// Parses n numbers; false when the text is not n finite numbers.
inline bool parse_n(const std::string& text, int n, double* out) {
  std::istringstream ss(text);
  for (int i = 0; i < n; ++i)
    if (!(ss >> out[i]) || !std::isfinite(out[i])) return false;
  std::string rest;
  return !(ss >> rest);
}

// A model's sigma key (drift, gaussianNoise) with a negative value: hector's SensorModelGaussianKernel draws
// sigma * X, so it runs as upstream and spreads as |sigma|, with a warning. A negative driftFrequency is refused:
// the drift's sqrt(2 f) is NaN, and so is every measurement from the first update on.
inline void check_sign(ResolveContext& ctx, const std::string& k, const std::string& name, const double* v, int n) {
  bool negative = false;
  for (int i = 0; i < n; ++i) negative = negative || v[i] < 0;
  if (!negative) return;
  if (name == "driftFrequency") {
    ctx.fail(k, "must be >= 0: hector's drift takes sqrt(2 driftFrequency), NaN for a negative one");
  } else {
    ctx.warn(Severity::Warning, "negative-noise", k,
             "<" + k + "> '" + ctx.config().text(k) +
                 "' is negative: hector's GaussianKernel draws sigma * X, so it spreads as its absolute value");
  }
}

// Checks a model's keys: N numbers each (a single number for a vector model is what upstream cannot read: a
// warning, and the default is kept, as upstream does); the signs of drift, noise and frequency (check_sign).
inline void finish_model(ResolveContext& ctx, const std::string& prefix, int n) {
  for (const char* name : {"offset", "drift", "driftFrequency", "gaussianNoise", "scaleError"}) {
    const std::string k = key(prefix, name);
    // a key not written keeps upstream's default (one number meant for every axis): nothing to report
    if (ctx.config().param(k).from_default) continue;
    double v[3];
    const std::string& t = ctx.config().text(k);
    if (parse_n(t, n, v)) {
      if (std::string(name) != "offset" && std::string(name) != "scaleError") check_sign(ctx, k, name, v, n);
      continue;
    }
    if (n == 3 && parse_n(t, 1, v)) {
      ctx.warn(Severity::Warning, "key-value", k,
               "<" + k + "> needs three numbers 'x y z'; hector's plug-in cannot read one number and keeps its default");
      continue;
    }
    ctx.fail(k, "'" + t + "' is not " + (n == 3 ? "three numbers 'x y z'" : "a number"));
  }
}

// N(0, sigma) as hector's SensorModelGaussianKernel draws it, sigma * X: a negative sigma gives -|sigma| X.
inline double gauss(std::mt19937_64& g, double sigma) {
  if (sigma > 0) return std::normal_distribution<double>(0.0, sigma)(g);
  if (sigma < 0) return -std::normal_distribution<double>(0.0, -sigma)(g);
  return 0.0;
}

template <int N>
class SensorModel {
 public:
  using Vec = Eigen::Matrix<double, N, 1>;
  Vec offset = Vec::Zero(), drift = Vec::Zero(), drift_frequency = Vec::Constant(1.0 / 3600.0),
      gaussian_noise = Vec::Zero(), scale_error = Vec::Ones();

  void load(const PluginConfig& c, const std::string& prefix) {
    read(c, key(prefix, "offset"), &offset);
    read(c, key(prefix, "drift"), &drift);
    read(c, key(prefix, "driftFrequency"), &drift_frequency);
    read(c, key(prefix, "gaussianNoise"), &gaussian_noise);
    read(c, key(prefix, "scaleError"), &scale_error);
  }
  void reset(std::mt19937_64& g) {
    for (int i = 0; i < N; ++i) current_drift_[i] = gauss(g, drift[i]);
    current_error_.setZero();
  }
  // The error after dt [s].
  const Vec& update(double dt, std::mt19937_64& g) {
    for (int i = 0; i < N; ++i) {
      current_drift_[i] = std::exp(-dt * drift_frequency[i]) * current_drift_[i] +
                          dt * gauss(g, std::sqrt(2 * drift_frequency[i]) * drift[i]);
      current_error_[i] = offset[i] + current_drift_[i] + gauss(g, gaussian_noise[i]);
    }
    return current_error_;
  }
  // A measurement of value after dt [s].
  Vec operator()(const Vec& value, double dt, std::mt19937_64& g) {
    const Vec e = update(dt, g);
    return value.cwiseProduct(scale_error) + e;
  }
  Vec bias() const { return current_drift_ + offset; }
  const Vec& drift_now() const { return current_drift_; }
  void set_drift(const Vec& d) { current_drift_ = d; }

 private:
  static void read(const PluginConfig& c, const std::string& k, Vec* v) {
    double x[N];
    if (parse_n(c.text(k), N, x))
      for (int i = 0; i < N; ++i) (*v)[i] = x[i];
  }
  Vec current_drift_ = Vec::Zero(), current_error_ = Vec::Zero();
};

}  // namespace hector
}  // namespace car_sim
