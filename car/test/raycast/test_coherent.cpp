// Car's coherent ray kernels (RayScene::render for pinhole cameras, RayScene::cast_fan for planar fans) against
// hand-worked distances, and against Embree's general path (RayScene::cast) ray by ray on a scene of boxes,
// cylinders, spheres and a ground plane seen from many poses.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "car_sim/raycast.hpp"
#include "xml_util.hpp"

using namespace car_sim;

namespace {

Shape box(double sx, double sy, double sz) {
  Shape s;
  s.type = ShapeType::Box;
  s.size = Eigen::Vector3d(sx, sy, sz);
  return s;
}
Shape cylinder(double r, double l) {
  Shape s;
  s.type = ShapeType::Cylinder;
  s.radius = r;
  s.length = l;
  return s;
}
Shape sphere(double r) {
  Shape s;
  s.type = ShapeType::Sphere;
  s.radius = r;
  return s;
}
Shape plane() {
  Shape s;
  s.type = ShapeType::Plane;
  s.size = Eigen::Vector3d(100, 100, 0);
  return s;
}

Eigen::Isometry3d at(double x, double y, double z, double yaw = 0, double pitch = 0, double roll = 0) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(x, y, z);
  T.linear() = detail::rpy_to_matrix(roll, pitch, yaw);
  return T;
}

using Shapes = std::vector<std::pair<Shape, Eigen::Isometry3d>>;

// A room: the ground, four walls 8 m apart, boxes, a cylinder lying down, a standing one and a sphere, one body
// carrying a box and a cylinder; some bodies placed by a pose rather than in their shapes.
void build_room(RayScene* s) {
  s->add_body({{plane(), Eigen::Isometry3d::Identity()}}, {});
  // the walls stand 1 and 2 mm off the floor: no face of one body is coplanar with another's (the floor and the
  // walls' bottoms, the two wall pairs' tops where they overlap at the corners), whose hit is a rounding tie that
  // two kernels, or one kernel built by two compilers, break differently (62 rays at one pose under clang -O1)
  s->add_body({{box(0.2, 8, 2), at(4, 0, 1.001)}, {box(0.2, 8, 2), at(-4, 0, 1.001)}}, {});
  s->add_body({{box(8, 0.2, 2), at(0, 4, 1.002)}, {box(8, 0.2, 2), at(0, -4, 1.002)}}, {});
  s->add_body({{box(1, 0.5, 0.8), at(1.5, 1, 0.4, 0.3)}}, {});
  s->add_body({{cylinder(0.3, 1.2), at(-1.5, -1, 0.3, 0.4, M_PI / 2)}}, {});
  s->add_body({{cylinder(0.25, 1.0), at(2, -2, 0.5)}}, {});
  s->add_body({{sphere(0.4), at(-2, 2, 0.6)}}, {});
  const int moved = s->add_body({{box(0.6, 0.3, 0.3), at(0, 0, 0)}, {cylinder(0.1, 0.05), at(0.2, 0.2, 0, 0, M_PI / 2)}}, {});
  s->set_pose(moved, at(0.5, -1.2, 0.35, 1.1, 0.2));
  s->commit();
}

// Pixel directions as the camera plug-in makes them (sensor frame, unit, pixel order).
std::vector<float> pixel_dirs(const Pinhole& c) {
  std::vector<float> d;
  for (int v = 0; v < c.height; ++v)
    for (int u = 0; u < c.width; ++u) {
      const Eigen::Vector3d r = Eigen::Vector3d(c.f, -(u - c.cx), -(v - c.cy)).normalized();
      for (int k = 0; k < 3; ++k) d.push_back(static_cast<float>(r[k]));
    }
  return d;
}

Pinhole camera(int w, int h, double hfov, double near) {
  const double f = w / (2 * std::tan(hfov / 2));
  return Pinhole{w, h, f, (w - 1) / 2.0, (h - 1) / 2.0, near};
}

// Fan directions as the laser plug-in makes them.
std::vector<float> fan_dirs(int n, double a, double b) {
  std::vector<float> d;
  for (int i = 0; i < n; ++i) {
    const double th = n > 1 ? a + i * (b - a) / (n - 1) : a;
    d.push_back(static_cast<float>(std::cos(th)));
    d.push_back(static_cast<float>(std::sin(th)));
    d.push_back(0.f);
  }
  return d;
}

// Rays where the two answers disagree: one hits and the other not, other bodies, distances more than
// 1e-5 m + 2e-5 relative apart, or normals more than 1e-3 apart. Both work in float: rays that graze a surface
// differ by a few micrometres (a 5 m segment's end points cancel in float; Embree's transform is float too).
int disagreements(const std::vector<RayHit>& a, const std::vector<RayHit>& b) {
  int bad = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    const bool ha = std::isfinite(a[i].distance), hb = std::isfinite(b[i].distance);
    if (ha != hb) {
      ++bad;
      continue;
    }
    if (!ha) continue;
    if (a[i].body != b[i].body || std::abs(a[i].distance - b[i].distance) > 1e-5f + 2e-5f * a[i].distance ||
        (a[i].normal - b[i].normal).norm() > 1e-3f)
      ++bad;
  }
  return bad;
}

}  // namespace

// A camera 2 m from a wall face, looking at it square on: pixel (u, v) reads 2 m / cos of its ray's angle to the
// optical axis, i.e. 2 |(f, u - cx, v - cy)| / f; the centre pixel of an odd image reads 2 m exactly.
TEST(RayKernels, CameraReadsTheWallAtTwoMetresOverCosine) {
  RayScene s;
  s.add_body({{box(0.2, 20, 20), at(3.1, 0, 0)}}, {});  // face at x = 3
  s.commit();
  const Pinhole c = camera(33, 25, 1.2, 0.05);
  const std::vector<float> d = pixel_dirs(c);
  std::vector<RayHit> out(33 * 25);
  s.render(Eigen::Vector3d(1, 0, 0), Eigen::Matrix3d::Identity(), c, d.data(), 100.f, out.data());
  for (int v = 0; v < 25; ++v)
    for (int u = 0; u < 33; ++u) {
      const double expect = 2 * std::sqrt(c.f * c.f + (u - c.cx) * (u - c.cx) + (v - c.cy) * (v - c.cy)) / c.f;
      EXPECT_NEAR(out[v * 33 + u].distance, expect, 1e-5) << u << " " << v;
      EXPECT_EQ(out[v * 33 + u].body, 0);
      EXPECT_NEAR(out[v * 33 + u].normal.x(), -1.0, 1e-6);  // the face's normal, facing the camera
    }
  EXPECT_NEAR(out[12 * 33 + 16].distance, 2.0, 1e-6);
}

// A standing cylinder of radius 0.5 m, its axis 3 m ahead: the centre pixel reads 2.5 m; the ray of a column
// at angle a to the axis meets it at 3 cos a - sqrt(0.25 - 9 sin^2 a).
TEST(RayKernels, CameraReadsACylinderAnalytically) {
  RayScene s;
  s.add_body({{cylinder(0.5, 4), at(3, 0, 0)}}, {});
  s.commit();
  const Pinhole c = camera(41, 11, 0.5, 0.05);
  const std::vector<float> d = pixel_dirs(c);
  std::vector<RayHit> out(41 * 11);
  s.render(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), c, d.data(), 100.f, out.data());
  EXPECT_NEAR(out[5 * 41 + 20].distance, 2.5, 1e-6);
  for (int u = 0; u < 41; ++u) {
    const double a = std::atan((u - c.cx) / c.f);
    const double disc = 0.25 - 9 * std::sin(a) * std::sin(a);
    if (disc < 1e-4) {
      if (disc < -1e-4) {
        EXPECT_FALSE(std::isfinite(out[5 * 41 + u].distance)) << u;
      }
      continue;
    }
    EXPECT_NEAR(out[5 * 41 + u].distance, 3 * std::cos(a) - std::sqrt(disc), 1e-5) << u;
  }
}

// Nothing nearer than the near clip plane: a box straddling the sensor is seen only by its far faces, 0.5 m away.
TEST(RayKernels, CameraSeesNothingBeforeTheNearPlane) {
  RayScene s;
  s.add_body({{box(1, 10, 10), at(0, 0, 0)}}, {});  // faces at x = -0.5 and +0.5
  s.commit();
  const Pinhole c = camera(9, 9, 0.3, 0.6);
  const std::vector<float> d = pixel_dirs(c);
  std::vector<RayHit> out(81);
  s.render(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), c, d.data(), 100.f, out.data());
  for (const RayHit& h : out) EXPECT_FALSE(std::isfinite(h.distance));
  const Pinhole c2 = camera(9, 9, 0.3, 0.4);
  s.render(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), c2, d.data(), 100.f, out.data());
  EXPECT_NEAR(out[40].distance, 0.5, 1e-6);
}

// The rasteriser and Embree agree ray by ray in the room from 40 random poses (inside and outside it, tilted).
TEST(RayKernels, CameraRenderMatchesEmbreeRayByRay) {
  RayScene s;
  build_room(&s);
  const Pinhole c = camera(96, 72, 1.3, 0.05);
  const std::vector<float> d = pixel_dirs(c);
  std::vector<float> t_near;
  for (size_t k = 0; k < d.size() / 3; ++k) t_near.push_back(static_cast<float>(c.near / d[3 * k]));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1, 1);
  std::vector<RayHit> a(96 * 72), b(96 * 72);
  int total = 0;
  for (int i = 0; i < 40; ++i) {
    const Eigen::Isometry3d T = at(5 * U(rng), 5 * U(rng), 0.2 + 1.5 * (U(rng) + 1), M_PI * U(rng), 0.6 * U(rng), 0.3 * U(rng));
    s.render(T.translation(), T.linear(), c, d.data(), 30.f, a.data());
    s.cast(T.translation(), T.linear(), d.data(), 96 * 72, t_near.data(), true, 30.f, b.data());
    total += disagreements(a, b);
  }
  // a pixel centre within rounding of a silhouette may go either way: at most a few in 276 480 rays
  EXPECT_LE(total, 5);
}

// The fan sweep and Embree agree ray by ray in the room from 60 random poses, level and tilted, with full and
// partial turns.
TEST(RayKernels, FanMatchesEmbreeRayByRay) {
  RayScene s;
  build_room(&s);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(-1, 1);
  int total = 0;
  for (int i = 0; i < 60; ++i) {
    const int n = i % 3 == 0 ? 1081 : 360;
    const double a = i % 2 ? -M_PI : -2.0, b = i % 2 ? M_PI : 1.5;
    const std::vector<float> d = fan_dirs(n, a, b);
    const Eigen::Isometry3d T = at(5 * U(rng), 5 * U(rng), 0.1 + 1.0 * (U(rng) + 1), M_PI * U(rng),
                                   i % 4 == 0 ? 0.0 : 0.4 * U(rng), i % 4 == 0 ? 0.0 : 0.4 * U(rng));
    std::vector<RayHit> x(n), y(n);
    const float t_near = 0.12f;
    s.cast_fan(T.translation(), T.linear(), d.data(), n, a, (b - a) / (n - 1), t_near, 12.f, x.data());
    s.cast(T.translation(), T.linear(), d.data(), n, &t_near, false, 12.f, y.data());
    total += disagreements(x, y);
  }
  EXPECT_LE(total, 3);
}

// Fan rays at the angles of a 3-4-5 triangle: a wall 3 m ahead is read at 3 / cos(th); rays parallel to the wall
// or pointing away read +inf.
TEST(RayKernels, FanReadsTheWallAtThreeMetresOverCosine) {
  RayScene s;
  s.add_body({{box(0.2, 50, 4), at(3.1, 0, 0)}}, {});
  s.commit();
  const int n = 9;
  const std::vector<float> d = fan_dirs(n, -M_PI, M_PI);  // every 45 degrees
  std::vector<RayHit> out(n);
  s.cast_fan(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), d.data(), n, -M_PI, M_PI / 4, 0.f, 30.f, out.data());
  EXPECT_NEAR(out[4].distance, 3.0, 1e-6);              // 0
  EXPECT_NEAR(out[3].distance, 3.0 * std::sqrt(2), 1e-5);  // -45 degrees
  EXPECT_NEAR(out[5].distance, 3.0 * std::sqrt(2), 1e-5);  // +45 degrees
  for (int i : {0, 1, 2, 6, 7, 8}) EXPECT_FALSE(std::isfinite(out[i].distance)) << i;
}

// The camera's rows are shared out among threads: one thread and two give the same bytes.
TEST(RayKernels, RenderIsTheSameOnOneThreadAndTwo) {
  RayScene s;
  build_room(&s);
  const Pinhole c = camera(320, 240, 1.0, 0.05);
  const std::vector<float> d = pixel_dirs(c);
  std::vector<RayHit> a(320 * 240), b(320 * 240);
  const Eigen::Isometry3d T = at(-3, -0.5, 0.6, 0.3, 0.1);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  s.render(T.translation(), T.linear(), c, d.data(), 30.f, a.data());
  omp_set_num_threads(2);
  s.render(T.translation(), T.linear(), c, d.data(), 30.f, b.data());
  omp_set_num_threads(threads);
  for (size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(std::memcmp(&a[i].distance, &b[i].distance, sizeof(float)), 0) << i;
    ASSERT_EQ(a[i].body, b[i].body) << i;
  }
}
