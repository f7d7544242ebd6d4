// The multicamera: each <camera> of the sensor (its name kept by the loader as camera/@name) becomes one camera
// of the shared renderer, placed at sensor pose x camera pose; as upstream, only a camera whose name contains
// "left" (topics under cameraName/left) or "right" (cameraName/right, P with -f hackBaseline) is published.
// Both render at the same tick. Per docs/COMPAT-sensors.md.
#include "multicamera.hpp"

#include <cmath>
#include <set>
#include <sstream>

namespace car_sim {

namespace {

constexpr ParamType T = ParamType::Text;
constexpr const char* kSides[2] = {"left", "right"};

// The per-camera keys (under camera/), with SDF 1.6 defaults.
struct CameraKey {
  const char* key;
  const char* default_value;
  const char* unit;
};
const CameraKey kCameraKeys[] = {
    {"@name", "", ""},
    {"pose", "0 0 0 0 0 0", "m, rad"},
    {"horizontal_fov", "1.047", "rad"},
    {"image/width", "320", "px"},
    {"image/height", "240", "px"},
    {"image/format", "R8G8B8", ""},
    {"clip/near", "0.1", "m"},
    {"clip/far", "100", "m"},
    {"noise/type", "none", ""},
    {"noise/mean", "0", ""},
    {"noise/stddev", "0", ""},
};

// "camera[left]/horizontal_fov": where the resolved per-side values are kept in the plug-in's configuration.
std::string side_key(const char* side, const char* key) { return std::string("camera[") + side + "]/" + key; }

const char* interned(const std::string& s) {
  static std::set<std::string> pool;
  return pool.insert(s).first->c_str();
}

// The sensor's <camera> blocks in order: a block starts at its camera/@name, or where a key repeats.
std::vector<ParamList> camera_blocks(const SensorSpec& s) {
  std::vector<ParamList> blocks;
  std::set<std::string> seen;
  for (const auto& [k, v] : s.params) {
    if (k.rfind("camera/", 0) != 0) continue;
    const std::string sub = k.substr(7);
    if (blocks.empty() || sub == "@name" || seen.count(sub)) {
      blocks.emplace_back();
      seen.clear();
    }
    seen.insert(sub);
    blocks.back().emplace_back(sub, v);
  }
  return blocks;
}

bool number(const std::string& t, double* v) {
  std::istringstream ss(t);
  std::string rest;
  return (ss >> *v) && !(ss >> rest) && std::isfinite(*v);
}

void finish(ResolveContext& ctx) {
  const SensorSpec* s = ctx.sensor();
  for (const ParamList& block : camera_blocks(*s)) {
    std::string name;
    for (const auto& [k, v] : block)
      if (k == "@name") name = v;
    for (const char* side : kSides) {
      if (name.find(side) == std::string::npos || !ctx.config().text(side_key(side, "@name")).empty()) continue;
      ctx.set(side_key(side, "@name"), name);
      for (const auto& [k, v] : block) {
        bool known = false;
        for (const CameraKey& ck : kCameraKeys) known = known || k == ck.key;
        if (known) ctx.set(side_key(side, k.c_str()), v);
      }
      // the same checks as a single camera's
      const std::string where = "camera[" + name + "]/";
      auto num = [&](const char* k) {
        double v = 0;
        if (!number(ctx.config().text(side_key(side, k)), &v))
          ctx.fail_sensor(where + k, "'" + ctx.config().text(side_key(side, k)) + "' is not a number");
        return v;
      };
      if (num("image/width") < 1 || std::floor(num("image/width")) != num("image/width"))
        ctx.fail_sensor(where + "image/width", "width must be a whole number >= 1");
      if (num("image/height") < 1 || std::floor(num("image/height")) != num("image/height"))
        ctx.fail_sensor(where + "image/height", "height must be a whole number >= 1");
      const double fov = num("horizontal_fov");
      if (!(fov > 0 && fov < M_PI)) ctx.fail_sensor(where + "horizontal_fov", "must be in (0, pi) rad");
      if (!(num("clip/near") > 0)) ctx.fail_sensor(where + "clip/near", "near must be > 0");
      if (num("clip/near") >= num("clip/far")) ctx.fail_sensor(where + "clip/near", "near >= far");
      static const std::set<std::string> formats = {"L8", "R8G8B8", "B8G8R8", "RGB_INT8", "BGR_INT8"};
      const std::string& f = ctx.config().text(side_key(side, "image/format"));
      if (!formats.count(f)) ctx.fail_sensor(where + "image/format", "unknown format '" + f + "'");
      std::istringstream ps(ctx.config().text(side_key(side, "pose")));
      double p[6];
      for (double& x : p)
        if (!(ps >> x)) ctx.fail_sensor(where + "pose", "pose is not 6 numbers");
    }
  }
  if (ctx.config().text(side_key("left", "@name")).empty() && ctx.config().text(side_key("right", "@name")).empty())
    ctx.warn(Severity::Warning, "multicamera-unnamed", "",
             "no <camera> of sensor '" + s->name + "' has 'left' or 'right' in its name: nothing is published");
}

class MultiCamera : public Plugin {
 public:
  MultiCamera(const PluginConfig& c, const std::string& robot, uint64_t seed) : rate_(c.number("update_rate")) {
    for (const char* side : kSides) {
      if (c.text(side_key(side, "@name")).empty()) continue;
      // this side as a plain camera: its keys under camera/, its pose after the sensor's, its own noise stream
      PluginConfig cc = c;
      for (const CameraKey& ck : kCameraKeys) {
        if (std::string(ck.key) == "@name" || std::string(ck.key) == "pose") continue;
        cc.params.push_back({std::string("camera/") + ck.key, c.text(side_key(side, ck.key)), ck.unit, false});
      }
      std::istringstream ps(c.text(side_key(side, "pose")));
      double p[6] = {0, 0, 0, 0, 0, 0};
      for (double& x : p) ps >> x;
      Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
      T.translation() = Eigen::Vector3d(p[0], p[1], p[2]);
      T.linear() = (Eigen::AngleAxisd(p[5], Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(p[4], Eigen::Vector3d::UnitY()) *
                    Eigen::AngleAxisd(p[3], Eigen::Vector3d::UnitX()))
                       .toRotationMatrix();
      cc.sensor_pose = c.sensor_pose * T;
      cc.sensor = c.sensor + "/" + side;
      sides_.push_back(side);
      cameras_.push_back(std::make_unique<CameraPlugin>(cc, robot, seed, false));
    }
  }

  double update_rate() const override { return rate_; }
  void reset() override {
    for (auto& c : cameras_) c->reset();
  }

  void post_physics(const StepContext& ctx, const RobotHandle& robot, OutputQueue* out) override {
    auto o = std::make_unique<MultiCameraOut>();
    for (size_t i = 0; i < cameras_.size(); ++i) {
      OutputQueue q;
      cameras_[i]->post_physics(ctx, robot, &q);
      o->sides.push_back(sides_[i]);
      o->frames.push_back(std::move(static_cast<CameraOut&>(*q.front())));
    }
    out->push_back(std::move(o));
  }

 private:
  double rate_;
  std::vector<std::string> sides_;
  std::vector<std::unique_ptr<CameraPlugin>> cameras_;
};

}  // namespace

void MultiCameraOut::samples(SampleList& list) const {
  for (size_t i = 0; i < frames.size(); ++i) list.add(frames[i].frame_view(), {}, i);
}

// Each side's fields under "<side>/": e.g. "left/image".
void MultiCameraOut::visit(FieldVisitor& v) const {
  class Prefixed : public FieldVisitor {
   public:
    Prefixed(FieldVisitor& v, const std::string& p) : v_(v), p_(p) {}
    void number(const char* k, double x) override { v_.number((p_ + k).c_str(), x); }
    void integer(const char* k, int64_t x) override { v_.integer((p_ + k).c_str(), x); }
    void text(const char* k, const std::string& x) override { v_.text((p_ + k).c_str(), x); }
    void vector(const char* k, const double* x, size_t n) override { v_.vector((p_ + k).c_str(), x, n); }
    void array(const char* k, const float* d, const std::vector<size_t>& s) override { v_.array((p_ + k).c_str(), d, s); }
    void array(const char* k, const uint8_t* d, const std::vector<size_t>& s) override { v_.array((p_ + k).c_str(), d, s); }

   private:
    FieldVisitor& v_;
    std::string p_;
  };
  for (size_t i = 0; i < frames.size(); ++i) {
    Prefixed p(v, sides[i] + "/");
    frames[i].visit(p);
  }
}

const PluginKind& multicamera_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "multicamera";
    k.filenames = {"libgazebo_ros_multicamera.so"};
    k.namespace_rule = NamespaceRule::EmptyIsModel;  // GetRobotNamespace (gazebo_ros_camera_utils.cpp)
    k.model_level = false;
    k.sensor_types = {"multicamera"};
    k.sensor_schema = {{"update_rate", ParamType::Number, "0", "Hz"}};
    k.schema = camera_plugin_schema();
    k.schema.push_back({"imageTopicName", T, "image_raw", ""});
    k.schema.push_back({"cameraInfoTopicName", T, "camera_info", ""});
    // filled in by finish from the sensor's <camera> blocks
    for (const char* side : kSides)
      for (const CameraKey& ck : kCameraKeys)
        k.schema.push_back({interned(side_key(side, ck.key)), T, ck.default_value, ck.unit});
    k.ignored = camera_ignored_keys();
    k.lazy = true;
    k.output_group = "multicameras";
    k.finish = finish;
    // per side that has a camera, its image and camera_info under <cameraName>/<side> (the frames in the same
    // order); the right camera's P carries -f hackBaseline
    k.outputs = [](const PluginConfig& c, const std::string& robot, const Environment&) {
      std::vector<OutputPort> ports;
      size_t frame = 0;
      for (const char* side : kSides) {
        if (c.text(side_key(side, "@name")).empty()) continue;
        const double baseline = std::string(side) == "left" ? 0.0 : c.number("hackBaseline");
        for (OutputPort& p : camera_ports(c, robot, std::string("/") + side, frame, baseline)) {
          p.name = std::string(side) + "/" + p.name;
          ports.push_back(std::move(p));
        }
        ++frame;
      }
      throttle_images(&ports);
      return ports;
    };
    k.make = [](const PluginConfig& c, const std::string& robot, uint64_t seed) -> std::unique_ptr<Plugin> {
      return std::make_unique<MultiCamera>(c, robot, seed);
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
