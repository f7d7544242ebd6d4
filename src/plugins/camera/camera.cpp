// The ray-cast camera (shared by the camera and depth-camera kinds) and the libgazebo_ros_camera.so kind.
// Behaviour per docs/COMPAT.md: one focal length f = W / (2 tan(hfov / 2)), cx = (W-1)/2, cy = (H-1)/2 (fix),
// colour channels in the image format's order (fix), depth NaN outside (cutoff, cutoff_max).
#include "camera.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

namespace car_sim {

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType Fr = ParamType::Frame;
constexpr ParamType N = ParamType::Number;
constexpr ParamType I = ParamType::Integer;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr double kInfD = std::numeric_limits<double>::infinity();
// Stated limits, checked before anything is allocated: each image side, pixels per image (a depth frame holds about
// 80 bytes a pixel: rays, hits, colour, depth, cloud) and pixels per second (pixels x update_rate).
constexpr double kMaxSide = 8192;
constexpr double kMaxPixels = 4194304;  // 2048 x 2048
constexpr double kMaxPixelsPerSecond = 1e9;

}  // namespace

const std::vector<ParamDef>& camera_sensor_schema() {
  static const std::vector<ParamDef> s = {
      {"update_rate", N, "0", "Hz"},
      {"camera/horizontal_fov", N, "1.047", "rad"},
      {"camera/image/width", I, "320", "px", -kInfD, kMaxSide},
      {"camera/image/height", I, "240", "px", -kInfD, kMaxSide},
      {"camera/image/format", T, "R8G8B8", ""},
      {"camera/clip/near", N, "0.1", "m"},
      {"camera/clip/far", N, "100", "m"},
      {"camera/noise/type", T, "none", ""},
      {"camera/noise/mean", N, "0", ""},
      {"camera/noise/stddev", N, "0", ""},
  };
  return s;
}

const std::vector<ParamDef>& camera_plugin_schema() {
  static const std::vector<ParamDef> s = {
      {"robotNamespace", T, "", ""},
      {"cameraName", T, "", ""},
      {"frameName", Fr, "/world", ""},
      {"updateRate", N, "0", "Hz"},
      {"hackBaseline", N, "0", "m"},
      {"distortionK1", N, "0", ""},
      {"distortionK2", N, "0", ""},
      {"distortionK3", N, "0", ""},
      {"distortionT1", N, "0", ""},
      {"distortionT2", N, "0", ""},
  };
  return s;
}

const std::map<std::string, std::string>& camera_ignored_keys() {
  static const std::map<std::string, std::string> m = {
      {"alwaysOn", ""},
      {"baseline", "<baseline> is never read upstream; set hackBaseline"},
      {"Cx", "car computes cx = (W-1)/2 from the image"},
      {"Cy", "car computes cy = (H-1)/2 from the image"},
      {"CxPrime", "car computes cx = (W-1)/2 from the image"},
      {"focalLength", "car computes f from the image width and horizontal_fov"}};
  return m;
}

void finish_camera(ResolveContext& ctx) {
  const PluginConfig& c = ctx.config();
  if (c.number("camera/image/width") < 1) ctx.fail_sensor("camera/image/width", "width must be >= 1");
  if (c.number("camera/image/height") < 1) ctx.fail_sensor("camera/image/height", "height must be >= 1");
  const double px = c.number("camera/image/width") * c.number("camera/image/height");
  if (px > kMaxPixels)
    ctx.fail_sensor("camera/image/width", "width x height = " + std::to_string(static_cast<long long>(px)) +
                                              " px is above the limit 4194304 px (2048 x 2048)");
  if (px * c.number("update_rate") > kMaxPixelsPerSecond)
    ctx.fail_sensor("update_rate", "width x height x update_rate = " + std::to_string(static_cast<long long>(px * c.number("update_rate"))) +
                                       " px/s is above the limit 1e9 px/s");
  const double fov = c.number("camera/horizontal_fov");
  if (!(fov > 0 && fov < M_PI)) ctx.fail_sensor("camera/horizontal_fov", "must be in (0, pi) rad");
  if (!(c.number("camera/clip/near") > 0)) ctx.fail_sensor("camera/clip/near", "near must be > 0");
  if (c.number("camera/clip/near") >= c.number("camera/clip/far"))
    ctx.fail_sensor("camera/clip/near", "near " + c.text("camera/clip/near") + " >= far " + c.text("camera/clip/far"));
  const std::string& f = c.text("camera/image/format");
  static const std::set<std::string> formats = {"L8", "R8G8B8", "B8G8R8", "RGB_INT8", "BGR_INT8"};
  if (!formats.count(f))
    ctx.fail_sensor("camera/image/format", "unknown format '" + f + "' (known: L8, R8G8B8, B8G8R8)");
}

CameraPlugin::CameraPlugin(const PluginConfig& c, const std::string& robot, uint64_t seed, bool depth)
    : link_(c.link), sensor_pose_(c.sensor_pose), rate_(c.number("update_rate")),
      rng0_(plugin_rng(seed, robot, c.sensor)), rng_(rng0_) {
  proto_.sensor = c.sensor;
  w_ = static_cast<int>(c.number("camera/image/width"));
  h_ = static_cast<int>(c.number("camera/image/height"));
  proto_.width = w_;
  proto_.height = h_;
  const double hfov = c.number("camera/horizontal_fov");
  proto_.f = w_ / (2.0 * std::tan(hfov / 2.0));
  proto_.cx = (w_ - 1) / 2.0;
  proto_.cy = (h_ - 1) / 2.0;
  near_ = c.number("camera/clip/near");
  far_ = c.number("camera/clip/far");
  const std::string fmt = c.text("camera/image/format");
  proto_.encoding = fmt == "L8" ? "mono8" : (fmt == "B8G8R8" || fmt == "BGR_INT8") ? "bgr8" : "rgb8";
  proto_.has_depth = depth;
  if (depth) {
    cutoff_ = c.number("pointCloudCutoff");
    // the generic depth camera has no upper cutoff
    cutoff_max_ = c.has("pointCloudCutoffMax") ? c.number("pointCloudCutoffMax") : kInf;
  }
  gaussian_ = c.text("camera/noise/type") == "gaussian";
  noise_mean_ = c.number("camera/noise/mean");
  noise_stddev_ = c.number("camera/noise/stddev");
  // one ray per pixel through its centre; sensor frame x forward, y left, z up
  const size_t n = static_cast<size_t>(w_) * h_;
  pixel_.reserve(n);
  for (int tv = 0; tv < h_; tv += 4)
    for (int tu = 0; tu < w_; tu += 4)
      for (int v = tv; v < std::min(tv + 4, h_); ++v)
        for (int u = tu; u < std::min(tu + 4, w_); ++u) pixel_.push_back(v * w_ + u);
  dirs_.resize(3 * n);
  cos_.resize(n);
  t_near_.resize(n);
  double min_cos = 1.0;
  for (size_t k = 0; k < n; ++k) {
    const int u = pixel_[k] % w_, v = pixel_[k] / w_;
    const Eigen::Vector3d d = Eigen::Vector3d(proto_.f, -(u - proto_.cx), -(v - proto_.cy)).normalized();
    dirs_[3 * k] = static_cast<float>(d.x());
    dirs_[3 * k + 1] = static_cast<float>(d.y());
    dirs_[3 * k + 2] = static_cast<float>(d.z());
    cos_[k] = static_cast<float>(d.x());
    t_near_[k] = static_cast<float>(near_ / d.x());  // the near clip plane, along this ray
    min_cos = std::min(min_cos, d.x());
  }
  t_far_ = static_cast<float>(far_ / min_cos);
  hits_.resize(n);
  rgb_.resize(3 * n);
}

void CameraPlugin::post_physics(const StepContext& ctx, const RobotHandle& robot, OutputQueue* out) {
  const int n = w_ * h_;
  const Eigen::Isometry3d pose = robot.link_pose(link_) * sensor_pose_;
  const RayScene& scene = ctx.world->rays();
  const Environment& env = ctx.world->environment();
  scene.cast(pose.translation(), pose.linear(), dirs_.data(), n, t_near_.data(), true, t_far_, hits_.data());
  auto o = std::make_unique<CameraOut>(proto_);
  const int channels = o->encoding == "mono8" ? 1 : 3;
  o->image.resize(static_cast<size_t>(n) * channels);
  if (o->has_depth) {
    o->depth.resize(n);
    o->points.resize(3 * static_cast<size_t>(n));
    o->point_rgb.resize(3 * static_cast<size_t>(n));
  }
  const Eigen::Vector3f light = (-env.sun_direction).normalized().cast<float>();
  const float ambient = static_cast<float>(env.ambient);
  const Eigen::Vector3f bg = env.background.cast<float>();
  const bool mono = o->encoding == "mono8";
  const bool bgr = o->encoding == "bgr8";
  const float f = static_cast<float>(o->f), cx = static_cast<float>(o->cx), cy = static_cast<float>(o->cy);
  const float far = static_cast<float>(far_);
  CameraOut& im = *o;
  // per pixel: depth, colour, point; independent pixels, so in parallel (noise, when configured, after)
#pragma omp parallel for schedule(static)
  for (int k = 0; k < n; ++k) {
    const int i = pixel_[k];
    const RayHit& h = hits_[k];
    // depth along the optical axis; beyond the far clip is no hit
    float d = std::isfinite(h.distance) ? h.distance * cos_[k] : kInf;
    if (d >= far) d = kInf;
    // colour: the material lit by the ambient and the directional light (Lambert), else the background
    Eigen::Vector3f rgb = bg;
    if (std::isfinite(d)) {
      const Eigen::Vector4d& m = scene.look(h.body).rgba;
      const float lit = std::min(1.f, ambient + 0.8f * std::max(0.f, h.normal.dot(light)));
      rgb = (m.head<3>().cast<float>() * lit).cwiseMin(1.f);
    }
    rgb_[3 * i] = rgb.x();
    rgb_[3 * i + 1] = rgb.y();
    rgb_[3 * i + 2] = rgb.z();
    if (!im.has_depth) continue;
    const bool valid = std::isfinite(d) && d > cutoff_ && d < cutoff_max_;
    const float dv = valid ? d : kNaN;
    im.depth[i] = dv;
    const int u = i % w_, v = i / w_;
    im.points[3 * i] = dv * (u - cx) / f;
    im.points[3 * i + 1] = dv * (v - cy) / f;
    im.points[3 * i + 2] = dv;
  }
  if (gaussian_) {
    std::normal_distribution<double> noise(noise_mean_, noise_stddev_ > 0 ? noise_stddev_ : 1.0);
    for (int i = 0; i < 3 * n; ++i) rgb_[i] = std::clamp(rgb_[i] + static_cast<float>(noise(rng_)), 0.f, 1.f);
  }
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    // [0, 1] to 0..255, rounded
    const uint8_t r = static_cast<uint8_t>(rgb_[3 * i] * 255.f + 0.5f);
    const uint8_t g = static_cast<uint8_t>(rgb_[3 * i + 1] * 255.f + 0.5f);
    const uint8_t b = static_cast<uint8_t>(rgb_[3 * i + 2] * 255.f + 0.5f);
    if (mono) {
      im.image[i] = static_cast<uint8_t>(0.299f * r + 0.587f * g + 0.114f * b + 0.5f);
    } else {
      // fix: channel order follows the image format (upstream swaps R and B for R8G8B8)
      im.image[3 * i] = bgr ? b : r;
      im.image[3 * i + 1] = g;
      im.image[3 * i + 2] = bgr ? r : b;
    }
    if (im.has_depth) {
      im.point_rgb[3 * i] = r;
      im.point_rgb[3 * i + 1] = g;
      im.point_rgb[3 * i + 2] = b;
    }
  }
  out->push_back(std::move(o));
}

void CameraOut::visit(FieldVisitor& v) const {
  v.integer("width", width);
  v.integer("height", height);
  v.number("f", f);
  v.number("cx", cx);
  v.number("cy", cy);
  v.text("encoding", encoding);
  const size_t H = static_cast<size_t>(height), W = static_cast<size_t>(width);
  v.array("image", image.data(), {H, W, encoding == "mono8" ? size_t(1) : size_t(3)});
  if (!has_depth) return;
  v.array("depth", depth.data(), {H, W});
  v.array("points", points.data(), {H, W, 3});
  v.array("point_rgb", point_rgb.data(), {H, W, 3});
}

const PluginKind& camera_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "camera";
    k.filenames = {"libgazebo_ros_camera.so"};
    k.model_level = false;
    k.sensor_types = {"camera"};
    k.sensor_schema = camera_sensor_schema();
    k.schema = camera_plugin_schema();
    k.schema.push_back({"imageTopicName", T, "image_raw", ""});
    k.schema.push_back({"cameraInfoTopicName", T, "camera_info", ""});
    k.ignored = camera_ignored_keys();
    k.lazy = true;
    k.output_group = "images";
    k.finish = finish_camera;
    k.make = [](const PluginConfig& c, const std::string& robot, uint64_t seed) -> std::unique_ptr<Plugin> {
      return std::make_unique<CameraPlugin>(c, robot, seed, false);
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
