#include "drive.hpp"

#include <algorithm>
#include <cmath>

namespace car_sim {

void wheel_speeds(double v, double w, double separation, double* left, double* right) {
  *left = v - w * separation / 2.0;
  *right = v + w * separation / 2.0;
}

void WheelRamp::update(const double target[2], const double current[2], double accel, double since,
                       double out[2]) {
  if (accel == 0.0 || std::fabs(target[0] - current[0]) < 0.01 || std::fabs(target[1] - current[1]) < 0.01) {
    out[0] = target[0];
    out[1] = target[1];
    return;
  }
  // [m/s] the most an update may add
  const double step = accel * since;
  for (int side = 0; side < 2; ++side) {
    instr[side] += std::clamp(target[side] - current[side], -step, step);
    out[side] = instr[side];
  }
}

void check_wheel_length(ResolveContext& ctx, const char* key) {
  const double v = ctx.config().number(key);
  if (v == 0.0) ctx.fail(key, "must not be 0 (the drive divides by it)");
  if (v < 0.0)
    ctx.warn(Severity::Warning, "wheel-negative", key,
             "is negative (" + ctx.config().text(key) + " m): the wheels turn the other way, as in Gazebo 11");
}

void EncoderOdometry::integrate(double sl, double sr, double separation, double dt) {
  const double ssum = sl + sr;
  const double sdiff = sr - sl;
  // midpoint heading over the step (Siegwart, Autonomous Mobile Robots, 2011, p. 337)
  const double heading = theta + sdiff / (2.0 * separation);
  x += ssum / 2.0 * std::cos(heading);
  y += ssum / 2.0 * std::sin(heading);
  theta += sdiff / separation;
  if (dt > 0.0) {
    v = ssum / 2.0 / dt;
    w = sdiff / separation / dt;
  }
}

}  // namespace car_sim
