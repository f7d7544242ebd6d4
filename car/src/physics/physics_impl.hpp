// Physics::Impl, the Bullet state behind Physics (private to physics/): the world, its solver and dispatcher, the
// shapes and objects it owns, the world models, the robots and the ray scene. Its methods live beside what they
// build: shapes here, world models in world_models.cpp, the ray scene in physics.cpp.
#pragma once

#include <btBulletDynamicsCommon.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>

#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "convert.hpp"
#include "island_world.hpp"
#include "physics.hpp"
#include "plane_collision.hpp"
#include "surface.hpp"

namespace car_sim {
namespace physics {

// Collision margin for boxes and cylinders [m]; Bullet keeps the outer size, so this only rounds edges.
inline constexpr double kMargin = 0.0005;

class BulletRobot;

struct Physics::Impl {
  Options options;
  std::unique_ptr<btCollisionConfiguration> config = make_collision_config();
  IslandDispatcher dispatcher{config.get()};  // the settled pairs' narrow phase on every core (island_world.hpp)
  btDbvtBroadphase broadphase;
  SurfaceSolver solver;  // Bullet's, with Gazebo's surface rules where a pair needs them (surface.hpp)
  // islands solved one by one, on every core OpenMP offers (island_world.hpp)
  IslandWorld world{&dispatcher, &broadphase, &solver, config.get()};
  // static meshes (declared before the shapes that point into them): Bullet's view of the triangles, and the scaled copies it points into
  std::vector<std::unique_ptr<btTriangleIndexVertexArray>> mesh_arrays;
  std::vector<std::unique_ptr<std::vector<btScalar>>> mesh_vertices;
  std::vector<std::unique_ptr<std::vector<int>>> mesh_indices;
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btCollisionObject>> objects;  // static objects and rigid bodies
  std::vector<std::unique_ptr<btMotionState>> motion_states;

  struct DynModel {
    std::string name;
    const WorldModelDesc* desc;
    std::vector<btRigidBody*> bodies;          // one per link
    std::vector<Eigen::Isometry3d> link_to_com;
  };
  std::vector<DynModel> dyn_models;            // dynamic world models
  // A static world model: where it is now, and its collisions that move with it (a plane stays where it was
  // loaded: ODE's plane is not placeable, docs/COMPAT.md set_model_state).
  struct StaticModel {
    const WorldModelDesc* desc;
    Eigen::Isometry3d pose;  // [m], world frame; the description's until set_model_state moves it
    struct Part {
      btCollisionObject* object;
      const WorldLink* link;
      const WorldCollision* collision;
    };
    std::vector<Part> parts;
    // its bodies in the ray scene (build_rays), built at the description's pose: moved, they are placed at
    // pose * description pose^-1; a link's planes are a body of their own, which stays
    std::vector<int> ray_bodies;
  };
  std::vector<StaticModel> static_models;
  std::map<std::string, std::vector<btCollisionObject*>> model_objects;  // world model -> its Bullet objects
  std::vector<std::unique_ptr<BulletRobot>> robots;
  std::vector<std::string> object_names;       // btCollisionObject user index -> "model/link"
  std::vector<std::unique_ptr<SurfaceSet>> surfaces;  // world objects' surfaces (their user pointers)

  std::unique_ptr<RayScene> rays;
  std::vector<std::pair<int, const btCollisionObject*>> moving_ray_bodies;  // ray body -> its Bullet object
  uint64_t rays_stamp = ~0ull;                 // the step count the ray poses were taken at
  uint64_t steps = 0;

  Impl(const WorldDescription& d, const Options& o);
  ~Impl();

  void name_object(btCollisionObject* o, const std::string& name) {
    o->setUserIndex(static_cast<int>(object_names.size()));
    object_names.push_back(name);
  }

  btCollisionShape* own(btCollisionShape* s) {
    shapes.emplace_back(s);
    return s;
  }

  // A Bullet shape for a primitive or a loaded mesh (a dynamic body's mesh as its convex hull, a static one as its
  // exact triangles); nullptr for what Bullet cannot collide (planes on moving bodies, meshes never loaded).
  btCollisionShape* make_shape(const Shape& s, bool dynamic) {
    switch (s.type) {
      case ShapeType::Box: {
        auto* b = new btBoxShape(bt(Eigen::Vector3d(s.size / 2.0)));
        b->setMargin(kMargin);
        return own(b);
      }
      case ShapeType::Cylinder: {
        auto* c = new btCylinderShapeZ(btVector3(s.radius, s.radius, s.length / 2.0));
        c->setMargin(kMargin);
        return own(c);
      }
      case ShapeType::Sphere:
        return own(new btSphereShape(s.radius));
      case ShapeType::Mesh:
        if (!s.mesh) return nullptr;
        return dynamic ? make_hull(*s.mesh, s.mesh_scale) : make_trimesh(*s.mesh, s.mesh_scale);
      default:
        return nullptr;
    }
  }

  // The convex hull of a mesh's vertices (scaled), reduced to the hull's own vertices; contacts use its faces.
  // Bullet inflates a hull by its margin, so a mesh body rests kMargin higher than its triangles say.
  btCollisionShape* make_hull(const TriMesh& m, const Eigen::Vector3d& scale) {
    auto* hull = new btConvexHullShape();
    for (const auto& v : m.vertices)
      hull->addPoint(btVector3(v.x() * scale.x(), v.y() * scale.y(), v.z() * scale.z()), false);
    hull->recalcLocalAabb();
    hull->optimizeConvexHull();
    hull->initializePolyhedralFeatures();
    hull->setMargin(kMargin);
    return own(hull);
  }

  // A static mesh's exact triangles (scaled), in a bounding-volume tree.
  btCollisionShape* make_trimesh(const TriMesh& m, const Eigen::Vector3d& scale) {
    auto verts = std::make_unique<std::vector<btScalar>>();
    auto idx = std::make_unique<std::vector<int>>(m.indices.begin(), m.indices.end());
    verts->reserve(3 * m.vertices.size());
    for (const auto& v : m.vertices) {
      verts->push_back(v.x() * scale.x());
      verts->push_back(v.y() * scale.y());
      verts->push_back(v.z() * scale.z());
    }
    btIndexedMesh im;
    im.m_numTriangles = static_cast<int>(idx->size() / 3);
    im.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(idx->data());
    im.m_triangleIndexStride = 3 * sizeof(int);
    im.m_numVertices = static_cast<int>(verts->size() / 3);
    im.m_vertexBase = reinterpret_cast<const unsigned char*>(verts->data());
    im.m_vertexStride = 3 * sizeof(btScalar);
    im.m_indexType = PHY_INTEGER;
    im.m_vertexType = sizeof(btScalar) == sizeof(double) ? PHY_DOUBLE : PHY_FLOAT;
    auto* array = new btTriangleIndexVertexArray();
    array->addIndexedMesh(im, PHY_INTEGER);
    mesh_arrays.emplace_back(array);
    mesh_vertices.push_back(std::move(verts));
    mesh_indices.push_back(std::move(idx));
    auto* shape = new btBvhTriangleMeshShape(array, true);
    shape->setMargin(kMargin);
    return own(shape);
  }

  // One shape, or a compound of several, placed relative to a frame (com for moving bodies).
  // kept: the indices of the parts Bullet collides, in compound-child order.
  btCollisionShape* make_body_shape(const std::vector<std::pair<Shape, Eigen::Isometry3d>>& parts,
                                    std::vector<int>* kept = nullptr) {
    std::vector<std::pair<btCollisionShape*, Eigen::Isometry3d>> made;
    for (size_t i = 0; i < parts.size(); ++i) {
      if (btCollisionShape* s = make_shape(parts[i].first, true)) {
        made.emplace_back(s, parts[i].second);
        if (kept) kept->push_back(static_cast<int>(i));
      }
    }
    if (made.empty()) return nullptr;
    if (made.size() == 1 && is_identity(made[0].second)) return made[0].first;
    auto* compound = new btCompoundShape(true, static_cast<int>(made.size()));
    for (const auto& m : made) compound->addChildShape(bt(m.second), m.first);
    return own(compound);
  }

  // Gives a collision object its surfaces (kept for the object's lifetime).
  void attach(btCollisionObject* o, std::unique_ptr<SurfaceSet> set) {
    set->finish();
    o->setUserPointer(set.get());
    surfaces.push_back(std::move(set));
  }

  void add_world_model(const WorldModelDesc& m);
  Eigen::Isometry3d dyn_model_pose(const DynModel& dm) const;
  // The dynamic model whose first link is dm's canonical link, as Gazebo 11's Model::LoadLinks picks it: dm's own
  // first link, or, for a model with no link of its own (it only holds nested models), the first link of its
  // first nested model that has one (nested models follow their parent in dyn_models, depth first). nullptr when
  // none of them has a dynamic link.
  const DynModel* canonical(const DynModel& dm) const;
  void build_rays();
  // Moves a static model's collisions (not its nested models) to `pose` [m], world frame.
  void place(StaticModel& sm, const Eigen::Isometry3d& pose);
  // Its ray bodies where the model is now.
  void place_rays(const StaticModel& sm);
};

}  // namespace physics
}  // namespace car_sim
