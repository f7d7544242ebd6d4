// hector_gazebo_plugins' SensorModel (sensor_model.h) and UpdateTimer keys, shared by car's hector kinds:
// measurement = value * scaleError + offset + drift + N(0, gaussianNoise), the drift a first-order Gauss-Markov
// process: drift = exp(-dt f) drift + dt N(0, sqrt(2 f) drift_stddev), reset to N(0, drift_stddev).
// Random numbers come from the instance's seeded generator. Behaviour per docs/COMPAT-sensors.md.
#pragma once

#include <Eigen/Core>
#include <cmath>
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

// updateRate [Hz] (default per plug-in) and updatePeriod [s]; the period wins when given.
inline std::vector<ParamDef> timer_schema(const char* default_rate) {
  return {{"updateRate", ParamType::Number, default_rate, "Hz"}, {"updatePeriod", ParamType::Number, "0", "s"}};
}
inline double timer_rate(const PluginConfig& c) {
  if (!c.param("updatePeriod").from_default) return c.number("updatePeriod") > 0 ? 1.0 / c.number("updatePeriod") : 0.0;
  return c.number("updateRate");
}

// Parses n numbers; false when the text is not n finite numbers.
inline bool parse_n(const std::string& text, int n, double* out) {
  std::istringstream ss(text);
  for (int i = 0; i < n; ++i)
    if (!(ss >> out[i]) || !std::isfinite(out[i])) return false;
  std::string rest;
  return !(ss >> rest);
}

// Checks a model's keys: N numbers each (a single number for a vector model is what upstream cannot read: a
// warning, and the default is kept, as upstream does); drift, noise and frequency >= 0.
inline void finish_model(ResolveContext& ctx, const std::string& prefix, int n) {
  for (const char* name : {"offset", "drift", "driftFrequency", "gaussianNoise", "scaleError"}) {
    const std::string k = key(prefix, name);
    // a key not written keeps upstream's default (one number meant for every axis): nothing to report
    if (ctx.config().param(k).from_default) continue;
    double v[3];
    const std::string& t = ctx.config().text(k);
    if (parse_n(t, n, v)) {
      if (std::string(name) != "offset" && std::string(name) != "scaleError")
        for (int i = 0; i < n; ++i)
          if (v[i] < 0) ctx.fail(k, "must be >= 0");
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
  static double gauss(std::mt19937_64& g, double sigma) {
    return sigma > 0 ? std::normal_distribution<double>(0.0, sigma)(g) : 0.0;
  }
  static void read(const PluginConfig& c, const std::string& k, Vec* v) {
    double x[N];
    if (parse_n(c.text(k), N, x))
      for (int i = 0; i < N; ++i) (*v)[i] = x[i];
  }
  Vec current_drift_ = Vec::Zero(), current_error_ = Vec::Zero();
};

}  // namespace hector
}  // namespace car_sim
