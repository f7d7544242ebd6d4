// The ray-cast camera every camera kind shares, and the record of the libgazebo_ros_camera.so kind.
// Behaviour per docs/COMPAT-spec.md: one focal length f = W / (2 tan(hfov / 2)), cx = (W-1)/2, cy = (H-1)/2 (fix),
// colour channels in the image format's order (fix), depth NaN outside (cutoff, cutoff_max).
#include "camera_render.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstddef>
#include <cstring>
#include <limits>
#include <map>
#include <sstream>

namespace car_sim {

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType Fr = ParamType::Frame;
constexpr ParamType N = ParamType::Number;
constexpr ParamType I = ParamType::Integer;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

}  // namespace

const std::vector<ParamDef>& camera_sensor_schema() {
  static const std::vector<ParamDef> s = {
      {"update_rate", N, "0", "Hz"},
      {"camera/horizontal_fov", N, "1.047", "rad"},
      // sizes within the sensor limits, checked where the description is read (validate.hpp check_sensor_limits)
      {"camera/image/width", I, "320", "px"},
      {"camera/image/height", I, "240", "px"},
      {"camera/image/format", T, "R8G8B8", ""},
      {"camera/clip/near", N, "0.1", "m"},
      {"camera/clip/far", N, "100", "m"},
      {"camera/noise/type", T, "none", ""},
      {"camera/noise/mean", N, "0", ""},
      {"camera/noise/stddev", N, "0", ""},
      {"camera/distortion/k1", N, "0", ""},
      {"camera/distortion/k2", N, "0", ""},
      {"camera/distortion/k3", N, "0", ""},
      {"camera/distortion/p1", N, "0", ""},
      {"camera/distortion/p2", N, "0", ""},
      {"camera/distortion/center", T, "0.5 0.5", ""},
  };
  return s;
}

const std::vector<ParamDef>& camera_plugin_schema() {
  static const std::vector<ParamDef> s = {
      {"robotNamespace", T, "", ""},
      {"cameraName", T, "", ""},
      {"frameName", Fr, "", ""},  // camera_utils only logs "defaults to /world": frame_name_ stays ""
      {"updateRate", N, "0", "Hz"},
      {"hackBaseline", N, "0", "m"},
      {"distortionK1", N, "0", ""},
      {"distortionK2", N, "0", ""},
      {"distortionK3", N, "0", ""},
      {"distortionT1", N, "0", ""},
      {"distortionT2", N, "0", ""},
      {"autoDistortion", ParamType::Flag, "false", ""},
      {"borderCrop", ParamType::Flag, "false", ""},
      // camera_info's intrinsics: 0 = computed from the image and horizontal_fov (GazeboRosCameraUtils::Init)
      {"Cx", N, "0", "px"},
      {"Cy", N, "0", "px"},
      {"focalLength", N, "0", "px"},
  };
  return s;
}

const std::map<std::string, std::string>& camera_ignored_keys() {
  static const std::map<std::string, std::string> m = {
      {"alwaysOn", ""},
      {"baseline", "<baseline> is never read upstream; set hackBaseline"},
      {"CxPrime", "read upstream and used nowhere"}};
  return m;
}

void finish_camera(ResolveContext& ctx) {
  const PluginConfig& c = ctx.config();
  if (c.number("camera/image/width") < 1) ctx.fail_sensor("camera/image/width", "width must be >= 1");
  if (c.number("camera/image/height") < 1) ctx.fail_sensor("camera/image/height", "height must be >= 1");
  const double fov = c.number("camera/horizontal_fov");
  if (!(fov > 0 && fov < M_PI)) ctx.fail_sensor("camera/horizontal_fov", "must be in (0, pi) rad");
  if (!(c.number("camera/clip/near") > 0)) ctx.fail_sensor("camera/clip/near", "near must be > 0");
  if (c.number("camera/clip/near") >= c.number("camera/clip/far"))
    ctx.fail_sensor("camera/clip/near", "near " + c.text("camera/clip/near") + " >= far " + c.text("camera/clip/far"));
  // autoDistortion: camera_info's D from the sensor's <distortion> (docs/COMPAT-sensors.md "Lens distortion")
  if (c.has("autoDistortion") && c.flag("autoDistortion")) {
    for (const auto& [key, from] : std::map<std::string, std::string>{{"distortionK1", "k1"}, {"distortionK2", "k2"},
                                                                       {"distortionK3", "k3"}, {"distortionT1", "p1"},
                                                                       {"distortionT2", "p2"}})
      ctx.set(key, c.text("camera/distortion/" + from));
    if (c.has("borderCrop") && c.flag("borderCrop"))
      ctx.warn(Severity::Warning, "border_crop", "borderCrop", "borderCrop true is not done: the image is not scaled");
  }
  if (c.has("camera/distortion/center")) {
    std::istringstream cs(c.text("camera/distortion/center"));
    double x = 0, y = 0;
    if (!(cs >> x >> y)) ctx.fail_sensor("camera/distortion/center", "must be two numbers");
  }
  // GazeboRosCameraUtils::Init's check of a given focal length against width and horizontal_fov
  // (ignition::math::equal: within 1e-6), in its words
  const double focal = c.number("focalLength");
  const double computed = c.number("camera/image/width") / (2.0 * std::tan(fov / 2.0));
  if (focal != 0 && !(std::abs(focal - computed) <= 1e-6)) {
    char msg[512];
    std::snprintf(msg, sizeof msg,
                  "The <focal_length>[%f] you have provided for camera_ [%s] is inconsistent with specified "
                  "image_width [%d] and HFOV [%f].   Please double check to see that focal_length = width_ / (2.0 * "
                  "tan(HFOV/2.0)), the explected focal_lengtth value is [%f], please update your camera_ model "
                  "description accordingly.",
                  focal, c.sensor.c_str(), static_cast<int>(c.number("camera/image/width")), fov, computed);
    ctx.warn(Severity::Warning, "focal-length", "focalLength", msg);
  }
  const std::string& f = c.text("camera/image/format");
  if (camera_encoding(f).empty())
    ctx.fail_sensor("camera/image/format", "unknown format '" + f + "' (known: L8, L16, R8G8B8, B8G8R8, R16G16B16)");
}

std::string camera_encoding(const std::string& format) {
  // gazebo_ros_camera_utils' names, with sdformat's aliases
  static const std::map<std::string, std::string> enc = {
      {"L8", "mono8"},    {"L_INT8", "mono8"},   {"L16", "mono16"},       {"L_INT16", "mono16"},
      {"R8G8B8", "rgb8"}, {"RGB_INT8", "rgb8"},  {"B8G8R8", "bgr8"},      {"BGR_INT8", "bgr8"},
      {"R16G16B16", "rgb16"}, {"RGB_INT16", "rgb16"}};
  const auto it = enc.find(format);
  return it == enc.end() ? std::string() : it->second;
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
  proto_.encoding = camera_encoding(c.text("camera/image/format"));
  if (proto_.encoding.empty()) proto_.encoding = "rgb8";
  sixteen_ = proto_.channel_bytes() == 2;
  proto_.has_depth = depth;
  if (depth) {
    cutoff_ = c.number("pointCloudCutoff");
    // the generic depth camera has no upper cutoff
    cutoff_max_ = c.has("pointCloudCutoffMax") ? c.number("pointCloudCutoffMax") : kInf;
  }
  if (c.has("camera/distortion/k1")) {
    lens_ = {c.number("camera/distortion/k1"), c.number("camera/distortion/k2"), c.number("camera/distortion/k3"),
             c.number("camera/distortion/p1"), c.number("camera/distortion/p2")};
    std::istringstream cs(c.text("camera/distortion/center"));
    double x = 0.5, y = 0.5;
    cs >> x >> y;
    lens_cx_ = x * w_ - 0.5;
    lens_cy_ = y * h_ - 0.5;
    distorted_ = lens_[0] != 0 || lens_[1] != 0 || lens_[2] != 0 || lens_[3] != 0 || lens_[4] != 0;
  }
  gaussian_ = c.text("camera/noise/type") == "gaussian";
  noise_mean_ = c.number("camera/noise/mean");
  noise_stddev_ = c.number("camera/noise/stddev");
  pinhole_ = Pinhole{w_, h_, proto_.f, proto_.cx, proto_.cy, near_};
}

// The per-pixel arrays (about 10 MB for 640 x 480) made at the first frame, not at spawn: a robot's camera that
// nobody subscribes to costs neither memory nor time (a fleet of 200 seed cars took 2 GB and 8 ms a spawn).
void CameraPlugin::prepare() {
  if (prepared_) return;
  prepared_ = true;
  if (distorted_) make_lens_map();
  // one ray per pixel through its centre; sensor frame x forward, y left, z up
  const size_t n = static_cast<size_t>(w_) * h_;
  dirs_.resize(3 * n);
  double min_cos = 1.0;
  for (size_t k = 0; k < n; ++k) {
    const int u = static_cast<int>(k % w_), v = static_cast<int>(k / w_);
    const Eigen::Vector3d d = Eigen::Vector3d(proto_.f, -(u - proto_.cx), -(v - proto_.cy)).normalized();
    dirs_[3 * k] = static_cast<float>(d.x());
    dirs_[3 * k + 1] = static_cast<float>(d.y());
    dirs_[3 * k + 2] = static_cast<float>(d.z());
    min_cos = std::min(min_cos, d.x());
  }
  t_far_ = static_cast<float>(far_ / min_cos);
  hits_.resize(n);
  if (gaussian_ || sixteen_) rgb_.resize(3 * n);
}

namespace {

// What shading a row needs: the frame's hits, rays and outputs (whole-frame pointers), the lighting and cutoffs.
struct Shading {
  const RayHit* hits;          // per pixel
  const float* dirs;           // x y z per pixel, sensor frame; x is the depth per unit distance
  const float* col_factor;     // (u - cx) / f per column
  const Eigen::Vector3f* mat;  // material colour per body
  Eigen::Vector3f light, bg;   // unit direction towards the light (world frame); background colour
  float ambient, far_clip, cut_lo, cut_hi, f, cy;
  int w;
  uint8_t* image;              // in the image's format
  float* depth;                // with kDepth: depth, points and point_rgb
  float* points;
  uint8_t* point_rgb;
  float* noisy_rgb;            // with kNoisy: [0, 1] r g b per pixel instead of image and point_rgb
};

// The hits of a RayHit after its distance: normal and body, 16 bytes (compared as two words).
static_assert(offsetof(RayHit, normal) == 4 && offsetof(RayHit, body) == 16 && sizeof(RayHit) == 20,
              "RayHit layout");

// A colour's bytes: [0, 1] to 0..255 rounded, and its grey (mono8).
struct PixelBytes {
  uint8_t r, g, b, grey;
};

inline PixelBytes pixel_bytes(float rf, float gf, float bf) {
  PixelBytes c;
  c.r = static_cast<uint8_t>(rf * 255.f + 0.5f);
  c.g = static_cast<uint8_t>(gf * 255.f + 0.5f);
  c.b = static_cast<uint8_t>(bf * 255.f + 0.5f);
  c.grey = static_cast<uint8_t>(0.299f * c.r + 0.587f * c.g + 0.114f * c.b + 0.5f);
  return c;
}

// One pixel's bytes into the image, in its channel order (mode 0 rgb8, 1 bgr8, 2 mono8), and r g b into the
// cloud's colour (cloud null: none).
inline void put_pixel(int mode, const PixelBytes& c, uint8_t* image, uint8_t* cloud) {
  if (mode == 2) {
    image[0] = c.grey;
  } else {
    // fix: channel order follows the image format (upstream swaps R and B for R8G8B8)
    image[0] = mode == 1 ? c.b : c.r;
    image[1] = c.g;
    image[2] = mode == 1 ? c.r : c.b;
  }
  if (cloud) {
    cloud[0] = c.r;
    cloud[1] = c.g;
    cloud[2] = c.b;
  }
}

// Row v: depth along the optical axis and the cloud (kDepth), and colour: the material lit by the ambient and the
// directional light (Lambert), else the background; [0, 1] to 0..255 rounded, in the image's channel order (kMode
// 0 rgb8, 1 bgr8, 2 mono8), r g b into the cloud's colour; kNoisy: the [0, 1] floats into noisy_rgb instead (the
// noise is drawn after). Beyond the far clip along the optical axis (or no hit: +inf) is no hit. A pixel's colour
// depends only on (body, normal), the same for every pixel of a flat face: it is worked out again only when these
// differ from the previous pixel's (the same arithmetic, so the same bytes).
template <int kMode, bool kDepth, bool kNoisy>
void shade_row(const Shading& s, int v) {
  const int w = s.w;
  const size_t i0 = static_cast<size_t>(v) * w;
  const RayHit* __restrict const hit_px = s.hits + i0;
  const float* __restrict const dir = s.dirs + 3 * i0;
  const float* __restrict const xf = s.col_factor;
  const Eigen::Vector3f* __restrict const mat = s.mat;
  uint8_t* __restrict const image = s.image + (kMode == 2 ? 1 : 3) * i0;
  float* __restrict const depth = kDepth ? s.depth + i0 : nullptr;
  float* __restrict const points = kDepth ? s.points + 3 * i0 : nullptr;
  uint8_t* __restrict const cloud_rgb = kDepth ? s.point_rgb + 3 * i0 : nullptr;
  float* __restrict const noisy_rgb = kNoisy ? s.noisy_rgb + 3 * i0 : nullptr;
  const float lx = s.light.x(), ly = s.light.y(), lz = s.light.z();
  const float amb = s.ambient, far_clip = s.far_clip, lo = s.cut_lo, hi = s.cut_hi;
  const float yf = (v - s.cy) / s.f;
  int key_hit = -1;  // the previous pixel's: hit (1) or not (0), -1 before the first; with its normal and body
  uint64_t key0 = 0, key1 = 0;
  float rf = 0, gf = 0, bf = 0;
  PixelBytes px{0, 0, 0, 0};
  for (int u = 0; u < w; ++u) {
    const RayHit& h = hit_px[u];
    const float d = h.distance * dir[3 * u];
    const bool hit = d < far_clip;
    if (kDepth) {
      // & rather than &&: no branch
      const float dv = (hit & (d > lo) & (d < hi)) ? d : kNaN;
      depth[u] = dv;
      points[3 * u] = dv * xf[u];
      points[3 * u + 1] = dv * yf;
      points[3 * u + 2] = dv;
    }
    uint64_t n0, n1;
    std::memcpy(&n0, reinterpret_cast<const char*>(&h) + 4, 8);
    std::memcpy(&n1, reinterpret_cast<const char*>(&h) + 12, 8);
    if ((static_cast<int>(hit) != key_hit) | (hit & (((n0 ^ key0) | (n1 ^ key1)) != 0))) {
      key_hit = hit;
      key0 = n0, key1 = n1;
      rf = s.bg.x(), gf = s.bg.y(), bf = s.bg.z();
      if (hit) {
        const float lit = std::min(1.f, amb + 0.8f * std::max(0.f, h.normal.x() * lx + h.normal.y() * ly +
                                                                        h.normal.z() * lz));
        const Eigen::Vector3f& m = mat[h.body];
        rf = std::min(1.f, m.x() * lit);
        gf = std::min(1.f, m.y() * lit);
        bf = std::min(1.f, m.z() * lit);
      }
      px = pixel_bytes(rf, gf, bf);
    }
    if (kNoisy) {
      noisy_rgb[3 * u] = rf;
      noisy_rgb[3 * u + 1] = gf;
      noisy_rgb[3 * u + 2] = bf;
      continue;
    }
    // rgb8's cloud colour is copied from the image row after the loop
    put_pixel(kMode, px, image + (kMode == 2 ? 1 : 3) * u, kDepth && kMode != 0 ? cloud_rgb + 3 * u : nullptr);
  }
  // rgb8: the cloud's colour is the image row's bytes
  if constexpr (kDepth && kMode == 0 && !kNoisy) std::memcpy(cloud_rgb, image, 3 * static_cast<size_t>(w));
}

// Row v's depth alone (a depth camera whose image and cloud nobody takes): the same values as shade_row's.
void depth_row(const Shading& s, int v) {
  const int w = s.w;
  const size_t i0 = static_cast<size_t>(v) * w;
  const RayHit* __restrict const hit_px = s.hits + i0;
  const float* __restrict const dir = s.dirs + 3 * i0;
  float* __restrict const depth = s.depth + i0;
  const float far_clip = s.far_clip, lo = s.cut_lo, hi = s.cut_hi;
  for (int u = 0; u < w; ++u) {
    const float d = hit_px[u].distance * dir[3 * u];
    depth[u] = ((d < far_clip) & (d > lo) & (d < hi)) ? d : kNaN;
  }
}

using ShadeRow = void (*)(const Shading&, int);

// The shade_row for an image format (0 rgb8, 1 bgr8, 2 mono8), with or without depth, noisy or not.
ShadeRow pick_shade_row(int mode, bool depth, bool noisy) {
  if (noisy) return depth ? shade_row<0, true, true> : shade_row<0, false, true>;
  static const ShadeRow rows[3][2] = {{shade_row<0, false, false>, shade_row<0, true, false>},
                                      {shade_row<1, false, false>, shade_row<1, true, false>},
                                      {shade_row<2, false, false>, shade_row<2, true, false>}};
  return rows[mode][depth ? 1 : 0];
}

}  // namespace

void CameraPlugin::post_physics(const StepContext& ctx, const RobotHandle& robot, OutputQueue* out) {
  prepare();
  const int n = w_ * h_;
  const Eigen::Isometry3d pose = robot.link_pose(link_) * sensor_pose_;
  const RayScene& scene = ctx.world->rays();
  const Environment& env = ctx.world->environment();
  auto o = std::make_unique<CameraOut>(proto_);
  const int channels = o->channels();
  const int bytes = o->channel_bytes();
  // the parts someone takes (none known: all): a depth camera makes depth for its depth image or cloud, colour for
  // its image or cloud; a plain camera always its image
  const uint32_t parts = (parts_ & (kCameraImage | kCameraDepth | kCameraCloud)) ? parts_ : ~0u;
  const bool make_depth = o->has_depth && (parts & (kCameraDepth | kCameraCloud));
  const bool make_colour = !make_depth || (parts & (kCameraImage | kCameraCloud));
  if (make_colour) o->image.resize(static_cast<size_t>(n) * channels * bytes);
  if (make_depth) o->depth.resize(n);
  if (make_depth && make_colour) {
    o->points.resize(3 * static_cast<size_t>(n));
    o->point_rgb.resize(3 * static_cast<size_t>(n));
  }
  const Eigen::Vector3f light = (-env.sun_direction).normalized().cast<float>();
  const float ambient = static_cast<float>(env.ambient);
  const Eigen::Vector3f bg = env.background.cast<float>();
  const bool mono = channels == 1;
  const bool bgr = o->encoding == "bgr8";
  const float f = static_cast<float>(o->f), cx = static_cast<float>(o->cx), cy = static_cast<float>(o->cy);
  const float far = static_cast<float>(far_);
  CameraOut& im = *o;
  // each body's material colour
  thread_local std::vector<Eigen::Vector3f> colour;
  colour.resize(scene.body_count());
  for (int b = 0; b < scene.body_count(); ++b) colour[b] = scene.look(b).rgba.head<3>().cast<float>();
  const std::vector<Eigen::Vector3f>& col = colour;
  // per pixel: depth, colour [0, 1], point. Points: x = d (u - cx) / f and y = d (v - cy) / f from factors per
  // column and row.
  thread_local std::vector<float> colf;
  colf.resize(w_);
  for (int u = 0; u < w_; ++u) colf[u] = (u - cx) / f;
  const float* xf = colf.data();
  // raw pointers: byte stores may alias anything, so through the vectors every store would reload them
  uint8_t* const img = make_colour ? im.image.data() : nullptr;
  uint8_t* const prgb = make_depth && make_colour ? im.point_rgb.data() : nullptr;
  float* const dep = make_depth ? im.depth.data() : nullptr;
  float* const pts = make_depth && make_colour ? im.points.data() : nullptr;
  float* const rgbf = rgb_.data();
  const RayHit* const hits = hits_.data();
  const float* const dirs = dirs_.data();
  const Eigen::Vector3f* const colours = col.data();
  const float cut_lo = static_cast<float>(cutoff_), cut_hi = static_cast<float>(cutoff_max_);
  // rows r0..r1 (shade_row): without noise straight to bytes, with noise or 16 bits into rgb_
  const int mode = mono ? 2 : bgr ? 1 : 0;
  const bool floats = gaussian_ || sixteen_;
  // depth and colour in one pass (with the cloud), or either alone
  const ShadeRow shade_one = make_colour ? pick_shade_row(mode, make_depth, floats) : depth_row;
  const Shading sh{hits, dirs, xf, colours, light, bg, ambient, far, cut_lo, cut_hi, f, cy, w_, img, dep, pts, prgb,
                   rgbf};
  auto shade = [shade_one, &sh](int r0, int r1) {
    for (int v = r0; v <= r1; ++v) shade_one(sh, v);
  };
  scene.render(pose.translation(), pose.linear(), pinhole_, dirs_.data(), t_far_, hits_.data(), shade);
  if (gaussian_ && make_colour) {
    std::normal_distribution<double> noise(noise_mean_, noise_stddev_ > 0 ? noise_stddev_ : 1.0);
    for (int i = 0; i < 3 * n; ++i) rgb_[i] = std::clamp(rgb_[i] + static_cast<float>(noise(rng_)), 0.f, 1.f);
  }
  if (floats && make_colour && !sixteen_) {
    for (int i = 0; i < n; ++i)
      put_pixel(mode, pixel_bytes(rgb_[3 * i], rgb_[3 * i + 1], rgb_[3 * i + 2]), img + channels * i,
                prgb ? prgb + 3 * i : nullptr);
  }
  if (sixteen_ && make_colour) {
    // [0, 1] to 0..65535 rounded, little-endian; the cloud's colour stays 8 bits
    auto put16 = [](uint8_t* p, uint16_t x) {
      p[0] = static_cast<uint8_t>(x & 0xff);
      p[1] = static_cast<uint8_t>(x >> 8);
    };
    for (int i = 0; i < n; ++i) {
      const float* c = &rgb_[3 * i];
      const uint16_t r = static_cast<uint16_t>(c[0] * 65535.f + 0.5f), g = static_cast<uint16_t>(c[1] * 65535.f + 0.5f),
                     b = static_cast<uint16_t>(c[2] * 65535.f + 0.5f);
      uint8_t* px = img + 2 * channels * static_cast<size_t>(i);
      if (mono) {
        put16(px, static_cast<uint16_t>(0.299f * r + 0.587f * g + 0.114f * b + 0.5f));
      } else {
        put16(px, r);
        put16(px + 2, g);
        put16(px + 4, b);
      }
      if (prgb) {
        const PixelBytes pb = pixel_bytes(c[0], c[1], c[2]);
        prgb[3 * i] = pb.r, prgb[3 * i + 1] = pb.g, prgb[3 * i + 2] = pb.b;
      }
    }
  }
  if (distorted_ && make_colour) distort(&o->image, channels * bytes, bytes);
  out->push_back(std::move(o));
}

void CameraPlugin::make_lens_map() {
  // OpenCV's plumb_bob model: output pixel q takes the pinhole point p with distort(p) = q, found as
  // cv::undistortPoints does (fixed-point iterations from p = q)
  const double k1 = lens_[0], k2 = lens_[1], k3 = lens_[2], p1 = lens_[3], p2 = lens_[4];
  const double f = proto_.f;
  lens_map_.resize(2 * static_cast<size_t>(w_) * h_);
  for (int v = 0; v < h_; ++v) {
    for (int u = 0; u < w_; ++u) {
      // [1] normalised coordinates of q, then of p
      const double xd = (u - lens_cx_) / f, yd = (v - lens_cy_) / f;
      double x = xd, y = yd;
      for (int it = 0; it < 20; ++it) {
        const double r2 = x * x + y * y;
        const double icdist = 1.0 / (1.0 + ((k3 * r2 + k2) * r2 + k1) * r2);
        const double dx = 2 * p1 * x * y + p2 * (r2 + 2 * x * x);
        const double dy = p1 * (r2 + 2 * y * y) + 2 * p2 * x * y;
        x = (xd - dx) * icdist;
        y = (yd - dy) * icdist;
      }
      // [px] p in the pinhole frame
      const size_t k = static_cast<size_t>(v) * w_ + u;
      lens_map_[2 * k] = x * f + lens_cx_;
      lens_map_[2 * k + 1] = y * f + lens_cy_;
    }
  }
}

void CameraPlugin::distort(FrameBuffer<uint8_t>* image, int pixel_bytes, int channel_bytes) const {
  // each output pixel sampled bilinearly at its pinhole point (lens_map_); black outside the frame
  const FrameBuffer<uint8_t> src = *image;
  const int nc = pixel_bytes / channel_bytes;
  auto at = [&](int u, int v, int ch) -> double {
    const uint8_t* p = &src[(static_cast<size_t>(v) * w_ + u) * pixel_bytes + ch * channel_bytes];
    return channel_bytes == 2 ? static_cast<double>(p[0] | (p[1] << 8)) : static_cast<double>(p[0]);
  };
  const size_t n = static_cast<size_t>(w_) * h_;
  for (size_t k = 0; k < n; ++k) {
    const double pu = lens_map_[2 * k], pv = lens_map_[2 * k + 1];
    uint8_t* out = &(*image)[k * pixel_bytes];
    const int u0 = static_cast<int>(std::floor(pu)), v0 = static_cast<int>(std::floor(pv));
    if (!(u0 >= 0 && v0 >= 0 && u0 + 1 < w_ && v0 + 1 < h_)) {
      std::memset(out, 0, pixel_bytes);
      continue;
    }
    const double a = pu - u0, b = pv - v0;
    for (int ch = 0; ch < nc; ++ch) {
      const double val = (1 - a) * (1 - b) * at(u0, v0, ch) + a * (1 - b) * at(u0 + 1, v0, ch) +
                         (1 - a) * b * at(u0, v0 + 1, ch) + a * b * at(u0 + 1, v0 + 1, ch);
      const long q = std::lround(val);
      if (channel_bytes == 2) {
        out[2 * ch] = static_cast<uint8_t>(q & 0xff);
        out[2 * ch + 1] = static_cast<uint8_t>(q >> 8);
      } else {
        out[ch] = static_cast<uint8_t>(q);
      }
    }
  }
}

void CameraOut::visit(FieldVisitor& v) const {
  v.integer("width", width);
  v.integer("height", height);
  v.number("f", f);
  v.number("cx", cx);
  v.number("cy", cy);
  v.text("encoding", encoding);
  const size_t H = static_cast<size_t>(height), W = static_cast<size_t>(width);
  // the parts this frame has (all of them unless set_parts left some out)
  // 16-bit encodings: a last axis of the channel's two bytes, little-endian
  if (!image.empty() && channel_bytes() == 1) v.array("image", image.data(), {H, W, size_t(channels())});
  if (!image.empty() && channel_bytes() == 2) v.array("image", image.data(), {H, W, size_t(channels()), 2});
  if (!has_depth) return;
  if (!depth.empty()) v.array("depth", depth.data(), {H, W});
  if (!points.empty()) v.array("points", points.data(), {H, W, 3});
  if (!point_rgb.empty()) v.array("point_rgb", point_rgb.data(), {H, W, 3});
}

ImageSample CameraOut::frame_view() const {
  ImageSample s;
  s.width = width;
  s.height = height;
  s.f = f;
  s.cx = cx;
  s.cy = cy;
  s.encoding = encoding;
  s.step = static_cast<uint32_t>(step());
  s.image = image.empty() ? nullptr : image.data();
  s.image_bytes = image.size();
  s.depth = depth.empty() ? nullptr : depth.data();
  s.points = points.empty() ? nullptr : points.data();
  s.point_rgb = point_rgb.empty() ? nullptr : point_rgb.data();
  return s;
}

std::string camera_base(const PluginConfig& c, const std::string& robot, const std::string& sub) {
  std::string base = plugin_robot_namespace(c, robot);
  std::string cam = c.text("cameraName") + sub;
  while (!cam.empty() && cam.front() == '/') cam.erase(cam.begin());
  if (!cam.empty()) base = base.empty() ? cam : base + "/" + cam;
  return base;
}

namespace {

OutputPort image_port(const PluginConfig& c, const std::string& robot, const std::string& base, const char* name,
                      SampleType type, const std::string& topic) {
  OutputPort p;
  p.name = name;
  p.type = type;
  p.ns = plugin_robot_namespace(c, robot);
  p.topic = resolve_topic(base, topic);
  p.queue = 2;
  p.frame = c.text("frameName");
  // camera_utils: frame_name_ = tf::resolve(tf::getPrefixParam(rosnode_), frameName), tf_prefix searched upwards
  p.frame_rule = FrameRule::PrefixSearched;
  return p;
}

// camera_info: D, the baseline, the period
OutputPort info_port(const PluginConfig& c, const std::string& robot, const std::string& base, const char* name,
                     const std::string& topic, size_t frame, double baseline) {
  OutputPort p = image_port(c, robot, base, name, sample_type<CameraInfoSample>(), topic);
  p.image.frame = frame;
  p.image.distortion = {c.number("distortionK1"), c.number("distortionK2"), c.number("distortionT1"),
                        c.number("distortionT2"), c.number("distortionK3")};
  p.image.baseline = baseline;
  p.image.cx = c.number("Cx");
  p.image.cy = c.number("Cy");
  p.image.focal_length = c.number("focalLength");
  const double r = c.number("updateRate");
  p.image.period = r > 0 ? 1.0 / r : 0.0;
  return p;
}

}  // namespace

std::vector<OutputPort> camera_ports(const PluginConfig& c, const std::string& robot, const std::string& sub,
                                     size_t frame, double baseline) {
  const std::string base = camera_base(c, robot, sub);
  OutputPort image = image_port(c, robot, base, "image", sample_type<ImageSample>(), c.text("imageTopicName"));
  image.image.frame = frame;
  return {image, info_port(c, robot, base, "camera_info", c.text("cameraInfoTopicName"), frame, baseline)};
}

void throttle_images(std::vector<OutputPort>* ports) {
  // each image takes its camera_info's period (the port after it)
  for (size_t i = 0; i + 1 < ports->size(); ++i)
    if ((*ports)[i].type == sample_type<ImageSample>() && (*ports)[i + 1].type == sample_type<CameraInfoSample>())
      (*ports)[i].min_period = (*ports)[i + 1].image.period;
}

std::vector<OutputPort> depth_camera_ports(const PluginConfig& c, const std::string& robot) {
  const std::string base = camera_base(c, robot);
  std::vector<OutputPort> ports = camera_ports(c, robot, "", 0, c.number("hackBaseline"));
  ports[0].parts = kCameraImage;
  ports[1].idle_parts = kCameraDepth;
  // the depth camera_info is the colour one's message, sent just before it
  OutputPort depth_info =
      info_port(c, robot, base, "depth_camera_info", c.text("depthImageCameraInfoTopicName"), 0, c.number("hackBaseline"));
  depth_info.idle_parts = kCameraDepth;
  ports.insert(ports.begin() + 1, depth_info);
  OutputPort depth =
      image_port(c, robot, base, "depth", sample_type<DepthImageSample>(), c.text("depthImageTopicName"));
  depth.image.millimetres = c.flag("useDepth16UC1Format");
  depth.parts = kCameraDepth;
  ports.push_back(depth);
  OutputPort cloud =
      image_port(c, robot, base, "points", sample_type<DepthCloudSample>(), c.text("pointCloudTopicName"));
  cloud.parts = kCameraCloud;
  ports.push_back(cloud);
  return ports;
}

PluginKind camera_kind_record() {
  return [] {
    PluginKind k;
    k.name = "camera";
    k.filenames = {"libgazebo_ros_camera.so"};
    k.namespace_rule = NamespaceRule::EmptyIsModel;  // GetRobotNamespace (gazebo_ros_camera_utils.cpp)
    k.model_level = false;
    // CameraPlugin takes any CameraSensor: a depth sensor is one (its colour image)
    k.sensor_types = {"camera", "depth"};
    k.sensor_schema = camera_sensor_schema();
    k.schema = camera_plugin_schema();
    k.schema.push_back({"imageTopicName", T, "image_raw", ""});
    k.schema.push_back({"cameraInfoTopicName", T, "camera_info", ""});
    k.ignored = camera_ignored_keys();
    k.lazy = true;
    k.output_group = "images";
    k.finish = finish_camera;
    k.outputs = [](const PluginConfig& c, const std::string& robot, const Environment&) {
      std::vector<OutputPort> ports = camera_ports(c, robot, "", 0, c.number("hackBaseline"));
      throttle_images(&ports);
      return ports;
    };
    k.make = [](const PluginConfig& c, const std::string& robot, uint64_t seed) -> std::unique_ptr<Plugin> {
      return std::make_unique<CameraPlugin>(c, robot, seed, false);
    };
    return k;
  }();
}

}  // namespace car_sim
