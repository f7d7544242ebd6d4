// RayScene's private state, shared by the Embree path (raycast.cpp) and car's coherent kernels (coherent.cpp):
// the Embree scenes, and each body's own copy of its geometry (body frame) for the kernels.
#pragma once

#include <embree3/rtcore.h>

#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "car_sim/raycast.hpp"

namespace car_sim {
namespace raycast_detail {

// An analytic primitive, in its own frame (cylinder axis z).
struct Primitive {
  int kind;           // 0 sphere, 1 cylinder
  float radius;       // [m]
  float half_length;  // [m], cylinder
  Eigen::Matrix3f R;  // primitive frame in the body frame
  Eigen::Vector3f t;  // [m], body frame
  // [m] radius of the primitive's bounding sphere about t
  float bound() const { return kind == 1 ? std::sqrt(radius * radius + half_length * half_length) : radius; }
};

// Nearest t in (t0, t1) where the ray (primitive frame, unit d) enters the primitive, with the outward normal
// (primitive frame). False when it does not.
bool hit_primitive(const Primitive& p, const Eigen::Vector3f& o, const Eigen::Vector3f& d, float t0, float t1,
                   float* t_out, Eigen::Vector3f* n_out);

}  // namespace raycast_detail

struct RayScene::Impl {
  RTCDevice device = nullptr;
  RTCScene top = nullptr;
  struct Body {
    RTCScene scene = nullptr;
    RTCGeometry instance = nullptr;
    unsigned inst_id = 0;
    SurfaceLook look;
    Eigen::Matrix3f rotation = Eigen::Matrix3f::Identity();  // body in world, for normals
    bool dirty = true;
    // For the coherent kernels: the body's triangles and primitives in the body frame, its bounding sphere
    // ([m], body frame) and its pose in the world.
    std::vector<Eigen::Vector3f> verts;
    std::vector<unsigned> idx;  // 3 per triangle
    std::vector<const raycast_detail::Primitive*> prims;
    Eigen::Vector3f centre = Eigen::Vector3f::Zero();
    float radius = 0.f;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  };
  std::vector<Body> bodies;
  std::vector<std::unique_ptr<raycast_detail::Primitive>> primitives;
  std::vector<int> body_of_instance;
  bool top_dirty = true;
};

}  // namespace car_sim
