// Ray casting over the world's collision geometry with Embree 3: boxes, planes and meshes as triangles (exact),
// cylinders and spheres as analytic user geometry (exact), every body an instance whose pose is updated before
// a cast, so moving bodies are seen where they are. No ROS headers.
#pragma once

#include <Eigen/Geometry>
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

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace car_sim
