// Ray casting over the world's collision geometry with Embree 3: boxes, planes and meshes as triangles (exact),
// cylinders and spheres as analytic user geometry (exact), every body an instance whose pose is updated before
// a cast, so moving bodies are seen where they are. No ROS headers.
#pragma once

#include <Eigen/Geometry>
#include <functional>
#include <memory>
#include <vector>

#include "car_sim/model.hpp"

namespace car_sim {

// The surface a ray hit.
struct RayHit {
  float distance;        // [m] along the unit ray; +inf when nothing was hit within the range
  Eigen::Vector3f normal;  // unit, world frame, facing the ray
  int body;              // index given by add_body, -1 for none
};

// A pinhole camera for RayScene::render: width x height pixels; the ray of pixel (u, v) (u right, v down, from 0)
// has the sensor-frame (x forward, y left, z up) direction (f, -(u - cx), -(v - cy)), normalised.
struct Pinhole {
  int width = 0, height = 0;
  double f = 0, cx = 0, cy = 0;  // [px]
  double near = 0;               // [m] along the optical axis (sensor x): only hits beyond it are seen
};

// What a body's surfaces look like to sensors.
struct SurfaceLook {
  Eigen::Vector4d rgba = Eigen::Vector4d(0.7, 0.7, 0.7, 1.0);  // material colour
  double laser_retro = 0.0;                                    // intensity a laser reads
};

class RayScene {
 public:
  RayScene();
  ~RayScene();
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  // A rigid body: shapes placed in the body frame (loaded meshes as their triangles). Returns its index.
  int add_body(const std::vector<std::pair<Shape, Eigen::Isometry3d>>& shapes, const SurfaceLook& look);
  // Body frame in the world; takes effect at the next commit().
  void set_pose(int body, const Eigen::Isometry3d& pose);
  // Builds what changed. Call after set_pose and before casting.
  void commit();

  const SurfaceLook& look(int body) const;
  int body_count() const;

  // Casts n rays from one origin: directions are unit vectors in the frame `rotation` maps to the world.
  // Hits between t_near and t_far [m] along each ray (t_near may be per ray: pass n values, or one).
  // Runs on all cores; results do not depend on the thread count.
  void cast(const Eigen::Vector3d& origin, const Eigen::Matrix3d& rotation, const float* directions, int n,
            const float* t_near, bool t_near_per_ray, float t_far, RayHit* out) const;

  // The fast paths for rays that share an origin (car's own kernels; cast() above is Embree's general path).
  // Each gives, per ray, what cast() gives up to float rounding; both are exact (no sampling, no resolution).
  //
  // A pinhole camera: out[v * width + u] is the nearest hit of pixel (u, v)'s ray with depth (distance x its
  // sensor-x) beyond cam.near and distance below t_far. directions: each pixel's unit direction in the sensor
  // frame (as Pinhole says, rounded to float), in the same order. A rasteriser: each triangle is clipped at the
  // near plane and projected, the pixel centres inside it read the exact distance to its plane; cylinders and
  // spheres are tested analytically on the pixels of their projected bound. Rows are shared out among the
  // cores; the output does not depend on the thread count. rows_done(r0, r1), when given, is called on the
  // thread that rendered rows r0..r1 (inclusive) as soon as they are final, bands in any order, so the caller's
  // per-pixel work shares the one parallel region and the rows' cache.
  void render(const Eigen::Vector3d& origin, const Eigen::Matrix3d& rotation, const Pinhole& cam,
              const float* directions, float t_far, RayHit* out,
              const std::function<void(int, int)>& rows_done = {}) const;
  // A planar fan: n rays in the sensor's x-y plane, ray i at angle angle_min + i * increment [rad] (increment > 0,
  // or n = 1) with the given directions (cos, sin, 0); hits in (t_near, t_far) [m]. Each triangle meets the plane
  // in a segment, which is tested against the rays within its angular span only; cylinders and spheres
  // analytically within theirs. One thread.
  void cast_fan(const Eigen::Vector3d& origin, const Eigen::Matrix3d& rotation, const float* directions, int n,
                double angle_min, double increment, float t_near, float t_far, RayHit* out) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace car_sim
