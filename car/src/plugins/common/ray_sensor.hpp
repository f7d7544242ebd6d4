// The ray sensor every ray kind reads (laser, block_laser, velodyne, range, hector_sonar): the sensor's schema as
// SDF 1.6 writes it, its checks, and the grid of rays of a sensor with several rows. Not a kind: shared code.
#pragma once

#include <vector>

#include "car_sim/plugin.hpp"

namespace car_sim {

const std::vector<ParamDef>& ray_sensor_schema();
// Checks the <ray> keys of ray_sensor_schema() (samples, resolution, angles, range, noise).
void finish_ray(ResolveContext& ctx);

// The ray sensor's grid: n_h x n_v rays (samples x resolution per axis), ray (i, j) at index i + j n_h with yaw
// h_i and pitch v_j [rad]; direction (cos v cos h, cos v sin h, sin v) in the sensor frame (up for v > 0). An axis
// of one sample looks straight ahead (0), whatever its min_angle, as Gazebo's MultiRayShape::Init casts it.
class RayGrid {
 public:
  explicit RayGrid(const PluginConfig& c);
  int nh() const { return nh_; }
  int nv() const { return nv_; }
  int size() const { return nh_ * nv_; }
  double yaw(int i) const;    // [rad]
  double pitch(int j) const;  // [rad]
  double yaw_min() const { return hmin_; }    // [rad] <horizontal><min_angle>
  double pitch_min() const { return vmin_; }  // [rad] <vertical><min_angle>
  float range_min() const { return rmin_; }
  float range_max() const { return rmax_; }
  // Casts every ray from the sensor frame (link pose x sensor pose); hits from range.min to range.max, the
  // sensor's own link included (a ray that starts inside a shape reads where it leaves it), as Gazebo 11's ray and
  // GPU ray sensors (docs/COMPAT-sensors.md "A ray sensor and its own body").
  const std::vector<RayHit>& cast(const StepContext& ctx, const Eigen::Isometry3d& sensor_in_world);

 private:
  int nh_ = 1, nv_ = 1;
  double hmin_ = 0, hmax_ = 0, vmin_ = 0, vmax_ = 0;
  float rmin_ = 0, rmax_ = 0;
  std::vector<float> dirs_;
  std::vector<RayHit> hits_;
};

}  // namespace car_sim
