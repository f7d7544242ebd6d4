// Resolution of a model's plug-ins through the registry: each <plugin> finds its kind by file name, every
// schema key gets its value (or its default), values are type-checked, unknown keys are warned with a
// "did you mean", and the kind's finish() validates against the model. Errors name the plug-in or sensor and key.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <sstream>

#include "car_sim/plugin.hpp"
#include "car_sim/shared_plugin.hpp"
#include "validate.hpp"
#include "shared_library/shared_library.hpp"
#include "xml_util.hpp"

namespace car_sim {

namespace {

std::string lower_alnum(const std::string& s) {
  std::string out;
  for (char c : s)
    if (std::isalnum(static_cast<unsigned char>(c))) out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::string strip_slash(const std::string& s) {
  size_t i = 0;
  while (i < s.size() && s[i] == '/') ++i;
  return s.substr(i);
}

// A value outside its key's stated limits: a load error naming the key, the value and the limit.
void check_limits(const RobotModel& m, const ParamDef& def, const std::string& value, const std::string& elem,
                  int line) {
  const double v = *detail::parse_number(value);
  if (v > def.max)
    throw LoadError(m.source, line, elem,
                    std::string(def.key) + " " + detail::trim(value) + " is above the limit " + limits::text(def.max, def.unit));
  if (v < def.min)
    throw LoadError(m.source, line, elem,
                    std::string(def.key) + " " + detail::trim(value) + " is below the limit " + limits::text(def.min, def.unit));
}

// Resolves schema keys from params; bad values are load errors naming element and key.
void resolve_keys(const RobotModel& m, const std::vector<ParamDef>& schema, const ParamList& params,
                  const std::string& where, int line, std::vector<ResolvedParam>* out) {
  for (const auto& def : schema) {
    ResolvedParam rp;
    rp.key = def.key;
    rp.unit = def.unit;
    const std::string* v = find_param(params, def.key);
    rp.from_default = (v == nullptr);
    rp.value = v ? *v : def.default_value;
    const std::string elem = where + "/" + def.key;
    switch (def.type) {
      case ParamType::Number:
        if (!detail::parse_number(rp.value)) throw LoadError(m.source, line, elem, "'" + rp.value + "' is not a number");
        check_limits(m, def, rp.value, elem, line);
        break;
      case ParamType::Integer: {
        const auto n = detail::parse_number(rp.value);
        if (!n || std::floor(*n) != *n) throw LoadError(m.source, line, elem, "'" + rp.value + "' is not an integer");
        check_limits(m, def, rp.value, elem, line);
        break;
      }
      case ParamType::Flag: {
        bool b = false;
        if (!parse_flag(rp.value, &b))
          throw LoadError(m.source, line, elem, "'" + rp.value + "' is not a boolean (true/false/1/0)");
        rp.value = b ? "true" : "false";
        break;
      }
      case ParamType::Frame:
        rp.value = strip_slash(detail::trim(rp.value));
        break;
      case ParamType::Text:
        break;
    }
    out->push_back(std::move(rp));
  }
}

// Plug-in keys that are in no schema: ignored quietly, with a note, or warned with a suggestion.
void check_unknown_keys(const PluginKind& kind, const PluginSpec& p, ResolveContext& ctx) {
  if (kind.any_keys) return;
  std::set<std::string> known;
  for (const auto& d : kind.schema) known.insert(d.key);
  for (const auto& kv : p.params) {
    const std::string& key = kv.first;
    if (known.count(key)) continue;
    const auto it = kind.ignored.find(key);
    if (it != kind.ignored.end()) {
      if (!it->second.empty()) ctx.warn(Severity::Info, "key-ignored", key, it->second);
      continue;
    }
    std::string hint;
    for (const auto& d : kind.schema)
      if (lower_alnum(d.key) == lower_alnum(key)) hint = "; did you mean <" + std::string(d.key) + ">?";
    ctx.warn(Severity::Warning, "key-unknown", key, "unknown key <" + key + "> in " + p.filename + " is ignored" + hint);
  }
}

// A sensor's own keys; update_rate was read into a field when the sensor was parsed.
ParamList sensor_params(const SensorSpec& s) {
  ParamList ps = s.params;
  std::ostringstream os;
  os.precision(17);
  os << s.update_rate;
  ps.emplace_back("update_rate", os.str());
  return ps;
}

PluginConfig resolve_one(const RobotModel& m, const PluginKind& kind, const PluginSpec& p, const SensorSpec* s,
                         std::vector<Diagnostic>* diags) {
  PluginConfig c;
  c.kind = kind.name;
  c.name = p.name;
  c.filename = p.filename;
  if (kind.any_keys) c.raw = p.params;
  if (s) {
    c.sensor = s->name;
    c.sensor_type = s->type;
    c.link = s->link;
    c.sensor_pose = s->pose;
  }
  ResolveContext ctx(m, p, s, &c, diags);
  if (s) {
    const auto own = kind.file_sensor_types.find(p.filename);
    const std::vector<std::string>& types = own == kind.file_sensor_types.end() ? kind.sensor_types : own->second;
    if (std::find(types.begin(), types.end(), s->type) == types.end())
      // upstream's sensor plug-ins check their parent's type in Load and log or throw: the model loads without it
      ctx.drop("", p.filename + " needs a sensor of type " + types.front() + ", not '" + s->type + "'");
    resolve_keys(m, kind.sensor_schema, sensor_params(*s), "sensor[" + s->name + "]", s->line, &c.params);
  }
  resolve_keys(m, kind.schema, p.params, ctx.where(""), p.line, &c.params);
  check_unknown_keys(kind, p, ctx);
  if (kind.finish) kind.finish(ctx);
  return c;
}

void warn_unknown(std::vector<Diagnostic>* diags, const std::string& where, const PluginSpec& p) {
  diags->push_back({Severity::Warning, "plugin-unknown", where,
                    "plug-in '" + p.filename + "' is not simulated by car; ignored", p.line});
}

// A robot-level file that is none of car's kinds and no file on the search path: Gazebo's message, with the folders
// searched (car_sim/shared_plugin.hpp).
void warn_not_found(std::vector<Diagnostic>* diags, const std::string& where, const PluginSpec& p) {
  std::string searched;
  for (const auto& d : shared_plugin_search_path()) searched += (searched.empty() ? "" : ":") + d;
  diags->push_back({Severity::Warning, "plugin-unknown", where,
                    "Failed to load plugin " + p.filename + ": not one car simulates, and no such file in " +
                        "GAZEBO_PLUGIN_PATH, the ROS library folders or LD_LIBRARY_PATH (searched: " + searched +
                        "); ignored",
                    p.line});
}

// Resolves one plug-in into `out`, or leaves it out with a warning where it does not load (ResolveContext::drop).
void resolve_into(const RobotModel& m, const PluginKind& kind, const PluginSpec& p, const SensorSpec* s,
                  ModelConfig* out) {
  try {
    out->plugins.push_back(resolve_one(m, kind, p, s, &out->diagnostics));
  } catch (const PluginNotLoaded& e) {
    out->diagnostics.push_back(
        {Severity::Warning, "plugin-not-loaded", e.element(), e.reason() + "; the plug-in is not loaded", p.line});
  }
}

// A sensor for Gazebo's sensors API (docs/PLUGINS.md "Sensors"): its plug-in from a library `p` (nullptr: a sensor
// with no plug-in), resolved as car's own kind for the sensor's type would be (the sensor's keys, the kind's
// defaults), then marked as the shared-library kind with the library's file and elements.
void resolve_sensor_feed(const RobotModel& m, const SensorSpec& s, const PluginSpec* p, std::vector<PluginConfig>* out,
                         std::vector<Diagnostic>* diags) {
  const std::string where = p ? "sensor[" + s.name + "]/plugin[" + p->name + "]" : "sensor[" + s.name + "]";
  const PluginKind* feed = sensor_feed_kind(s.type);
  if (!feed) {
    if (p)
      diags->push_back({Severity::Warning, "plugin-not-loaded", where,
                        "sensor type '" + s.type + "' is not offered by car's Gazebo sensors API (ray, gpu_ray, " +
                            "contact, imu, camera, depth); the plug-in " + p->filename + " is not loaded",
                        p->line});
    return;
  }
  PluginSpec own;
  own.name = p ? p->name : s.name;
  own.filename = sensor_feed_file(s.type);
  own.line = p ? p->line : s.line;
  own.params = sensor_feed_params(s);
  try {
    std::vector<Diagnostic> mine;
    PluginConfig c = resolve_one(m, *feed, own, &s, &mine);
    for (const Diagnostic& d : mine) {
      bool car_s = false;
      for (const auto& kv : own.params)
        car_s = car_s || d.element == "sensor[" + s.name + "]/plugin[" + own.name + "]/" + kv.first;
      if (!car_s) diags->push_back(d);
    }
    c.kind = shared_library_kind().name;
    c.filename = p ? p->filename : "";
    c.raw = p ? p->params : ParamList();
    out->push_back(std::move(c));
  } catch (const PluginNotLoaded& e) {
    diags->push_back({Severity::Warning, "plugin-not-loaded", e.element(), e.reason() + "; the plug-in is not loaded",
                      own.line});
  }
}

}  // namespace

PluginConfig resolve_plugin(const RobotModel& model, const PluginSpec& p, std::vector<Diagnostic>* diags) {
  const PluginKind* kind = plugin_kind_for_file(p.filename);
  if (!kind || !kind->model_level)
    throw LoadError(model.source, p.line, "gazebo/plugin[" + p.name + "]",
                    "plug-in '" + p.filename + "' is not a robot-level plug-in car simulates");
  return resolve_one(model, *kind, p, nullptr, diags);
}

ModelConfig resolve_plugins(const RobotModel& m) {
  ModelConfig out;
  for (const auto& p : m.plugins) {
    const PluginKind* kind = plugin_kind_for_file(p.filename);
    if (!kind) {
      warn_not_found(&out.diagnostics, "gazebo/plugin[" + p.name + "]", p);
      continue;
    }
    if (!kind->model_level) {
      warn_unknown(&out.diagnostics, "gazebo/plugin[" + p.name + "]", p);
      continue;
    }
    resolve_into(m, *kind, p, nullptr, &out);
  }
  std::vector<PluginConfig> feeds;  // the sensors of Gazebo's sensors API, with or without a plug-in
  std::set<std::string> sensor_types;
  for (const PluginKind* k : plugin_kinds()) sensor_types.insert(k->sensor_types.begin(), k->sensor_types.end());
  for (const auto& s : m.sensors) {
    if (!sensor_types.count(s.type))
      out.diagnostics.push_back({Severity::Warning, "sensor-unknown", "sensor[" + s.name + "]",
                                 "sensor type '" + s.type + "' is not simulated by car; ignored", s.line});
    if (s.plugins.empty())
      out.diagnostics.push_back({Severity::Info, "sensor-no-plugin", "sensor[" + s.name + "]",
                                 "sensor has no plug-in, so nothing is published for it", s.line});
    for (const auto& p : s.plugins) {
      const PluginKind* kind = plugin_kind_for_file(p.filename);
      if (kind == &shared_library_kind()) {
        resolve_sensor_feed(m, s, &p, &feeds, &out.diagnostics);
        continue;
      }
      if (!kind || kind->sensor_types.empty()) {
        warn_unknown(&out.diagnostics, "sensor[" + s.name + "]/plugin[" + p.name + "]", p);
        continue;
      }
      resolve_into(m, *kind, p, &s, &out);
    }
  }
  // A robot that runs plug-ins from libraries offers its sensors with no plug-in to Gazebo's sensors API too
  // (SensorManager finds them, as Kobuki's model plug-in does its bumper and cliff sensors); the sensors come
  // before the robot's plug-ins from libraries, so that their Load finds them.
  const auto is_library = [](const PluginConfig& c) { return c.kind == shared_library_kind().name; };
  if (!feeds.empty() || std::any_of(out.plugins.begin(), out.plugins.end(), is_library))
    for (const auto& s : m.sensors)
      if (s.plugins.empty()) resolve_sensor_feed(m, s, nullptr, &feeds, &out.diagnostics);
  const auto first = std::find_if(out.plugins.begin(), out.plugins.end(), is_library);
  out.plugins.insert(first, feeds.begin(), feeds.end());
  return out;
}

const std::vector<ParamDef>& plugin_schema(const std::string& kind) {
  static std::map<std::string, std::vector<ParamDef>> cache;
  static const std::vector<ParamDef> empty;
  const PluginKind* k = find_plugin_kind(kind);
  if (!k) return empty;
  auto it = cache.find(kind);
  if (it == cache.end()) {
    std::vector<ParamDef> all = k->sensor_schema;
    all.insert(all.end(), k->schema.begin(), k->schema.end());
    it = cache.emplace(kind, std::move(all)).first;
  }
  return it->second;
}

std::string plugin_kind(const std::string& filename) {
  const PluginKind* k = plugin_kind_for_file(filename);
  return k ? k->name : "";
}

}  // namespace car_sim
