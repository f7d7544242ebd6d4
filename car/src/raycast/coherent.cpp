// Car's ray kernels for rays that share an origin: a rasteriser for pinhole cameras and a segment sweep for planar
// fans (lidars). Embree (raycast.cpp) traverses its BVH once per ray; these visit each triangle once per cast and
// touch only the rays it covers. Rules in docs/COMPAT-sensors.md "Ray kernels".
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "car_sim/parallel.hpp"
#include "car_sim/raycast.hpp"
#include "scene_impl.hpp"

namespace car_sim {

using raycast_detail::hit_primitive;
using raycast_detail::Primitive;

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr double kTwoPi = 2.0 * M_PI;

// A body's frame seen from the sensor: p_sensor = M p_body + t.
struct Xform {
  Eigen::Matrix3f M;
  Eigen::Vector3f t;
};

Xform sensor_from_body(const Eigen::Isometry3d& body, const Eigen::Vector3d& origin, const Eigen::Matrix3d& R) {
  return {(R.transpose() * body.linear()).cast<float>(), (R.transpose() * (body.translation() - origin)).cast<float>()};
}

// The body's vertices in the sensor frame, into a per-thread buffer.
const std::vector<Eigen::Vector3f>& sensor_vertices(const std::vector<Eigen::Vector3f>& verts, const Xform& X) {
  thread_local std::vector<Eigen::Vector3f> ps;
  ps.resize(verts.size());
  for (size_t i = 0; i < verts.size(); ++i) ps[i] = X.M * verts[i] + X.t;
  return ps;
}

// A triangle clipped at the near plane and projected into the image.
struct Poly {
  double u[4], v[4];   // [px] vertices in order
  int count;           // 3 or 4
  Eigen::Vector3f ns;  // plane normal, sensor frame (any length)
  float h;             // ns . p for points p on the plane
  Eigen::Vector3f nw;  // unit normal, world frame, facing the sensor (the side a ray from the origin meets)
  int body;
  int row0, row1;      // image rows its pixel centres can lie on
};

// A cylinder or sphere and the image rectangle of its bound.
struct PrimView {
  const Primitive* p;
  Eigen::Matrix3f Q;  // primitive frame into the sensor frame
  Eigen::Vector3f o;  // the sensor origin in the primitive frame
  float nearest;      // [m] no point of it is nearer to the sensor
  int body;
  double u[20], v[20];  // [px] the convex hull of its box's image (cut at the near plane), in order
  int count;
  int row0, row1;
};

// A primitive placed in the sensor frame: its centre q [m], its frame's rotation Q into the sensor frame, the
// sensor origin o [m] in its frame, and nearest [m]: no point of it is nearer to the sensor (a millionth short,
// so that rounding never puts a hit before it). Shared by the camera's and the fan's candidate lists.
struct Placed {
  Eigen::Vector3f q;
  Eigen::Matrix3f Q;
  Eigen::Vector3f o;
  float nearest;
};

Placed place(const Primitive& p, const Xform& X) {
  Placed s;
  s.q = X.M * p.t + X.t;
  s.Q = X.M * p.R;
  s.o = -(s.Q.transpose() * s.q);
  s.nearest = s.q.norm() * (1 - 1e-6f) - p.bound();
  return s;
}

// The 8 corners of a primitive's box (its extent about its frame) placed at q with rotation Q: corner c has the
// + side on axis k when bit k of c is set, so corners c and c | bit share an edge.
void box_corners(const Primitive& p, const Eigen::Vector3f& q, const Eigen::Matrix3f& Q, Eigen::Vector3f corner[8]) {
  const Eigen::Vector3f ext(p.radius, p.radius, p.kind == 1 ? p.half_length : p.radius);
  for (int c = 0; c < 8; ++c)
    corner[c] = q + Q * Eigen::Vector3f((c & 1) ? ext.x() : -ext.x(), (c & 2) ? ext.y() : -ext.y(),
                                        (c & 4) ? ext.z() : -ext.z());
}

// The span [xl, xr] of row y inside a convex polygon (vertices in order); each edge taken from its lower (v, u)
// end, so an edge two triangles share gives both the same x. Empty (xl > xr) when the row misses it.
void row_span(const double* u, const double* v, int count, double y, double* xl, double* xr) {
  *xl = 1e300;
  *xr = -1e300;
  for (int e = 0; e < count; ++e) {
    const int a0 = e, b0 = (e + 1) % count;
    const bool swap = v[b0] < v[a0] || (v[b0] == v[a0] && u[b0] < u[a0]);
    const int a = swap ? b0 : a0, b = swap ? a0 : b0;
    if (y < v[a] || y > v[b]) continue;
    if (v[a] == v[b]) {
      *xl = std::min(*xl, u[a]);
      *xr = std::max(*xr, u[b]);
      continue;
    }
    const double x = u[a] + (y - v[a]) * (u[b] - u[a]) / (v[b] - v[a]);
    *xl = std::min(*xl, x);
    *xr = std::max(*xr, x);
  }
}

// Convex hull of n 2D points (Andrew's monotone chain), counter-clockwise in (u, v), into hu/hv; returns its size.
int convex_hull(const double* u, const double* v, int n, double* hu, double* hv) {
  int order[20];
  for (int i = 0; i < n; ++i) order[i] = i;
  std::sort(order, order + n, [&](int a, int b) { return u[a] < u[b] || (u[a] == u[b] && v[a] < v[b]); });
  int h[41], k = 0;
  auto cross = [&](int o, int a, int b) { return (u[a] - u[o]) * (v[b] - v[o]) - (v[a] - v[o]) * (u[b] - u[o]); };
  for (int i = 0; i < n; ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], order[i]) <= 0) --k;
    h[k++] = order[i];
  }
  for (int i = n - 2, lower = k + 1; i >= 0; --i) {
    while (k >= lower && cross(h[k - 2], h[k - 1], order[i]) <= 0) --k;
    h[k++] = order[i];
  }
  const int m = n > 1 ? k - 1 : n;
  for (int i = 0; i < m; ++i) {
    hu[i] = u[h[i]];
    hv[i] = v[h[i]];
  }
  return m;
}

// A triangle (vertices ps[id[0..2]], sensor frame) as the camera sees it: clipped at x = near, projected onto the
// image [px], its rows, its plane (ns . p = h) and its normal facing the rays (R: sensor to world). False when it
// is degenerate, seen edge-on, or outside the image.
bool triangle_view(const std::vector<Eigen::Vector3f>& ps, const unsigned id[3], const Pinhole& cam,
                   const Eigen::Matrix3f& R, int body, Poly* poly) {
  const int W = cam.width, H = cam.height;
  const double f = cam.f, cx = cam.cx, cy = cam.cy;
  const float near = static_cast<float>(cam.near);
  const Eigen::Vector3f& p0 = ps[id[0]];
  const Eigen::Vector3f ns = (ps[id[1]] - p0).cross(ps[id[2]] - p0);
  const float h = ns.dot(p0);
  // degenerate, or its plane passes through the eye (seen edge-on)
  if (h == 0.f || !std::isfinite(h)) return false;
  // clip at x = near; a point on an edge is interpolated from the edge's lower vertex index, so the two
  // triangles sharing an edge get the same point (no gap between them)
  Eigen::Vector3d q[4];
  int m = 0;
  for (int e = 0; e < 3; ++e) {
    const unsigned ia = id[e], ib = id[(e + 1) % 3];
    const Eigen::Vector3f& A = ps[ia];
    const Eigen::Vector3f& B = ps[ib];
    const bool in_a = A.x() >= near, in_b = B.x() >= near;
    if (in_a) q[m++] = A.cast<double>();
    if (in_a != in_b) {
      const Eigen::Vector3d lo = (ia < ib ? A : B).cast<double>(), hi = (ia < ib ? B : A).cast<double>();
      Eigen::Vector3d c = lo + (hi - lo) * ((near - lo.x()) / (hi.x() - lo.x()));
      c.x() = near;
      q[m++] = c;
    }
  }
  if (m < 3) return false;
  poly->count = m;
  double vmin = 1e300, vmax = -1e300, umin = 1e300, umax = -1e300;
  for (int i = 0; i < m; ++i) {
    poly->u[i] = cx - f * q[i].y() / q[i].x();
    poly->v[i] = cy - f * q[i].z() / q[i].x();
    vmin = std::min(vmin, poly->v[i]);
    vmax = std::max(vmax, poly->v[i]);
    umin = std::min(umin, poly->u[i]);
    umax = std::max(umax, poly->u[i]);
  }
  if (umax < 0 || umin > W - 1) return false;
  poly->row0 = static_cast<int>(std::max(0.0, std::ceil(vmin)));
  poly->row1 = static_cast<int>(std::min(H - 1.0, std::floor(vmax)));
  if (poly->row0 > poly->row1) return false;
  poly->ns = ns;
  poly->h = h;
  // a ray meets the plane at t = h / (ns . d) > 0, so ns . d has the sign of h: -sign(h) ns faces every ray
  poly->nw = (R * (h > 0 ? -ns : ns)).normalized();
  poly->body = body;
  return true;
}

// A primitive placed in the sensor frame (at) as the camera sees it: its box's image (the hull of the corners beyond
// the near plane and of the box edges' crossings of it, grown by a thousandth of a pixel), its rows. False when
// none of it is in the image.
bool primitive_view(const Primitive& p, const Placed& at, const Pinhole& cam, int body, PrimView* pv) {
  const int W = cam.width, H = cam.height;
  const double f = cam.f, cx = cam.cx, cy = cam.cy;
  const float near = static_cast<float>(cam.near);
  pv->p = &p;
  pv->Q = at.Q;
  pv->o = at.o;
  pv->body = body;
  pv->nearest = at.nearest;
  // its box's corners (sensor frame), those beyond the near plane and the box edges' crossings of it
  Eigen::Vector3f corner[8];
  box_corners(p, at.q, at.Q, corner);
  double pu[20], pvv[20];
  int m = 0;
  auto add = [&](const Eigen::Vector3d& x) {
    pu[m] = cx - f * x.y() / x.x();
    pvv[m] = cy - f * x.z() / x.x();
    ++m;
  };
  for (int c = 0; c < 8; ++c)
    if (corner[c].x() >= near) add(corner[c].cast<double>());
  for (int c = 0; c < 8; ++c)
    for (int bit : {1, 2, 4}) {
      if (c & bit) continue;
      const Eigen::Vector3d A = corner[c].cast<double>(), B = corner[c | bit].cast<double>();
      if ((A.x() >= near) == (B.x() >= near)) continue;
      Eigen::Vector3d X2 = A + (B - A) * ((near - A.x()) / (B.x() - A.x()));
      X2.x() = near;
      add(X2);
    }
  if (m == 0) return false;
  // the hull of their images, grown by a thousandth of a pixel: the primitive touches its box's faces
  pv->count = convex_hull(pu, pvv, m, pv->u, pv->v);
  double cu = 0, cv = 0;
  for (int i = 0; i < pv->count; ++i) cu += pv->u[i] / pv->count, cv += pv->v[i] / pv->count;
  double vmin = 1e300, vmax = -1e300, umin = 1e300, umax = -1e300;
  for (int i = 0; i < pv->count; ++i) {
    const double du = pv->u[i] - cu, dv = pv->v[i] - cv, len = std::hypot(du, dv);
    if (len > 0) pv->u[i] += 1e-3 * du / len, pv->v[i] += 1e-3 * dv / len;
    vmin = std::min(vmin, pv->v[i]);
    vmax = std::max(vmax, pv->v[i]);
    umin = std::min(umin, pv->u[i]);
    umax = std::max(umax, pv->u[i]);
  }
  if (pv->count < 3 || umax < 0 || umin > W - 1) return false;
  pv->row0 = static_cast<int>(std::max(0.0, std::ceil(vmin)));
  pv->row1 = static_cast<int>(std::min(H - 1.0, std::floor(vmax)));
  return pv->row0 <= pv->row1;
}

}  // namespace

void RayScene::render(const Eigen::Vector3d& origin, const Eigen::Matrix3d& rotation, const Pinhole& cam,
                      const float* directions, float t_far, RayHit* out,
                      const std::function<void(int, int)>& rows_done) const {
  const int W = cam.width, H = cam.height;
  const double f = cam.f, cx = cam.cx, cy = cam.cy;
  const float near = static_cast<float>(cam.near);
  const Impl& im = *impl_;
  // The frustum's side planes through the outer pixel edges (sensor frame, pointing out): a point p is outside
  // when n . p > 0.
  const Eigen::Vector3f side[4] = {
      Eigen::Vector3d(-(cx + 0.5), f, 0).normalized().cast<float>(),       // left, u = -0.5
      Eigen::Vector3d(-(W - 0.5 - cx), -f, 0).normalized().cast<float>(),  // right, u = W - 0.5
      Eigen::Vector3d(-(cy + 0.5), 0, f).normalized().cast<float>(),       // top, v = -0.5
      Eigen::Vector3d(-(H - 0.5 - cy), 0, -f).normalized().cast<float>()}; // bottom, v = H - 0.5
  auto culled = [&](const Eigen::Vector3f& c, float r) {
    if (c.x() + r <= near || c.norm() - r >= t_far) return true;
    for (const auto& s : side)
      if (s.dot(c) > r) return true;
    return false;
  };
  const Eigen::Matrix3f R = rotation.cast<float>();
  thread_local std::vector<Poly> polys;
  thread_local std::vector<PrimView> prims;
  polys.clear();
  prims.clear();
  for (size_t b = 0; b < im.bodies.size(); ++b) {
    const Impl::Body& body = im.bodies[b];
    const Xform X = sensor_from_body(body.pose, origin, rotation);
    if (culled(X.M * body.centre + X.t, body.radius)) continue;
    const std::vector<Eigen::Vector3f>& ps = sensor_vertices(body.verts, X);
    for (size_t k = 0; k + 2 < body.idx.size(); k += 3) {
      const unsigned id[3] = {body.idx[k], body.idx[k + 1], body.idx[k + 2]};
      Poly poly;
      if (triangle_view(ps, id, cam, R, static_cast<int>(b), &poly)) polys.push_back(poly);
    }
    for (const Primitive* p : body.prims) {
      const Placed at = place(*p, X);
      if (culled(at.q, p->bound())) continue;
      PrimView pv;
      if (primitive_view(*p, at, cam, static_cast<int>(b), &pv)) prims.push_back(pv);
    }
  }
  const std::vector<Poly>& P = polys;
  const std::vector<PrimView>& V = prims;
  // Bands of 8 rows, handed out as threads come free. Every band visits the triangles, then the primitives, in
  // the same order, so each pixel sees the same sequence of candidates for any thread count.
  constexpr int kBand = 8;
  const int bands = (H + kBand - 1) / kBand;
  auto band = [&](int bi) {
    const int r0 = bi * kBand, r1 = std::min(H - 1, r0 + kBand - 1);
    const size_t n = static_cast<size_t>(r1 - r0 + 1) * W;
    // the band's rays as separate x, y, z arrays, and per pixel the nearest distance so far and the polygon it
    // lies on (-1: none), so that a polygon's row of pixels is one loop the compiler turns into vector code
    thread_local std::vector<float> sx, sy, sz, dist;
    thread_local std::vector<int> which;
    sx.resize(n), sy.resize(n), sz.resize(n), dist.resize(n), which.resize(n);
    {
      const float* __restrict const d_band = directions + 3 * static_cast<size_t>(r0) * W;
      float* __restrict const x = sx.data();
      float* __restrict const y = sy.data();
      float* __restrict const z = sz.data();
      float* __restrict const best = dist.data();
      int* __restrict const on = which.data();
      for (size_t k = 0; k < n; ++k) {
        x[k] = d_band[3 * k];
        y[k] = d_band[3 * k + 1];
        z[k] = d_band[3 * k + 2];
        best[k] = t_far;
        on[k] = -1;
      }
    }
    for (size_t pi = 0; pi < P.size(); ++pi) {
      const Poly& poly = P[pi];
      if (poly.row1 < r0 || poly.row0 > r1) continue;
      const float nx = poly.ns.x(), ny = poly.ns.y(), nz = poly.ns.z(), h = poly.h;
      const int id = static_cast<int>(pi);
      for (int row = std::max(r0, poly.row0); row <= std::min(r1, poly.row1); ++row) {
        // the row's pixel centres inside the polygon
        double xl, xr;
        row_span(poly.u, poly.v, poly.count, row, &xl, &xr);
        const int c0 = static_cast<int>(std::max(0.0, std::ceil(xl)));
        const int c1 = static_cast<int>(std::min(W - 1.0, std::floor(xr)));
        const size_t off = static_cast<size_t>(row - r0) * W;
        const float* __restrict const dx = sx.data() + off;
        const float* __restrict const dy = sy.data() + off;
        const float* __restrict const dz = sz.data() + off;
        float* __restrict const best = dist.data() + off;
        int* __restrict const on = which.data() + off;
        for (int c = c0; c <= c1; ++c) {
          // the exact distance along the pixel's ray to the triangle's plane
          const float t = h / (nx * dx[c] + ny * dy[c] + nz * dz[c]);
          // both tests always evaluated (&, not &&): no branch, so the loop vectorises
          const bool nearer = (t < best[c]) & (t * dx[c] > near);
          best[c] = nearer ? t : best[c];
          on[c] = nearer ? id : on[c];
        }
      }
    }
    // into the hits: no hit reads +inf with a zero normal (a primitive below may still claim the pixel, within
    // t_far)
    RayHit* const ob = out + static_cast<size_t>(r0) * W;
    for (size_t k = 0; k < n; ++k) {
      if (which[k] >= 0) {
        const Poly& poly = P[which[k]];
        ob[k].distance = dist[k];
        ob[k].body = poly.body;
        ob[k].normal = poly.nw;
      } else {
        ob[k].distance = kInf;
        ob[k].body = -1;
        ob[k].normal.setZero();
      }
    }
    for (const PrimView& pv : V) {
      if (pv.row1 < r0 || pv.row0 > r1) continue;
      for (int row = std::max(r0, pv.row0); row <= std::min(r1, pv.row1); ++row) {
        double xl, xr;
        row_span(pv.u, pv.v, pv.count, row, &xl, &xr);
        const int c0 = static_cast<int>(std::max(0.0, std::ceil(xl)));
        const int c1 = static_cast<int>(std::min(W - 1.0, std::floor(xr)));
        for (int c = c0; c <= c1; ++c) {
          const size_t k = static_cast<size_t>(row) * W + c;
          // what the pixel already sees, else the far end of the rays
          const float seen = out[k].body >= 0 ? out[k].distance : t_far;
          if (pv.nearest >= seen) continue;  // hidden behind it
          const float* dc = directions + 3 * k;
          const Eigen::Vector3f ds(dc[0], dc[1], dc[2]);
          float t;
          Eigen::Vector3f n;
          if (hit_primitive(*pv.p, pv.o, pv.Q.transpose() * ds, near / dc[0], seen, &t, &n)) {
            // the unit outward normal; flipped when the ray leaves the primitive (the sensor inside it)
            Eigen::Vector3f ns = pv.Q * n;
            if (ns.dot(ds) > 0) ns = -ns;
            out[k].distance = t;
            out[k].body = pv.body;
            out[k].normal = R * ns;
          }
        }
      }
    }
    if (rows_done) rows_done(r0, r1);
  };
  // car's pool (parallel.hpp) for camera-sized images: a late worker is not waited for
  if (static_cast<long>(W) * H >= 65536) {
    parallel_for(bands, band);
  } else {
    for (int bi = 0; bi < bands; ++bi) band(bi);
  }
}

namespace {

// The rays of a fan whose angles fall in [lo, lo + span] [rad] (modulo 2 pi), with a margin, as index ranges.
template <typename F>
void for_rays_in_arc(double lo, double span, double angle_min, double inc, int n, F&& f) {
  if (n <= 1 || !(inc > 0)) {
    for (int i = 0; i < n; ++i) f(i);
    return;
  }
  // a ray's float direction is within 1e-6 rad of its angle: one index, and more for very fine fans
  const int margin = 1 + static_cast<int>(std::ceil(1e-6 / inc));
  const double angle_max = angle_min + (n - 1) * inc;
  const int k0 = static_cast<int>(std::floor((angle_min - lo - span) / kTwoPi)) - 1;
  const int k1 = static_cast<int>(std::ceil((angle_max - lo) / kTwoPi)) + 1;
  int done = -1;  // rays up to here are visited (arcs of successive turns do not overlap but their margins may)
  for (int k = k0; k <= k1; ++k) {
    const double a = lo + kTwoPi * k;
    const double i0 = std::floor((a - angle_min) / inc) - margin, i1 = std::ceil((a + span - angle_min) / inc) + margin;
    if (i1 < 0 || i0 > n - 1) continue;
    const int first = std::max({0, static_cast<int>(i0), done + 1}), last = std::min(n - 1, static_cast<int>(i1));
    for (int i = first; i <= last; ++i) f(i);
    done = std::max(done, last);
  }
}

}  // namespace

namespace {

// What a fan's rays may meet: a triangle's segment in the scan plane, or a primitive; nearest possible first.
struct FanItem {
  float dmin = 0;                                    // [m] no point of it is nearer to the sensor
  int order = 0;                                     // collection order, the tie-break (deterministic)
  int body = -1;
  Eigen::Vector2f p0 = Eigen::Vector2f::Zero();      // segment: from p0 along e [m], sensor frame
  Eigen::Vector2f e = Eigen::Vector2f::Zero();
  float num = 0;                                     // cross(p0, e)
  Eigen::Vector3f nw = Eigen::Vector3f::Zero();      // segment: unit normal, world frame, facing the sensor
  const Primitive* prim = nullptr;                   // or a primitive (null for a segment)
  Eigen::Matrix3f Q = Eigen::Matrix3f::Identity();   // primitive frame into the sensor frame
  Eigen::Vector3f o = Eigen::Vector3f::Zero();       // the sensor origin in the primitive frame
  double lo = 0, span = 0;                           // [rad] its angular span
};

// A primitive's angular span [rad] (it->lo, it->span), seen from the sensor: that of its box's cut by the plane
// z = 0 (the box's edges' crossings); the whole turn when the sensor may be inside. q: its centre, it->Q its axes,
// sensor frame. False when the box does not reach the plane.
bool primitive_arc(const Primitive& p, const Eigen::Vector3f& q, FanItem* it) {
  Eigen::Vector3f corner[8];
  box_corners(p, q, it->Q, corner);
  Eigen::Vector2d cut[12];
  int m = 0;
  for (int c = 0; c < 8; ++c)
    for (int bit : {1, 2, 4}) {
      if (c & bit) continue;
      const Eigen::Vector3d A = corner[c].cast<double>(), B = corner[c | bit].cast<double>();
      if ((A.z() > 0 && B.z() > 0) || (A.z() < 0 && B.z() < 0)) continue;
      const double s = A.z() == B.z() ? 0.0 : A.z() / (A.z() - B.z());
      cut[m++] = (A + (B - A) * s).head<2>();
    }
  if (m == 0) return false;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (int k = 0; k < m; ++k) centre += cut[k] / m;
  double reach = 0;
  for (int k = 0; k < m; ++k) reach = std::max(reach, (cut[k] - centre).norm());
  if (centre.norm() <= reach * 1.001 + 1e-6) {
    it->lo = -M_PI;
    it->span = kTwoPi;
  } else {
    const double fc = std::atan2(centre.y(), centre.x());
    double lo = 0, hi = 0;
    for (int k = 0; k < m; ++k) {
      double a = std::atan2(cut[k].y(), cut[k].x()) - fc;
      if (a > M_PI) a -= kTwoPi;
      if (a < -M_PI) a += kTwoPi;
      lo = std::min(lo, a);
      hi = std::max(hi, a);
    }
    it->lo = fc + lo;
    it->span = hi - lo;
  }
  return true;
}

}  // namespace

void RayScene::cast_fan(const Eigen::Vector3d& origin, const Eigen::Matrix3d& rotation, const float* directions,
                        int n, double angle_min, double increment, float t_near, float t_far, RayHit* out) const {
  const Impl& im = *impl_;
  const Eigen::Matrix3f R = rotation.cast<float>();
  thread_local std::vector<FanItem> items;
  items.clear();
  auto arc = [](const Eigen::Vector2f& p0, const Eigen::Vector2f& p1, FanItem* it) {
    const double f0 = std::atan2(p0.y(), p0.x()), f1 = std::atan2(p1.y(), p1.x());
    double delta = f1 - f0;
    if (delta > M_PI) delta -= kTwoPi;
    if (delta < -M_PI) delta += kTwoPi;
    it->lo = delta >= 0 ? f0 : f1;
    it->span = std::abs(delta);
  };
  for (size_t b = 0; b < im.bodies.size(); ++b) {
    const Impl::Body& body = im.bodies[b];
    const Xform X = sensor_from_body(body.pose, origin, rotation);
    const Eigen::Vector3f c = X.M * body.centre + X.t;
    // the body's bound misses the plane z = 0, or lies beyond the range
    if (std::abs(c.z()) > body.radius || c.norm() - body.radius >= t_far) continue;
    const std::vector<Eigen::Vector3f>& ps = sensor_vertices(body.verts, X);
    for (size_t k = 0; k + 2 < body.idx.size(); k += 3) {
      const unsigned id[3] = {body.idx[k], body.idx[k + 1], body.idx[k + 2]};
      const float z[3] = {ps[id[0]].z(), ps[id[1]].z(), ps[id[2]].z()};
      if ((z[0] > 0 && z[1] > 0 && z[2] > 0) || (z[0] < 0 && z[1] < 0 && z[2] < 0)) continue;
      if (z[0] == 0 && z[1] == 0 && z[2] == 0) continue;  // in the plane: seen edge-on
      // the segment where the triangle meets z = 0: its vertices on the plane and its edges' crossings (each
      // interpolated from the edge's lower vertex index, so neighbours share the end point exactly)
      Eigen::Vector2f s[3];
      int m = 0;
      for (int e = 0; e < 3; ++e) {
        if (z[e] == 0) s[m++] = ps[id[e]].head<2>();
        const int a = e, bb = (e + 1) % 3;
        if ((z[a] > 0 && z[bb] < 0) || (z[a] < 0 && z[bb] > 0)) {
          const Eigen::Vector3f& lo = ps[std::min(id[a], id[bb])];
          const Eigen::Vector3f& hi = ps[std::max(id[a], id[bb])];
          s[m++] = (lo + (hi - lo) * (lo.z() / (lo.z() - hi.z()))).head<2>();
        }
      }
      if (m < 2) continue;
      FanItem it;
      it.p0 = s[0];
      it.e = s[1] - s[0];
      it.num = it.p0.x() * it.e.y() - it.p0.y() * it.e.x();
      // nearest point of the segment to the sensor
      const float ee = it.e.squaredNorm();
      const float u = ee > 0 ? std::clamp(-it.p0.dot(it.e) / ee, 0.f, 1.f) : 0.f;
      it.dmin = (it.p0 + u * it.e).norm() * (1 - 1e-6f);
      if (it.dmin >= t_far || std::max(s[0].norm(), s[1].norm()) <= t_near) continue;
      // the normal facing the sensor: the origin lies on the side -ns points to when ns . p0 > 0
      const Eigen::Vector3f ns = (ps[id[1]] - ps[id[0]]).cross(ps[id[2]] - ps[id[0]]);
      it.nw = (R * (ns.dot(ps[id[0]]) > 0 ? -ns : ns)).normalized();
      it.prim = nullptr;
      it.body = static_cast<int>(b);
      arc(s[0], s[1], &it);
      it.order = static_cast<int>(items.size());
      items.push_back(it);
    }
    for (const Primitive* p : body.prims) {
      const Placed at = place(*p, X);
      const Eigen::Vector3f& q = at.q;
      const float r = p->bound();
      // it misses the plane, lies beyond the range, or wholly within t_near (the sensor's own housing)
      if (std::abs(q.z()) > r || q.norm() - r >= t_far || q.norm() + r <= t_near) continue;
      FanItem it;
      it.prim = p;
      it.Q = at.Q;
      it.o = at.o;
      it.body = static_cast<int>(b);
      it.dmin = at.nearest;
      if (!primitive_arc(*p, q, &it)) continue;
      it.order = static_cast<int>(items.size());
      items.push_back(it);
    }
  }
  // nearest first: a ray skips whatever cannot be nearer than what it already hit
  std::sort(items.begin(), items.end(), [](const FanItem& a, const FanItem& b) {
    return a.dmin < b.dmin || (a.dmin == b.dmin && a.order < b.order);
  });
  for (int i = 0; i < n; ++i) {
    out[i].distance = t_far;
    out[i].body = -1;
  }
  for (const FanItem& it : items) {
    if (!it.prim) {
      const Eigen::Vector2f p0 = it.p0, p1 = it.p0 + it.e, e = it.e;
      for_rays_in_arc(it.lo, it.span, angle_min, increment, n, [&](int i) {
        if (it.dmin >= out[i].distance) return;
        const float dx = directions[3 * i], dy = directions[3 * i + 1];
        // the ray's line separates the end points (or touches one): the same signs for both triangles at a
        // shared end point, so no ray slips between them
        const float c0 = dx * p0.y() - dy * p0.x(), c1 = dx * p1.y() - dy * p1.x();
        if ((c0 > 0 && c1 > 0) || (c0 < 0 && c1 < 0) || (c0 == 0 && c1 == 0)) return;
        const float t = it.num / (dx * e.y() - dy * e.x());
        if (t > t_near && t < out[i].distance) {
          out[i].distance = t;
          out[i].body = it.body;
          out[i].normal = it.nw;
        }
      });
    } else {
      for_rays_in_arc(it.lo, it.span, angle_min, increment, n, [&](int i) {
        if (it.dmin >= out[i].distance) return;
        const Eigen::Vector3f d(directions[3 * i], directions[3 * i + 1], directions[3 * i + 2]);
        float t;
        Eigen::Vector3f nrm;
        if (hit_primitive(*it.prim, it.o, it.Q.transpose() * d, t_near, out[i].distance, &t, &nrm)) {
          // the unit outward normal; flipped when the ray leaves the primitive (the sensor inside it)
          Eigen::Vector3f ns = it.Q * nrm;
          if (ns.dot(d) > 0) ns = -ns;
          out[i].distance = t;
          out[i].body = it.body;
          out[i].normal = R * ns;
        }
      });
    }
  }
  // no hit reads +inf
  for (int i = 0; i < n; ++i)
    if (out[i].body < 0) {
      out[i].distance = kInf;
      out[i].normal.setZero();
    }
}

}  // namespace car_sim
