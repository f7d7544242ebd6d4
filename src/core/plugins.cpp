// Plug-in schemas (every key, default and unit, per gazebo_ros Noetic and SDF defaults) and their resolution.
#include "car_sim/plugins.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "xml_util.hpp"

namespace car_sim {

using detail::parse_number;

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType N = ParamType::Number;
constexpr ParamType I = ParamType::Integer;
constexpr ParamType F = ParamType::Flag;

// Sensor keys, as flattened paths of the <sensor> element (SDF 1.6 defaults).
const std::vector<ParamDef> kRaySensor = {
    {"update_rate", N, "0", "Hz"},
    {"ray/scan/horizontal/samples", I, "640", ""},
    {"ray/scan/horizontal/resolution", N, "1", ""},
    {"ray/scan/horizontal/min_angle", N, "0", "rad"},
    {"ray/scan/horizontal/max_angle", N, "0", "rad"},
    {"ray/range/min", N, "0", "m"},
    {"ray/range/max", N, "0", "m"},
    {"ray/range/resolution", N, "0", "m"},
    {"ray/noise/type", T, "none", ""},
    {"ray/noise/mean", N, "0", "m"},
    {"ray/noise/stddev", N, "0", "m"},
};

const std::vector<ParamDef> kCameraSensor = {
    {"update_rate", N, "0", "Hz"},
    {"camera/horizontal_fov", N, "1.047", "rad"},
    {"camera/image/width", I, "320", "px"},
    {"camera/image/height", I, "240", "px"},
    {"camera/image/format", T, "R8G8B8", ""},
    {"camera/clip/near", N, "0.1", "m"},
    {"camera/clip/far", N, "100", "m"},
    {"camera/noise/type", T, "none", ""},
    {"camera/noise/mean", N, "0", ""},
    {"camera/noise/stddev", N, "0", ""},
};

const std::vector<ParamDef> kImuSensor = {
    {"update_rate", N, "0", "Hz"},
};

const std::vector<ParamDef> kDiffDrive = {
    {"robotNamespace", T, "", ""},
    {"commandTopic", T, "cmd_vel", ""},
    {"odometryTopic", T, "odom", ""},
    {"odometryFrame", T, "odom", ""},
    {"robotBaseFrame", T, "base_footprint", ""},
    {"wheelSeparation", N, "0.34", "m"},
    {"wheelDiameter", N, "0.15", "m"},
    {"wheelTorque", N, "5.0", "N m"},
    {"wheelAcceleration", N, "0", "m/s^2"},
    {"updateRate", N, "100", "Hz"},
    {"odometrySource", T, "world", ""},
    {"publishTf", F, "true", ""},
    {"publishOdomTF", F, "true", ""},
    {"publishWheelTF", F, "false", ""},
    {"publishWheelJointState", F, "false", ""},
    {"leftJoint", T, "left_joint", ""},
    {"rightJoint", T, "right_joint", ""},
    {"rosDebugLevel", T, "na", ""},
};

const std::vector<ParamDef> kLaser = {
    {"robotNamespace", T, "", ""},
    {"topicName", T, "/world", ""},
    {"frameName", T, "/world", ""},
};

const std::vector<ParamDef> kCameraCommon = {
    {"robotNamespace", T, "", ""},
    {"cameraName", T, "", ""},
    {"frameName", T, "/world", ""},
    {"updateRate", N, "0", "Hz"},
    {"hackBaseline", N, "0", "m"},
    {"distortionK1", N, "0", ""},
    {"distortionK2", N, "0", ""},
    {"distortionK3", N, "0", ""},
    {"distortionT1", N, "0", ""},
    {"distortionT2", N, "0", ""},
};

std::vector<ParamDef> kinect_schema() {
  std::vector<ParamDef> s = kCameraCommon;
  const std::vector<ParamDef> extra = {
      {"imageTopicName", T, "ir/image_raw", ""},
      {"cameraInfoTopicName", T, "ir/camera_info", ""},
      {"depthImageTopicName", T, "depth/image_raw", ""},
      {"depthImageCameraInfoTopicName", T, "depth/camera_info", ""},
      {"pointCloudTopicName", T, "points", ""},
      {"pointCloudCutoff", N, "0.4", "m"},
      {"pointCloudCutoffMax", N, "5.0", "m"},
      {"useDepth16UC1Format", F, "false", ""},
  };
  s.insert(s.end(), extra.begin(), extra.end());
  return s;
}

std::vector<ParamDef> camera_schema() {
  std::vector<ParamDef> s = kCameraCommon;
  s.push_back({"imageTopicName", T, "image_raw", ""});
  s.push_back({"cameraInfoTopicName", T, "camera_info", ""});
  return s;
}

const std::vector<ParamDef> kImu = {
    {"robotNamespace", T, "", ""},
    {"bodyName", T, "", ""},
    {"topicName", T, "imu", ""},
    {"frameName", T, "", ""},
    {"gaussianNoise", N, "0", ""},
    {"updateRate", N, "0", "Hz"},
    {"xyzOffset", T, "0 0 0", "m"},
    {"rpyOffset", T, "0 0 0", "rad"},
};

// Keys upstream accepts and ignores, and keys users write that upstream never reads.
const std::map<std::string, std::map<std::string, std::string>> kIgnored = {
    {"diff_drive",
     {{"legacyMode", ""}, {"broadcastTF", ""}, {"alwaysOn", ""}}},
    {"laser", {{"alwaysOn", ""}, {"updateRate", ""}, {"gaussianNoise", ""}, {"hokuyoMinIntensity", ""}}},
    {"openni_kinect",
     {{"alwaysOn", ""},
      {"baseline", "<baseline> is never read upstream; set hackBaseline"},
      {"Cx", "car computes cx = (W-1)/2 from the image"},
      {"Cy", "car computes cy = (H-1)/2 from the image"},
      {"CxPrime", "car computes cx = (W-1)/2 from the image"},
      {"focalLength", "car computes f from the image width and horizontal_fov"},
      {"borderCrop", ""}}},
    {"camera",
     {{"alwaysOn", ""},
      {"baseline", "<baseline> is never read upstream; set hackBaseline"},
      {"Cx", "car computes cx = (W-1)/2 from the image"},
      {"Cy", "car computes cy = (H-1)/2 from the image"},
      {"CxPrime", "car computes cx = (W-1)/2 from the image"},
      {"focalLength", "car computes f from the image width and horizontal_fov"}}},
    {"imu", {{"alwaysOn", ""}, {"serviceName", ""}}},
};

const std::vector<ParamDef> kEmpty;

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

class Resolver {
 public:
  Resolver(const RobotModel& m, ModelConfig* out) : m_(m), out_(out) {}

  [[noreturn]] void fail(int line, const std::string& element, const std::string& reason) const {
    throw LoadError(m_.source, line, element, reason);
  }

  void warn(Severity sev, const std::string& code, const std::string& element, const std::string& msg, int line) {
    out_->diagnostics.push_back({sev, code, element, msg, line});
  }

  // Resolves schema keys from params; bad values are load errors naming element and key.
  void resolve(const std::vector<ParamDef>& schema, const ParamList& params, const std::string& where, int line,
               std::vector<ResolvedParam>* out) const {
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
          if (!parse_number(rp.value)) fail(line, elem, "'" + rp.value + "' is not a number");
          break;
        case ParamType::Integer: {
          const auto n = parse_number(rp.value);
          if (!n || std::floor(*n) != *n) fail(line, elem, "'" + rp.value + "' is not an integer");
          break;
        }
        case ParamType::Flag: {
          bool b = false;
          if (!parse_flag(rp.value, &b)) fail(line, elem, "'" + rp.value + "' is not a boolean (true/false/1/0)");
          rp.value = b ? "true" : "false";
          break;
        }
        case ParamType::Text:
          break;
      }
      out->push_back(std::move(rp));
    }
  }

  // Plug-in keys that are in no schema: ignored quietly, with a note, or warned with a suggestion.
  void check_unknown_keys(const std::string& kind, const std::vector<ParamDef>& schema, const PluginSpec& p,
                          const std::string& where) {
    std::set<std::string> known;
    for (const auto& d : schema) known.insert(d.key);
    const auto ign = kIgnored.find(kind);
    for (const auto& kv : p.params) {
      const std::string& key = kv.first;
      if (known.count(key)) continue;
      if (ign != kIgnored.end()) {
        const auto it = ign->second.find(key);
        if (it != ign->second.end()) {
          if (!it->second.empty()) warn(Severity::Info, "key-ignored", where + "/" + key, it->second, p.line);
          continue;
        }
      }
      std::string hint;
      for (const auto& d : schema)
        if (lower_alnum(d.key) == lower_alnum(key)) hint = "; did you mean <" + std::string(d.key) + ">?";
      warn(Severity::Warning, "key-unknown", where + "/" + key,
           "unknown key <" + key + "> in " + p.filename + " is ignored" + hint, p.line);
    }
  }

  PluginConfig make(const std::string& kind, const PluginSpec& p, const SensorSpec* s) {
    PluginConfig c;
    c.kind = kind;
    c.name = p.name;
    c.filename = p.filename;
    if (s) {
      c.sensor = s->name;
      c.sensor_type = s->type;
      c.link = s->link;
    }
    return c;
  }

  std::string plugin_where(const PluginSpec& p, const SensorSpec* s) const {
    const std::string pl = "plugin[" + p.name + "]";
    return s ? "sensor[" + s->name + "]/" + pl : "gazebo/" + pl;
  }

  // A sensor's own keys; update_rate and pose were read into fields when the sensor was parsed.
  ParamList sensor_params(const SensorSpec& s) const {
    ParamList ps = s.params;
    std::ostringstream os;
    os.precision(17);
    os << s.update_rate;
    ps.emplace_back("update_rate", os.str());
    return ps;
  }

  void validate_diff_drive(PluginConfig& c, const PluginSpec& p, const std::string& where) {
    for (const char* key : {"leftJoint", "rightJoint"}) {
      const std::string& jn = c.text(key);
      const Joint* j = m_.find_joint(jn);
      if (!j)
        fail(p.line, where + "/" + key,
             "joint '" + jn + "' not found in the model (plug-in '" + p.name + "', " + p.filename + ")");
      if (j->type == JointType::Fixed)
        fail(p.line, where + "/" + key, "joint '" + jn + "' is fixed; a drive wheel needs a continuous joint");
    }
    if (!(c.number("wheelSeparation") > 0)) fail(p.line, where + "/wheelSeparation", "must be > 0");
    if (!(c.number("wheelDiameter") > 0)) fail(p.line, where + "/wheelDiameter", "must be > 0");
    if (c.number("wheelTorque") < 0) fail(p.line, where + "/wheelTorque", "must be >= 0");
    if (c.number("wheelAcceleration") < 0) fail(p.line, where + "/wheelAcceleration", "must be >= 0 (0 = unlimited)");
    if (c.number("updateRate") < 0) fail(p.line, where + "/updateRate", "must be >= 0");
    const std::string& src = c.text("odometrySource");
    if (src != "world" && src != "encoder")
      fail(p.line, where + "/odometrySource", "'" + src + "' is neither 'world' nor 'encoder'");
    if (!c.flag("publishTf"))
      warn(Severity::Warning, "publish-tf-off", where + "/publishTf",
           "publishTf false: like gazebo_ros, no /odom is published at all", p.line);
  }

  void validate_ray(const PluginConfig& c, const SensorSpec& s) {
    const std::string w = "sensor[" + s.name + "]/";
    if (c.number("ray/scan/horizontal/samples") < 1)
      fail(s.line, w + "ray/scan/horizontal/samples", "samples must be >= 1");
    if (!(c.number("ray/scan/horizontal/resolution") > 0))
      fail(s.line, w + "ray/scan/horizontal/resolution", "resolution must be > 0");
    if (c.number("ray/scan/horizontal/min_angle") > c.number("ray/scan/horizontal/max_angle"))
      fail(s.line, w + "ray/scan/horizontal/min_angle", "min_angle " + c.text("ray/scan/horizontal/min_angle") +
           " > max_angle " + c.text("ray/scan/horizontal/max_angle"));
    if (c.number("ray/range/min") < 0) fail(s.line, w + "ray/range/min", "min must be >= 0");
    if (c.number("ray/range/min") >= c.number("ray/range/max"))
      fail(s.line, w + "ray/range/min",
           "min " + c.text("ray/range/min") + " >= max " + c.text("ray/range/max"));
    const std::string& nt = c.text("ray/noise/type");
    if (nt != "none" && nt != "gaussian") fail(s.line, w + "ray/noise/type", "unknown noise type '" + nt + "'");
    if (c.number("ray/noise/stddev") < 0) fail(s.line, w + "ray/noise/stddev", "stddev must be >= 0");
  }

  void validate_camera(const PluginConfig& c, const SensorSpec& s) {
    const std::string w = "sensor[" + s.name + "]/";
    if (c.number("camera/image/width") < 1) fail(s.line, w + "camera/image/width", "width must be >= 1");
    if (c.number("camera/image/height") < 1) fail(s.line, w + "camera/image/height", "height must be >= 1");
    const double fov = c.number("camera/horizontal_fov");
    if (!(fov > 0 && fov < M_PI)) fail(s.line, w + "camera/horizontal_fov", "must be in (0, pi) rad");
    if (!(c.number("camera/clip/near") > 0)) fail(s.line, w + "camera/clip/near", "near must be > 0");
    if (c.number("camera/clip/near") >= c.number("camera/clip/far"))
      fail(s.line, w + "camera/clip/near",
           "near " + c.text("camera/clip/near") + " >= far " + c.text("camera/clip/far"));
    const std::string& f = c.text("camera/image/format");
    static const std::set<std::string> formats = {"L8", "R8G8B8", "B8G8R8", "RGB_INT8", "BGR_INT8"};
    if (!formats.count(f))
      fail(s.line, w + "camera/image/format", "unknown format '" + f + "' (known: L8, R8G8B8, B8G8R8)");
  }

  void add_sensor_plugin(const std::string& kind, const PluginSpec& p, const SensorSpec& s) {
    static const std::map<std::string, std::set<std::string>> needs = {
        {"laser", {"ray", "gpu_ray"}}, {"openni_kinect", {"depth"}}, {"camera", {"camera"}}, {"imu", {"imu"}}};
    const std::string where = plugin_where(p, &s);
    if (!needs.at(kind).count(s.type))
      fail(p.line, where, p.filename + " needs a sensor of type " + *needs.at(kind).begin() + ", not '" + s.type + "'");
    PluginConfig c = make(kind, p, &s);
    const std::vector<ParamDef>& ss = kind == "laser" ? kRaySensor : kind == "imu" ? kImuSensor : kCameraSensor;
    resolve(ss, sensor_params(s), "sensor[" + s.name + "]", s.line, &c.params);
    resolve(plugin_schema(kind), p.params, where, p.line, &c.params);
    check_unknown_keys(kind, plugin_schema(kind), p, where);
    for (const char* fk : {"frameName"})
      for (auto& rp : c.params)
        if (rp.key == fk) rp.value = strip_slash(rp.value);
    if (kind == "laser") validate_ray(c, s);
    if (kind == "openni_kinect" || kind == "camera") validate_camera(c, s);
    if (kind == "openni_kinect" && c.number("pointCloudCutoff") >= c.number("pointCloudCutoffMax"))
      fail(p.line, where + "/pointCloudCutoff", "pointCloudCutoff " + c.text("pointCloudCutoff") +
           " >= pointCloudCutoffMax " + c.text("pointCloudCutoffMax"));
    if (kind == "imu") {
      for (auto& rp : c.params)
        if ((rp.key == "frameName" || rp.key == "bodyName") && rp.value.empty()) rp.value = s.link;
    }
    out_->plugins.push_back(std::move(c));
  }

  void run() {
    for (const auto& p : m_.plugins) {
      const std::string kind = plugin_kind(p.filename);
      const std::string where = plugin_where(p, nullptr);
      if (kind != "diff_drive" && kind != "imu") {
        warn(Severity::Warning, "plugin-unknown", where,
             "plug-in '" + p.filename + "' is not simulated by car; ignored", p.line);
        continue;
      }
      PluginConfig c = make(kind, p, nullptr);
      resolve(plugin_schema(kind), p.params, where, p.line, &c.params);
      check_unknown_keys(kind, plugin_schema(kind), p, where);
      for (auto& rp : c.params)
        if (rp.key == "odometryFrame" || rp.key == "robotBaseFrame" || rp.key == "frameName")
          rp.value = strip_slash(rp.value);
      if (kind == "diff_drive") validate_diff_drive(c, p, where);
      if (kind == "imu") {
        const std::string& body = c.text("bodyName");
        if (!m_.find_link(body)) fail(p.line, where + "/bodyName", "link '" + body + "' not found in the model");
        c.link = body;
        for (auto& rp : c.params)
          if (rp.key == "frameName" && rp.value.empty()) rp.value = body;
      }
      out_->plugins.push_back(std::move(c));
    }
    for (const auto& s : m_.sensors) {
      static const std::set<std::string> types = {"ray", "gpu_ray", "depth", "camera", "imu"};
      if (!types.count(s.type))
        warn(Severity::Warning, "sensor-unknown", "sensor[" + s.name + "]",
             "sensor type '" + s.type + "' is not simulated by car; ignored", s.line);
      if (s.plugins.empty())
        warn(Severity::Info, "sensor-no-plugin", "sensor[" + s.name + "]",
             "sensor has no plug-in, so nothing is published for it", s.line);
      for (const auto& p : s.plugins) {
        const std::string kind = plugin_kind(p.filename);
        if (kind.empty() || kind == "diff_drive") {
          warn(Severity::Warning, "plugin-unknown", plugin_where(p, &s),
               "plug-in '" + p.filename + "' is not simulated by car; ignored", p.line);
          continue;
        }
        add_sensor_plugin(kind, p, s);
      }
    }
  }

 private:
  const RobotModel& m_;
  ModelConfig* out_;
};

}  // namespace

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

std::string plugin_kind(const std::string& filename) {
  static const std::map<std::string, std::string> kinds = {
      {"libgazebo_ros_diff_drive.so", "diff_drive"},
      {"libgazebo_ros_laser.so", "laser"},
      {"libgazebo_ros_gpu_laser.so", "laser"},
      {"libgazebo_ros_openni_kinect.so", "openni_kinect"},
      {"libgazebo_ros_camera.so", "camera"},
      {"libgazebo_ros_imu_sensor.so", "imu"},
      {"libgazebo_ros_imu.so", "imu"},
  };
  const auto it = kinds.find(filename);
  return it == kinds.end() ? "" : it->second;
}

const std::vector<ParamDef>& plugin_schema(const std::string& kind) {
  static const std::vector<ParamDef> kinect = kinect_schema();
  static const std::vector<ParamDef> camera = camera_schema();
  if (kind == "diff_drive") return kDiffDrive;
  if (kind == "laser") return kLaser;
  if (kind == "openni_kinect") return kinect;
  if (kind == "camera") return camera;
  if (kind == "imu") return kImu;
  return kEmpty;
}

const ResolvedParam& PluginConfig::param(const std::string& key) const {
  for (const auto& p : params)
    if (p.key == key) return p;
  throw std::out_of_range("plug-in '" + name + "' has no key '" + key + "'");
}

const std::string& PluginConfig::text(const std::string& key) const { return param(key).value; }

double PluginConfig::number(const std::string& key) const {
  const auto v = parse_number(param(key).value);
  if (!v) throw std::invalid_argument("plug-in '" + name + "' key '" + key + "' is not a number");
  return *v;
}

bool PluginConfig::flag(const std::string& key) const {
  bool b = false;
  if (!parse_flag(param(key).value, &b))
    throw std::invalid_argument("plug-in '" + name + "' key '" + key + "' is not a boolean");
  return b;
}

ModelConfig resolve_plugins(const RobotModel& model) {
  ModelConfig out;
  Resolver(model, &out).run();
  return out;
}

}  // namespace car_sim
