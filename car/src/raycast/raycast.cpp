#include "car_sim/raycast.hpp"

#include <embree3/rtcore.h>

#include "car_sim/parallel.hpp"
#include "scene_impl.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace car_sim {

namespace {

using raycast_detail::Primitive;

void bounds(const RTCBoundsFunctionArguments* args) {
  const Primitive& p = *static_cast<const Primitive*>(args->geometryUserPtr);
  const Eigen::Vector3f h(p.radius, p.radius, p.kind == 1 ? p.half_length : p.radius);
  // box of the rotated extent
  const Eigen::Vector3f e = p.R.cwiseAbs() * h;
  RTCBounds* b = args->bounds_o;
  b->lower_x = p.t.x() - e.x();
  b->lower_y = p.t.y() - e.y();
  b->lower_z = p.t.z() - e.z();
  b->upper_x = p.t.x() + e.x();
  b->upper_y = p.t.y() + e.y();
  b->upper_z = p.t.z() + e.z();
}

using raycast_detail::hit_primitive;

void intersect(const RTCIntersectFunctionNArguments* args) {
  const Primitive& p = *static_cast<const Primitive*>(args->geometryUserPtr);
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
  for (unsigned i = 0; i < args->N; ++i) {
    if (!args->valid[i]) continue;
    // into the primitive frame
    const Eigen::Vector3f ob(RTCRayN_org_x(ray, args->N, i), RTCRayN_org_y(ray, args->N, i),
                             RTCRayN_org_z(ray, args->N, i));
    const Eigen::Vector3f db(RTCRayN_dir_x(ray, args->N, i), RTCRayN_dir_y(ray, args->N, i),
                             RTCRayN_dir_z(ray, args->N, i));
    const Eigen::Vector3f o = p.R.transpose() * (ob - p.t);
    const Eigen::Vector3f d = p.R.transpose() * db;
    float t;
    Eigen::Vector3f n;
    if (!hit_primitive(p, o, d, RTCRayN_tnear(ray, args->N, i), RTCRayN_tfar(ray, args->N, i), &t, &n)) continue;
    const Eigen::Vector3f nb = p.R * n;
    RTCRayN_tfar(ray, args->N, i) = t;
    RTCHitN_Ng_x(hit, args->N, i) = nb.x();
    RTCHitN_Ng_y(hit, args->N, i) = nb.y();
    RTCHitN_Ng_z(hit, args->N, i) = nb.z();
    RTCHitN_u(hit, args->N, i) = 0.f;
    RTCHitN_v(hit, args->N, i) = 0.f;
    RTCHitN_primID(hit, args->N, i) = args->primID;
    RTCHitN_geomID(hit, args->N, i) = args->geomID;
    RTCHitN_instID(hit, args->N, i, 0) = args->context->instID[0];
  }
}

void occluded(const RTCOccludedFunctionNArguments* args) {
  const Primitive& p = *static_cast<const Primitive*>(args->geometryUserPtr);
  RTCRayN* ray = args->ray;
  for (unsigned i = 0; i < args->N; ++i) {
    if (!args->valid[i]) continue;
    const Eigen::Vector3f o = p.R.transpose() * (Eigen::Vector3f(RTCRayN_org_x(ray, args->N, i), RTCRayN_org_y(ray, args->N, i),
                                                                 RTCRayN_org_z(ray, args->N, i)) - p.t);
    const Eigen::Vector3f d = p.R.transpose() * Eigen::Vector3f(RTCRayN_dir_x(ray, args->N, i),
                                                                RTCRayN_dir_y(ray, args->N, i), RTCRayN_dir_z(ray, args->N, i));
    float t;
    Eigen::Vector3f n;
    if (hit_primitive(p, o, d, RTCRayN_tnear(ray, args->N, i), RTCRayN_tfar(ray, args->N, i), &t, &n))
      RTCRayN_tfar(ray, args->N, i) = -std::numeric_limits<float>::infinity();
  }
}

// Box and plane corners as triangles, in the body frame.
void add_triangles(std::vector<Eigen::Vector3f>* v, std::vector<unsigned>* idx, const Shape& s,
                   const Eigen::Isometry3d& T) {
  const unsigned base = static_cast<unsigned>(v->size());
  if (s.type == ShapeType::Box) {
    const Eigen::Vector3d h = s.size / 2.0;
    for (int k = 0; k < 8; ++k)
      v->push_back((T * Eigen::Vector3d((k & 1) ? h.x() : -h.x(), (k & 2) ? h.y() : -h.y(), (k & 4) ? h.z() : -h.z()))
                       .cast<float>());
    static const unsigned faces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                                          {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    for (const auto& f : faces)
      for (unsigned i : f) idx->push_back(base + i);
  } else {
    // a plane through the shape origin with its normal, as a square of the given size (default 100 m)
    const Eigen::Vector3d n = s.normal.normalized();
    const Eigen::Vector3d a = (std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY()).cross(n).normalized();
    const Eigen::Vector3d b = n.cross(a);
    const double hx = (s.size.x() > 0 ? s.size.x() : 100.0) / 2, hy = (s.size.y() > 0 ? s.size.y() : 100.0) / 2;
    const Eigen::Vector3d corners[4] = {-hx * a - hy * b, hx * a - hy * b, hx * a + hy * b, -hx * a + hy * b};
    for (const auto& c : corners) v->push_back((T * c).cast<float>());
    for (unsigned i : {0u, 1u, 2u, 0u, 2u, 3u}) idx->push_back(base + i);
  }
}

}  // namespace

namespace raycast_detail {

bool hit_primitive(const Primitive& p, const Eigen::Vector3f& o, const Eigen::Vector3f& d, float t0, float t1,
                   float* t_out, Eigen::Vector3f* n_out) {
  float best = t1;
  bool found = false;
  auto consider = [&](float t, const Eigen::Vector3f& n) {
    if (t > t0 && t < best) {
      best = t;
      *n_out = n;
      found = true;
    }
  };
  if (p.kind == 0) {
    const float b = o.dot(d), c = o.squaredNorm() - p.radius * p.radius;
    const float disc = b * b - c;
    if (disc < 0) return false;
    const float s = std::sqrt(disc);
    for (float t : {-b - s, -b + s}) consider(t, (o + t * d) / p.radius);
  } else {
    // side: x^2 + y^2 = r^2 with |z| <= h
    const float a = d.x() * d.x() + d.y() * d.y();
    if (a > 0) {
      const float b = o.x() * d.x() + o.y() * d.y();
      const float c = o.x() * o.x() + o.y() * o.y() - p.radius * p.radius;
      const float disc = b * b - a * c;
      if (disc >= 0) {
        const float s = std::sqrt(disc);
        for (float t : {(-b - s) / a, (-b + s) / a}) {
          const Eigen::Vector3f q = o + t * d;
          if (std::abs(q.z()) <= p.half_length) consider(t, Eigen::Vector3f(q.x(), q.y(), 0) / p.radius);
        }
      }
    }
    // caps: z = +-h with x^2 + y^2 <= r^2
    if (d.z() != 0) {
      for (float zc : {-p.half_length, p.half_length}) {
        const float t = (zc - o.z()) / d.z();
        const Eigen::Vector3f q = o + t * d;
        if (q.x() * q.x() + q.y() * q.y() <= p.radius * p.radius) consider(t, Eigen::Vector3f(0, 0, zc > 0 ? 1.f : -1.f));
      }
    }
  }
  if (found) *t_out = best;
  return found;
}

}  // namespace raycast_detail

RayScene::RayScene() : impl_(std::make_unique<Impl>()) {
  impl_->device = rtcNewDevice("threads=1");
  if (!impl_->device) throw std::runtime_error("Embree: cannot create a device");
  impl_->top = rtcNewScene(impl_->device);
  rtcSetSceneFlags(impl_->top, RTC_SCENE_FLAG_DYNAMIC);
  rtcSetSceneBuildQuality(impl_->top, RTC_BUILD_QUALITY_LOW);
}

RayScene::~RayScene() {
  for (auto& b : impl_->bodies) rtcReleaseScene(b.scene);
  rtcReleaseScene(impl_->top);
  rtcReleaseDevice(impl_->device);
}

int RayScene::add_body(const std::vector<std::pair<Shape, Eigen::Isometry3d>>& shapes, const SurfaceLook& look) {
  Impl::Body b;
  b.look = look;
  b.scene = rtcNewScene(impl_->device);
  std::vector<Eigen::Vector3f> verts;
  std::vector<unsigned> idx;
  for (const auto& [s, T] : shapes) {
    if (s.type == ShapeType::Mesh && s.mesh) {
      // a mesh's exact triangles, scaled, in the body frame
      const unsigned base = static_cast<unsigned>(verts.size());
      for (const auto& v : s.mesh->vertices)
        verts.push_back((T * Eigen::Vector3d(v.cast<double>().cwiseProduct(s.mesh_scale))).cast<float>());
      for (uint32_t i : s.mesh->indices) idx.push_back(base + i);
    } else if (s.type == ShapeType::Box || s.type == ShapeType::Plane) {
      add_triangles(&verts, &idx, s, T);
    } else if (s.type == ShapeType::Sphere || s.type == ShapeType::Cylinder) {
      auto p = std::make_unique<Primitive>();
      p->kind = s.type == ShapeType::Sphere ? 0 : 1;
      p->radius = static_cast<float>(s.radius);
      p->half_length = static_cast<float>(s.length / 2.0);
      p->R = T.linear().cast<float>();
      p->t = T.translation().cast<float>();
      RTCGeometry g = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_USER);
      rtcSetGeometryUserPrimitiveCount(g, 1);
      rtcSetGeometryUserData(g, p.get());
      rtcSetGeometryBoundsFunction(g, bounds, nullptr);
      rtcSetGeometryIntersectFunction(g, intersect);
      rtcSetGeometryOccludedFunction(g, occluded);
      rtcCommitGeometry(g);
      rtcAttachGeometry(b.scene, g);
      rtcReleaseGeometry(g);
      b.prims.push_back(p.get());
      impl_->primitives.push_back(std::move(p));
    }
  }
  if (!idx.empty()) {
    RTCGeometry g = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), verts.size()));
    for (size_t i = 0; i < verts.size(); ++i)
      for (int k = 0; k < 3; ++k) vb[3 * i + k] = verts[i][k];
    auto* ib = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), idx.size() / 3));
    std::copy(idx.begin(), idx.end(), ib);
    rtcCommitGeometry(g);
    rtcAttachGeometry(b.scene, g);
    rtcReleaseGeometry(g);
  }
  rtcCommitScene(b.scene);
  // the coherent kernels' copy, and the bounding sphere about the centre of the geometry's box
  Eigen::AlignedBox3f box;
  for (const auto& v : verts) box.extend(v);
  for (const auto* p : b.prims) {
    box.extend(p->t - Eigen::Vector3f::Constant(p->bound()));
    box.extend(p->t + Eigen::Vector3f::Constant(p->bound()));
  }
  if (!box.isEmpty()) {
    b.centre = box.center();
    for (const auto& v : verts) b.radius = std::max(b.radius, (v - b.centre).norm());
    for (const auto* p : b.prims) b.radius = std::max(b.radius, (p->t - b.centre).norm() + p->bound());
    b.radius *= 1.0001f;  // [m], rounding margin
  }
  b.verts = std::move(verts);
  b.idx = std::move(idx);
  b.instance = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_INSTANCE);
  rtcSetGeometryInstancedScene(b.instance, b.scene);
  b.inst_id = rtcAttachGeometry(impl_->top, b.instance);
  rtcReleaseGeometry(b.instance);
  const int index = static_cast<int>(impl_->bodies.size());
  if (impl_->body_of_instance.size() <= b.inst_id) impl_->body_of_instance.resize(b.inst_id + 1, -1);
  impl_->body_of_instance[b.inst_id] = index;
  impl_->bodies.push_back(b);
  set_pose(index, Eigen::Isometry3d::Identity());
  return index;
}

void RayScene::set_pose(int body, const Eigen::Isometry3d& pose) {
  Impl::Body& b = impl_->bodies.at(body);
  float xfm[12];  // 3x4 column major
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) xfm[c * 3 + r] = static_cast<float>(pose.linear()(r, c));
  for (int r = 0; r < 3; ++r) xfm[9 + r] = static_cast<float>(pose.translation()(r));
  rtcSetGeometryTransform(b.instance, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
  b.rotation = pose.linear().cast<float>();
  b.pose = pose;
  b.dirty = true;
  impl_->top_dirty = true;
}

void RayScene::commit() {
  if (!impl_->top_dirty) return;
  for (auto& b : impl_->bodies) {
    if (!b.dirty) continue;
    rtcCommitGeometry(b.instance);
    b.dirty = false;
  }
  rtcCommitScene(impl_->top);
  impl_->top_dirty = false;
}

const SurfaceLook& RayScene::look(int body) const { return impl_->bodies.at(body).look; }
int RayScene::body_count() const { return static_cast<int>(impl_->bodies.size()); }

void RayScene::cast(const Eigen::Vector3d& origin, const Eigen::Matrix3d& rotation, const float* directions, int n,
                    const float* t_near, bool t_near_per_ray, float t_far, RayHit* out) const {
  const float ox = static_cast<float>(origin.x()), oy = static_cast<float>(origin.y()), oz = static_cast<float>(origin.z());
  float R[9];  // row-major
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) R[3 * r + c] = static_cast<float>(rotation(r, c));
  const int packets = (n + 15) / 16;
  const float inf = std::numeric_limits<float>::infinity();
  const Impl& im = *impl_;
  // Threads only for camera-sized batches (a 360-ray scan is cheaper than handing it out); chunks of 64 packets
  // claimed as threads come free (car's pool, parallel.hpp: a thread the OS runs late is not waited for).
  // Each ray's result depends only on that ray: the output is the same for any thread count.
  constexpr int kChunk = 64;
  auto chunk = [&](int ci) {
    for (int p = ci * kChunk; p < std::min(packets, (ci + 1) * kChunk); ++p) {
      alignas(64) RTCRayHit16 rh;
      alignas(64) int valid[16];
      RTCIntersectContext ctx;
      rtcInitIntersectContext(&ctx);
      const int base = p * 16;
      const int count = std::min(16, n - base);
      for (int k = 0; k < 16; ++k) {
        const int j = base + (k < count ? k : count - 1);
        const float* d = directions + 3 * j;
        valid[k] = k < count ? -1 : 0;
        rh.ray.org_x[k] = ox;
        rh.ray.org_y[k] = oy;
        rh.ray.org_z[k] = oz;
        rh.ray.dir_x[k] = R[0] * d[0] + R[1] * d[1] + R[2] * d[2];
        rh.ray.dir_y[k] = R[3] * d[0] + R[4] * d[1] + R[5] * d[2];
        rh.ray.dir_z[k] = R[6] * d[0] + R[7] * d[1] + R[8] * d[2];
        rh.ray.tnear[k] = t_near_per_ray ? t_near[j] : t_near[0];
        rh.ray.tfar[k] = t_far;
        rh.ray.mask[k] = 0xFFFFFFFF;
        rh.ray.flags[k] = 0;
        rh.ray.time[k] = 0.f;
        rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
      }
      rtcIntersect16(valid, im.top, &ctx, &rh);
      for (int k = 0; k < count; ++k) {
        RayHit& h = out[base + k];
        if (rh.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID) {
          h.distance = inf;
          h.normal.setZero();
          h.body = -1;
          continue;
        }
        h.distance = rh.ray.tfar[k];
        const int body = im.body_of_instance[rh.hit.instID[0][k]];
        h.body = body;
        // the hit normal is in the instance's frame: into the world, unit, facing the ray
        const Eigen::Matrix3f& B = im.bodies[body].rotation;
        const float nx = rh.hit.Ng_x[k], ny = rh.hit.Ng_y[k], nz = rh.hit.Ng_z[k];
        float wx = B(0, 0) * nx + B(0, 1) * ny + B(0, 2) * nz;
        float wy = B(1, 0) * nx + B(1, 1) * ny + B(1, 2) * nz;
        float wz = B(2, 0) * nx + B(2, 1) * ny + B(2, 2) * nz;
        float s = 1.f / std::sqrt(wx * wx + wy * wy + wz * wz);
        if (wx * rh.ray.dir_x[k] + wy * rh.ray.dir_y[k] + wz * rh.ray.dir_z[k] > 0) s = -s;
        h.normal = Eigen::Vector3f(wx * s, wy * s, wz * s);
      }
    }
  };
  const int chunks = (packets + kChunk - 1) / kChunk;
  if (packets >= 256) {
    parallel_for(chunks, chunk);
  } else {
    for (int ci = 0; ci < chunks; ++ci) chunk(ci);
  }
}

}  // namespace car_sim
