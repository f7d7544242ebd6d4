#include "car_sim/sensors.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace car_sim {

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// FNV-1a: a fixed hash, so a sensor's noise does not depend on the standard library's std::hash.
uint64_t fnv1a(const std::string& s) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

// ---- libgazebo_ros_laser.so on a ray sensor -------------------------------------------------------------

class Lidar : public Sensor {
 public:
  Lidar(const PluginConfig& c, const std::string& robot) {
    out_.robot = robot;
    out_.sensor = c.sensor;
    out_.plugin = c.name;
    const int n = static_cast<int>(c.number("ray/scan/horizontal/samples") * c.number("ray/scan/horizontal/resolution"));
    const double a = c.number("ray/scan/horizontal/min_angle"), b = c.number("ray/scan/horizontal/max_angle");
    out_.angle_min = static_cast<float>(a);
    out_.angle_max = static_cast<float>(b);
    out_.angle_increment = n > 1 ? static_cast<float>((b - a) / (n - 1)) : 0.f;
    out_.range_min = static_cast<float>(c.number("ray/range/min"));
    out_.range_max = static_cast<float>(c.number("ray/range/max"));
    gaussian_ = c.text("ray/noise/type") == "gaussian";
    mean_ = c.number("ray/noise/mean");
    stddev_ = c.number("ray/noise/stddev");
    // ray i at a + i (b - a) / (n - 1), in the sensor's x-y plane
    dirs_.resize(3 * static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
      const double th = n > 1 ? a + i * (b - a) / (n - 1) : a;
      dirs_[3 * i] = static_cast<float>(std::cos(th));
      dirs_[3 * i + 1] = static_cast<float>(std::sin(th));
      dirs_[3 * i + 2] = 0.f;
    }
    hits_.resize(n);
    out_.ranges.resize(n);
    out_.intensities.resize(n);
  }

  void update(const SensorInput& in, std::mt19937_64& rng, SensorOutputs* out) override {
    const int n = static_cast<int>(hits_.size());
    const float t_near = out_.range_min;
    in.scene->cast(in.pose.translation(), in.pose.linear(), dirs_.data(), n, &t_near, false, out_.range_max,
                   hits_.data());
    std::normal_distribution<double> noise(mean_, stddev_ > 0 ? stddev_ : 1.0);
    for (int i = 0; i < n; ++i) {
      const RayHit& h = hits_[i];
      if (!std::isfinite(h.distance)) {
        out_.ranges[i] = kInf;  // REP 117: no hit within range_max
        out_.intensities[i] = 0.f;
        continue;
      }
      double r = h.distance;
      // noise on in-range readings only, then clamped to [min, max]
      if (gaussian_ && stddev_ > 0) r = std::clamp(r + noise(rng), double(out_.range_min), double(out_.range_max));
      else if (gaussian_) r = std::clamp(r + mean_, double(out_.range_min), double(out_.range_max));
      out_.ranges[i] = static_cast<float>(r);
      out_.intensities[i] = static_cast<float>(in.scene->look(h.body).laser_retro);
    }
    out_.tick = in.tick;
    out->scans.push_back(out_);
  }

 private:
  LaserScanOut out_;
  bool gaussian_ = false;
  double mean_ = 0, stddev_ = 0;
  std::vector<float> dirs_;
  std::vector<RayHit> hits_;
};

// ---- libgazebo_ros_openni_kinect.so (depth) and libgazebo_ros_camera.so (camera) ------------------------

class Camera : public Sensor {
 public:
  Camera(const PluginConfig& c, const std::string& robot, bool depth) {
    out_.robot = robot;
    out_.sensor = c.sensor;
    out_.plugin = c.name;
    w_ = static_cast<int>(c.number("camera/image/width"));
    h_ = static_cast<int>(c.number("camera/image/height"));
    out_.width = w_;
    out_.height = h_;
    const double hfov = c.number("camera/horizontal_fov");
    out_.f = w_ / (2.0 * std::tan(hfov / 2.0));
    out_.cx = (w_ - 1) / 2.0;
    out_.cy = (h_ - 1) / 2.0;
    near_ = c.number("camera/clip/near");
    far_ = c.number("camera/clip/far");
    const std::string fmt = c.text("camera/image/format");
    out_.encoding = fmt == "L8" ? "mono8" : (fmt == "B8G8R8" || fmt == "BGR_INT8") ? "bgr8" : "rgb8";
    out_.has_depth = depth;
    if (depth) {
      cutoff_ = c.number("pointCloudCutoff");
      cutoff_max_ = c.number("pointCloudCutoffMax");
    }
    gaussian_ = c.text("camera/noise/type") == "gaussian";
    noise_mean_ = c.number("camera/noise/mean");
    noise_stddev_ = c.number("camera/noise/stddev");
    // one ray per pixel through its centre; sensor frame x forward, y left, z up
    const size_t n = static_cast<size_t>(w_) * h_;
    dirs_.resize(3 * n);
    cos_.resize(n);
    t_near_.resize(n);
    double min_cos = 1.0;
    for (int v = 0; v < h_; ++v) {
      for (int u = 0; u < w_; ++u) {
        const size_t i = static_cast<size_t>(v) * w_ + u;
        const Eigen::Vector3d d = Eigen::Vector3d(out_.f, -(u - out_.cx), -(v - out_.cy)).normalized();
        dirs_[3 * i] = static_cast<float>(d.x());
        dirs_[3 * i + 1] = static_cast<float>(d.y());
        dirs_[3 * i + 2] = static_cast<float>(d.z());
        cos_[i] = static_cast<float>(d.x());
        t_near_[i] = static_cast<float>(near_ / d.x());  // the near clip plane, along this ray
        min_cos = std::min(min_cos, d.x());
      }
    }
    t_far_ = static_cast<float>(far_ / min_cos);
    hits_.resize(n);
    rgb_.resize(3 * n);
    const int channels = out_.encoding == "mono8" ? 1 : 3;
    out_.image.resize(n * channels);
    if (depth) {
      out_.depth.resize(n);
      out_.points.resize(3 * n);
      out_.point_rgb.resize(3 * n);
    }
  }

  void update(const SensorInput& in, std::mt19937_64& rng, SensorOutputs* out) override {
    const int n = w_ * h_;
    in.scene->cast(in.pose.translation(), in.pose.linear(), dirs_.data(), n, t_near_.data(), true, t_far_, hits_.data());
    const Eigen::Vector3f light = (-in.sun_direction).normalized().cast<float>();
    const float ambient = static_cast<float>(in.ambient);
    const Eigen::Vector3f bg = in.background.cast<float>();
    const bool mono = out_.encoding == "mono8";
    const bool bgr = out_.encoding == "bgr8";
    const float f = static_cast<float>(out_.f), cx = static_cast<float>(out_.cx), cy = static_cast<float>(out_.cy);
    const float far = static_cast<float>(far_);
    // per pixel: depth, colour, point; independent pixels, so in parallel (noise, when configured, after)
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i) {
      const RayHit& h = hits_[i];
      // depth along the optical axis; beyond the far clip is no hit
      float d = std::isfinite(h.distance) ? h.distance * cos_[i] : kInf;
      if (d >= far) d = kInf;
      // colour: the material lit by the ambient and the directional light (Lambert), else the background
      Eigen::Vector3f rgb = bg;
      if (std::isfinite(d)) {
        const Eigen::Vector4d& m = in.scene->look(h.body).rgba;
        const float lit = std::min(1.f, ambient + 0.8f * std::max(0.f, h.normal.dot(light)));
        rgb = (m.head<3>().cast<float>() * lit).cwiseMin(1.f);
      }
      rgb_[3 * i] = rgb.x();
      rgb_[3 * i + 1] = rgb.y();
      rgb_[3 * i + 2] = rgb.z();
      if (!out_.has_depth) continue;
      const bool valid = std::isfinite(d) && d > cutoff_ && d < cutoff_max_;
      const float dv = valid ? d : kNaN;
      out_.depth[i] = dv;
      const int u = i % w_, v = i / w_;
      out_.points[3 * i] = dv * (u - cx) / f;
      out_.points[3 * i + 1] = dv * (v - cy) / f;
      out_.points[3 * i + 2] = dv;
    }
    if (gaussian_) {
      std::normal_distribution<double> noise(noise_mean_, noise_stddev_ > 0 ? noise_stddev_ : 1.0);
      for (int i = 0; i < 3 * n; ++i) rgb_[i] = std::clamp(rgb_[i] + static_cast<float>(noise(rng)), 0.f, 1.f);
    }
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i) {
      // [0, 1] to 0..255, rounded
      const uint8_t r = static_cast<uint8_t>(rgb_[3 * i] * 255.f + 0.5f);
      const uint8_t g = static_cast<uint8_t>(rgb_[3 * i + 1] * 255.f + 0.5f);
      const uint8_t b = static_cast<uint8_t>(rgb_[3 * i + 2] * 255.f + 0.5f);
      if (mono) {
        out_.image[i] = static_cast<uint8_t>(0.299f * r + 0.587f * g + 0.114f * b + 0.5f);
      } else {
        // fix: channel order follows the image format (upstream swaps R and B for R8G8B8)
        out_.image[3 * i] = bgr ? b : r;
        out_.image[3 * i + 1] = g;
        out_.image[3 * i + 2] = bgr ? r : b;
      }
      if (out_.has_depth) {
        out_.point_rgb[3 * i] = r;
        out_.point_rgb[3 * i + 1] = g;
        out_.point_rgb[3 * i + 2] = b;
      }
    }
    out_.tick = in.tick;
    out->images.push_back(out_);
  }

 private:
  CameraOut out_;
  int w_ = 0, h_ = 0;
  double near_ = 0.1, far_ = 100.0, cutoff_ = 0.0, cutoff_max_ = 0.0;
  bool gaussian_ = false;
  double noise_mean_ = 0, noise_stddev_ = 0;
  std::vector<float> dirs_, cos_, t_near_;
  std::vector<float> rgb_;  // [0, 1] per channel, before rounding
  float t_far_ = 0;
  std::vector<RayHit> hits_;
};

// ---- libgazebo_ros_imu(_sensor).so ------------------------------------------------------------------------

class Imu : public Sensor {
 public:
  Imu(const PluginConfig& c, const std::string& robot) {
    out_.robot = robot;
    out_.sensor = c.sensor.empty() ? c.name : c.sensor;
    out_.plugin = c.name;
    stddev_ = c.number("gaussianNoise");
  }
  bool needs_rays() const override { return false; }
  bool needs_history() const override { return true; }

  void update(const SensorInput& in, std::mt19937_64& rng, SensorOutputs* out) override {
    const Eigen::Isometry3d* p = in.history;  // p[0] oldest, p[2] now
    const double dt = in.dt;
    const Eigen::Matrix3d Rt = p[2].linear().transpose();
    // angular velocity from the last rotation step, in the sensor frame
    const Eigen::AngleAxisd step(p[1].linear().transpose() * p[2].linear());
    Eigen::Vector3d w = step.axis() * step.angle() / dt;
    // acceleration from the last two velocities, minus gravity: at rest it reads +g up
    const Eigen::Vector3d v1 = (p[1].translation() - p[0].translation()) / dt;
    const Eigen::Vector3d v2 = (p[2].translation() - p[1].translation()) / dt;
    Eigen::Vector3d a = Rt * ((v2 - v1) / dt - in.gravity);
    if (stddev_ > 0) {
      std::normal_distribution<double> noise(0.0, stddev_);
      for (int k = 0; k < 3; ++k) w[k] += noise(rng);
      for (int k = 0; k < 3; ++k) a[k] += noise(rng);
    }
    out_.tick = in.tick;
    out_.orientation = Eigen::Quaterniond(p[2].linear());
    out_.angular_velocity = w;
    out_.linear_acceleration = a;
    out->imus.push_back(out_);
  }

 private:
  ImuOut out_;
  double stddev_ = 0.0;
};

}  // namespace

std::unique_ptr<Sensor> make_sensor(const PluginConfig& c, const std::string& robot) {
  if (c.kind == "laser") return std::make_unique<Lidar>(c, robot);
  if (c.kind == "openni_kinect") return std::make_unique<Camera>(c, robot, true);
  if (c.kind == "camera") return std::make_unique<Camera>(c, robot, false);
  if (c.kind == "imu") return std::make_unique<Imu>(c, robot);
  return nullptr;
}

std::mt19937_64 sensor_rng(uint64_t seed, const std::string& robot, const std::string& sensor) {
  const uint64_t h = fnv1a(robot + "/" + sensor);
  std::seed_seq seq{static_cast<uint32_t>(seed), static_cast<uint32_t>(seed >> 32), static_cast<uint32_t>(h),
                    static_cast<uint32_t>(h >> 32)};
  return std::mt19937_64(seq);
}

}  // namespace car_sim
