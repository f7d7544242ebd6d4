#include "ray_sensor.hpp"

#include <algorithm>
#include <cmath>

namespace car_sim {

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType N = ParamType::Number;
constexpr ParamType I = ParamType::Integer;

}  // namespace

void finish_ray(ResolveContext& ctx) {
  const PluginConfig& c = ctx.config();
  for (const char* axis : {"horizontal", "vertical"}) {
    const std::string k = std::string("ray/scan/") + axis + "/";
    if (c.number(k + "samples") < 1) ctx.fail_sensor(k + "samples", "samples must be >= 1");
    if (!(c.number(k + "resolution") > 0)) ctx.fail_sensor(k + "resolution", "resolution must be > 0");
    if (c.number(k + "min_angle") > c.number(k + "max_angle"))
      ctx.fail_sensor(k + "min_angle",
                      "min_angle " + c.text(k + "min_angle") + " > max_angle " + c.text(k + "max_angle"));
  }
  if (c.number("ray/range/min") < 0) ctx.fail_sensor("ray/range/min", "min must be >= 0");
  if (c.number("ray/range/min") >= c.number("ray/range/max"))
    ctx.fail_sensor("ray/range/min", "min " + c.text("ray/range/min") + " >= max " + c.text("ray/range/max"));
  const std::string& nt = c.text("ray/noise/type");
  if (nt != "none" && nt != "gaussian") ctx.fail_sensor("ray/noise/type", "unknown noise type '" + nt + "'");
  if (c.number("ray/noise/stddev") < 0) ctx.fail_sensor("ray/noise/stddev", "stddev must be >= 0");
}

const std::vector<ParamDef>& ray_sensor_schema() {
  // SDF 1.6 defaults; samples and rays within the sensor limits, checked where the description is read
  // (validate.hpp check_sensor_limits)
  static const std::vector<ParamDef> s = {
      {"update_rate", N, "0", "Hz"},
      {"ray/scan/horizontal/samples", I, "640", ""},
      {"ray/scan/horizontal/resolution", N, "1", ""},
      {"ray/scan/horizontal/min_angle", N, "0", "rad"},
      {"ray/scan/horizontal/max_angle", N, "0", "rad"},
      {"ray/scan/vertical/samples", I, "1", ""},
      {"ray/scan/vertical/resolution", N, "1", ""},
      {"ray/scan/vertical/min_angle", N, "0", "rad"},
      {"ray/scan/vertical/max_angle", N, "0", "rad"},
      {"ray/range/min", N, "0", "m"},
      {"ray/range/max", N, "0", "m"},
      {"ray/range/resolution", N, "0", "m"},
      {"ray/noise/type", T, "none", ""},
      {"ray/noise/mean", N, "0", "m"},
      {"ray/noise/stddev", N, "0", "m"},
  };
  return s;
}

RayGrid::RayGrid(const PluginConfig& c) {
  nh_ = std::max(1, static_cast<int>(c.number("ray/scan/horizontal/samples") * c.number("ray/scan/horizontal/resolution")));
  nv_ = std::max(1, static_cast<int>(c.number("ray/scan/vertical/samples") * c.number("ray/scan/vertical/resolution")));
  hmin_ = c.number("ray/scan/horizontal/min_angle");
  hmax_ = c.number("ray/scan/horizontal/max_angle");
  vmin_ = c.number("ray/scan/vertical/min_angle");
  vmax_ = c.number("ray/scan/vertical/max_angle");
  rmin_ = static_cast<float>(c.number("ray/range/min"));
  rmax_ = static_cast<float>(c.number("ray/range/max"));
  dirs_.resize(3 * static_cast<size_t>(size()));
  for (int j = 0; j < nv_; ++j) {
    const double v = pitch(j);
    for (int i = 0; i < nh_; ++i) {
      const double h = yaw(i);
      float* d = &dirs_[3 * (static_cast<size_t>(j) * nh_ + i)];
      d[0] = static_cast<float>(std::cos(v) * std::cos(h));
      d[1] = static_cast<float>(std::cos(v) * std::sin(h));
      d[2] = static_cast<float>(std::sin(v));
    }
  }
  hits_.resize(size());
}

double RayGrid::yaw(int i) const { return nh_ > 1 ? hmin_ + i * (hmax_ - hmin_) / (nh_ - 1) : 0.0; }
double RayGrid::pitch(int j) const { return nv_ > 1 ? vmin_ + j * (vmax_ - vmin_) / (nv_ - 1) : 0.0; }

const std::vector<RayHit>& RayGrid::cast(const StepContext& ctx, const Eigen::Isometry3d& pose) {
  // one row in the sensor's x-y plane is a planar fan (car's kernel); other grids go through Embree
  if (nv_ == 1 && pitch(0) == 0.0)
    ctx.world->rays().cast_fan(pose.translation(), pose.linear(), dirs_.data(), size(), yaw(0),
                               nh_ > 1 ? (hmax_ - hmin_) / (nh_ - 1) : 0.0, rmin_, rmax_, hits_.data());
  else
    ctx.world->rays().cast(pose.translation(), pose.linear(), dirs_.data(), size(), &rmin_, false, rmax_,
                           hits_.data());
  return hits_;
}

}  // namespace car_sim
