// Car's collision algorithms for a shape against a plane (a box, a sphere, another convex shape, a compound) and
// the collision configuration that hands them to Bullet's dispatcher; the rest is Bullet's.
#include "plane_collision.hpp"

#include <BulletCollision/CollisionDispatch/btActivatingCollisionAlgorithm.h>
#include <BulletCollision/CollisionDispatch/btConvexPlaneCollisionAlgorithm.h>

#include <cmath>
#include <vector>

#include "island_world.hpp"

namespace car_sim {
namespace physics {

namespace {

// Whether a convex shape is clearly beyond a plane's contact distance: its bounding sphere (centre in the shape's
// frame, radius [m]) lies above the plane by more than the manifold's contact breaking threshold and the result's
// closest-point distance, by a margin for the rounding of the two routes to a distance.
bool clearly_apart(const btCollisionObjectWrapper* convex, const btCollisionObjectWrapper* plane,
                   const btVector3& centre, btScalar radius, const btPersistentManifold* manifold,
                   const btManifoldResult* out) {
  const auto* ground = static_cast<const btStaticPlaneShape*>(plane->getCollisionShape());
  const btTransform& tp = plane->getWorldTransform();
  const btVector3 c = convex->getWorldTransform()(centre);  // world
  const btScalar offset = ground->getPlaneConstant();
  // [m] the sphere's lowest point above the plane, along its normal
  const btScalar gap = (tp.getBasis() * ground->getPlaneNormal()).dot(c - tp.getOrigin()) - offset - radius;
  const btScalar limit = manifold->getContactBreakingThreshold() + out->m_closestPointDistanceThreshold;
  // (sums of magnitudes bound the lengths: no square roots)
  const btVector3 ca = c.absolute(), oa = tp.getOrigin().absolute();
  const btScalar slack = 1e-9 * (ca[0] + ca[1] + ca[2] + oa[0] + oa[1] + oa[2] + std::abs(offset) + radius) + 1e-9;
  return gap > limit + slack;
}

// Bullet's convex-plane algorithm (a cylinder, capsule, cone or hull on a plane), skipped while its manifold is empty
// and the shape is clearly apart from the plane: Bullet's pass would find no point there and leave the manifold
// empty, so the state is the same bit for bit, without its two transform products and support query. A robot's
// body parts above the ground (a lidar, a camera mount in the base's compound) spend every step so.
class ConvexPlaneAlgorithm : public btConvexPlaneCollisionAlgorithm {
 public:
  ConvexPlaneAlgorithm(const btCollisionAlgorithmConstructionInfo& ci, const btCollisionObjectWrapper* a,
                       const btCollisionObjectWrapper* b, bool swapped, int iterations, int threshold)
      : btConvexPlaneCollisionAlgorithm(nullptr, ci, a, b, swapped, iterations, threshold), swapped_(swapped) {
    btManifoldArray own;
    getAllContactManifolds(own);
    manifold_ = own.size() ? own[0] : nullptr;
    (swapped ? b : a)->getCollisionShape()->getBoundingSphere(centre_, radius_);
  }
  void processCollision(const btCollisionObjectWrapper* a, const btCollisionObjectWrapper* b,
                        const btDispatcherInfo& info, btManifoldResult* out) override {
    if (manifold_ && !manifold_->getNumContacts() &&
        clearly_apart(swapped_ ? b : a, swapped_ ? a : b, centre_, radius_, manifold_, out)) {
      out->setPersistentManifold(manifold_);
      return;
    }
    btConvexPlaneCollisionAlgorithm::processCollision(a, b, info, out);
  }

  // Bullet's create function's settings (perturbation iterations and threshold), car's algorithm
  struct CreateFunc : btConvexPlaneCollisionAlgorithm::CreateFunc {
    btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                   const btCollisionObjectWrapper* a,
                                                   const btCollisionObjectWrapper* b) override {
      void* mem = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(ConvexPlaneAlgorithm));
      return new (mem) ConvexPlaneAlgorithm(ci, a, b, m_swapped, m_numPerturbationIterations,
                                            m_minimumPointsPerturbationThreshold);
    }
  };

 private:
  btPersistentManifold* manifold_ = nullptr;
  bool swapped_;
  btVector3 centre_;  // [m], the shape's frame
  btScalar radius_ = 0;
};

// Bullet's create function for one of car's algorithms A(ci, a, b, swapped).
template <class A>
struct CreateFuncOf : btCollisionAlgorithmCreateFunc {
  btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                 const btCollisionObjectWrapper* a,
                                                 const btCollisionObjectWrapper* b) override {
    void* mem = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(A));
    return new (mem) A(ci, a, b, m_swapped);
  }
};

// One of car's algorithms for a shape against a plane: it owns one manifold, made with it (when the pair may
// collide), so the dispatcher counts its pair as settled; no time of impact (a plane sweeps nothing).
template <class Derived>
class PlaneManifoldAlgorithm : public SettledAlgorithm {
 public:
  PlaneManifoldAlgorithm(const btCollisionAlgorithmConstructionInfo& ci, const btCollisionObjectWrapper* a,
                         const btCollisionObjectWrapper* b, bool swapped)
      : SettledAlgorithm(ci, a, b), swapped_(swapped) {
    const btCollisionObject* shape = (swapped ? b : a)->getCollisionObject();
    const btCollisionObject* plane = (swapped ? a : b)->getCollisionObject();
    if (m_dispatcher->needsCollision(shape, plane)) manifold_ = m_dispatcher->getNewManifold(shape, plane);
  }
  ~PlaneManifoldAlgorithm() override {
    if (manifold_) m_dispatcher->releaseManifold(manifold_);
  }
  btScalar calculateTimeOfImpact(btCollisionObject*, btCollisionObject*, const btDispatcherInfo&,
                                 btManifoldResult*) override {
    return btScalar(1);
  }
  void getAllContactManifolds(btManifoldArray& manifolds) override {
    if (manifold_) manifolds.push_back(manifold_);
  }

  using CreateFunc = CreateFuncOf<Derived>;

 protected:
  btPersistentManifold* manifold_ = nullptr;
  bool swapped_;
};

// A sphere against a plane: one point, the sphere's lowest along the plane's normal, as ODE's dCollideSpherePlane
// and Bullet's convex-plane algorithm find it; Bullet's turns the plane into the sphere's frame and the point back
// (two transform products and a support query) to get the centre less the radius along the normal. Contact within
// the manifold's breaking threshold, as Bullet's; the manifold refreshed as Bullet's (docs/COMPAT-physics.md
// "Contact points").
class SpherePlaneAlgorithm : public PlaneManifoldAlgorithm<SpherePlaneAlgorithm> {
 public:
  using PlaneManifoldAlgorithm::PlaneManifoldAlgorithm;

  void processCollision(const btCollisionObjectWrapper* a, const btCollisionObjectWrapper* b, const btDispatcherInfo&,
                        btManifoldResult* out) override {
    if (!manifold_) return;
    const btCollisionObjectWrapper* sphere = swapped_ ? b : a;
    const btCollisionObjectWrapper* plane = swapped_ ? a : b;
    const auto* shape = static_cast<const btSphereShape*>(sphere->getCollisionShape());
    const auto* ground = static_cast<const btStaticPlaneShape*>(plane->getCollisionShape());
    const btTransform& tp = plane->getWorldTransform();
    const btVector3 normal = tp.getBasis() * ground->getPlaneNormal();  // world
    // the sphere's lowest point (world) and its distance from the plane [m] (negative: below)
    const btVector3 low = sphere->getWorldTransform().getOrigin() - normal * shape->getRadius();
    const btScalar distance = normal.dot(low - tp.getOrigin()) - ground->getPlaneConstant();
    out->setPersistentManifold(manifold_);
    if (distance < manifold_->getContactBreakingThreshold() + out->m_closestPointDistanceThreshold)
      out->addContactPoint(normal, low - normal * distance, distance);
    if (manifold_->getNumContacts()) out->refreshContactPoints();
  }
};

// A box against a plane as ODE's dCollideBoxPlane: every corner of the box within the manifold's contact
// breaking distance of the plane is a contact point, every step, at the corner's own distance [m] (negative:
// below). Bullet's plane algorithm adds one point per step (the deepest corner), and its multipoint option only
// while the manifold holds few points, so the other corners' points go stale as the box slides and are dropped
// together (a sliding box then stands on one corner for a step and rocks); here each corner's point is replaced
// every step (the manifold matches it to its cached point, keeping the warm start) and the manifold keeps at most
// 4 (docs/COMPAT-physics.md "Contact points").
class BoxPlaneAlgorithm : public PlaneManifoldAlgorithm<BoxPlaneAlgorithm> {
 public:
  BoxPlaneAlgorithm(const btCollisionAlgorithmConstructionInfo& ci, const btCollisionObjectWrapper* a,
                    const btCollisionObjectWrapper* b, bool swapped)
      : PlaneManifoldAlgorithm(ci, a, b, swapped) {
    (swapped ? b : a)->getCollisionShape()->getBoundingSphere(centre_, radius_);
  }

  void processCollision(const btCollisionObjectWrapper* a, const btCollisionObjectWrapper* b, const btDispatcherInfo&,
                        btManifoldResult* out) override {
    if (!manifold_) return;
    const btCollisionObjectWrapper* box = swapped_ ? b : a;
    const btCollisionObjectWrapper* plane = swapped_ ? a : b;
    // no corner can be near (the same empty manifold as the corners' test gives)
    if (!manifold_->getNumContacts() && clearly_apart(box, plane, centre_, radius_, manifold_, out)) {
      out->setPersistentManifold(manifold_);
      return;
    }
    const auto* shape = static_cast<const btBoxShape*>(box->getCollisionShape());
    const auto* ground = static_cast<const btStaticPlaneShape*>(plane->getCollisionShape());
    // the plane's normal and offset [m] in its own frame; the box's pose in the plane's frame
    const btVector3& n = ground->getPlaneNormal();
    const btScalar offset = ground->getPlaneConstant();
    const btTransform box_in_plane = plane->getWorldTransform().inverse() * box->getWorldTransform();
    const btVector3 normal = plane->getWorldTransform().getBasis() * n;  // world
    out->setPersistentManifold(manifold_);
    for (int i = 0; i < shape->getNumVertices(); ++i) {
      btVector3 corner;
      shape->getVertex(i, corner);  // box frame, half extents with margin: the true box
      const btVector3 c = box_in_plane(corner);
      const btScalar distance = n.dot(c) - offset;
      if (distance >= manifold_->getContactBreakingThreshold()) continue;
      // the point on the plane under the corner, world
      out->addContactPoint(normal, plane->getWorldTransform() * (c - distance * n), distance);
    }
    if (manifold_->getNumContacts()) out->refreshContactPoints();
  }

 private:
  btVector3 centre_;  // [m], bounding sphere in the box's frame
  btScalar radius_ = 0;
};

// A compound shape (a robot body of several collisions) against a plane: Bullet's btCompoundCollisionAlgorithm
// for the case where the other shape's bounding box covers every child, as a plane's does: every child has its
// algorithm (a plane one above) for as long as the shape is unchanged, so there is no tree query for overlapping
// children, no bounding box per child and step, and no pass to drop children that stopped overlapping. Per step,
// as Bullet's: the children's manifolds that hold points are refreshed, then each child collides at its world pose
// with the result's shape identifiers set to its index (car's surface rules read them).
class CompoundPlaneAlgorithm : public SettledAlgorithm {
 public:
  CompoundPlaneAlgorithm(const btCollisionAlgorithmConstructionInfo& ci, const btCollisionObjectWrapper* a,
                         const btCollisionObjectWrapper* b, bool swapped)
      : SettledAlgorithm(ci, a, b), swapped_(swapped) {
    make_children(a, b);
  }
  ~CompoundPlaneAlgorithm() override { free_children(); }

  bool settled() const override {
    if (!unchanged() || !children_settled_) return false;
    for (const btCollisionAlgorithm* child : nested_)
      if (!writes_own_manifold(child)) return false;
    return true;
  }

  void processCollision(const btCollisionObjectWrapper* a, const btCollisionObjectWrapper* b,
                        const btDispatcherInfo& info, btManifoldResult* out) override {
    const btCollisionObjectWrapper* body = swapped_ ? b : a;
    const btCollisionObjectWrapper* plane = swapped_ ? a : b;
    if (!unchanged()) {
      free_children();
      make_children(a, b);
    }
    for (btCollisionAlgorithm* child : children_) {
      manifolds_.resize(0);
      child->getAllContactManifolds(manifolds_);
      for (int m = 0; m < manifolds_.size(); ++m)
        if (manifolds_[m]->getNumContacts()) {
          out->setPersistentManifold(manifolds_[m]);
          out->refreshContactPoints();
          out->setPersistentManifold(nullptr);
        }
    }
    const btTransform& pose = body->getWorldTransform();
    for (int i = 0; i < static_cast<int>(children_.size()); ++i) {
      const btTransform& in_body = compound_->getChildTransform(i);
      btTransform pre = in_body;
      if (body->m_preTransform) pre = pre * *body->m_preTransform;
      // (the wrapper keeps references to both transforms)
      const btTransform world = pose * in_body;
      const btCollisionObjectWrapper child(body, compound_->getChildShape(i), body->getCollisionObject(), world, pre,
                                           -1, i);
      const bool first = out->getBody0Internal() == body->getCollisionObject();
      const btCollisionObjectWrapper* kept = first ? out->getBody0Wrap() : out->getBody1Wrap();
      if (first) {
        out->setBody0Wrap(&child);
        out->setShapeIdentifiersA(-1, i);
      } else {
        out->setBody1Wrap(&child);
        out->setShapeIdentifiersB(-1, i);
      }
      children_[i]->processCollision(&child, plane, info, out);
      if (first)
        out->setBody0Wrap(kept);
      else
        out->setBody1Wrap(kept);
    }
  }
  btScalar calculateTimeOfImpact(btCollisionObject*, btCollisionObject*, const btDispatcherInfo&,
                                 btManifoldResult*) override {
    // every child's against a plane is 1 (Bullet's convex-plane algorithm's), so the compound's is
    return btScalar(1);
  }
  void getAllContactManifolds(btManifoldArray& manifolds) override {
    for (btCollisionAlgorithm* child : children_) child->getAllContactManifolds(manifolds);
  }

  using CreateFunc = CreateFuncOf<CompoundPlaneAlgorithm>;

 private:
  // the shape as its children's algorithms were made for it
  bool unchanged() const { return compound_->getUpdateRevision() == revision_; }
  void make_children(const btCollisionObjectWrapper* a, const btCollisionObjectWrapper* b) {
    const btCollisionObjectWrapper* body = swapped_ ? b : a;
    const btCollisionObjectWrapper* plane = swapped_ ? a : b;
    compound_ = static_cast<const btCompoundShape*>(body->getCollisionShape());
    revision_ = compound_->getUpdateRevision();
    children_.resize(compound_->getNumChildShapes());
    for (int i = 0; i < static_cast<int>(children_.size()); ++i) {
      const btTransform world = body->getWorldTransform() * compound_->getChildTransform(i);
      const btCollisionObjectWrapper child(body, compound_->getChildShape(i), body->getCollisionObject(), world, -1, i);
      children_[i] = m_dispatcher->findAlgorithm(&child, plane, nullptr, BT_CONTACT_POINT_ALGORITHMS);
    }
    // whether the children write only their own manifolds, found once: a child's kind does not change while it
    // lives, except a nested compound's (its own shape may change), which settled() asks each time
    children_settled_ = true;
    nested_.clear();
    for (btCollisionAlgorithm* child : children_) {
      if (dynamic_cast<CompoundPlaneAlgorithm*>(child))
        nested_.push_back(child);
      else if (!writes_own_manifold(child))
        children_settled_ = false;
    }
  }
  void free_children() {
    for (btCollisionAlgorithm* child : children_) {
      child->~btCollisionAlgorithm();
      m_dispatcher->freeCollisionAlgorithm(child);
    }
    children_.clear();
  }

  bool swapped_;
  const btCompoundShape* compound_ = nullptr;
  int revision_ = 0;
  std::vector<btCollisionAlgorithm*> children_;  // per child shape
  bool children_settled_ = false;                // every child but the nested compounds writes its own manifold
  std::vector<const btCollisionAlgorithm*> nested_;  // the children that are compounds on the plane
  btManifoldArray manifolds_;
};

// Bullet's collision algorithms, except a shape against a plane: a box (BoxPlaneAlgorithm), a sphere
// (SpherePlaneAlgorithm), another convex shape (ConvexPlaneAlgorithm, Bullet's with its early exit), a compound
// (CompoundPlaneAlgorithm).
class CollisionConfig : public btDefaultCollisionConfiguration {
 public:
  CollisionConfig() {
    plane_box_.m_swapped = true;
    plane_sphere_.m_swapped = true;
    plane_convex_.m_swapped = true;
    plane_compound_.m_swapped = true;
  }
  btCollisionAlgorithmCreateFunc* getCollisionAlgorithmCreateFunc(int a, int b) override {
    if (b == STATIC_PLANE_PROXYTYPE) {
      if (a == BOX_SHAPE_PROXYTYPE) return &box_plane_;
      if (a == SPHERE_SHAPE_PROXYTYPE) return &sphere_plane_;
      if (btBroadphaseProxy::isConvex(a)) return &convex_plane_;
      if (a == COMPOUND_SHAPE_PROXYTYPE) return &compound_plane_;
    }
    if (a == STATIC_PLANE_PROXYTYPE) {
      if (b == BOX_SHAPE_PROXYTYPE) return &plane_box_;
      if (b == SPHERE_SHAPE_PROXYTYPE) return &plane_sphere_;
      if (btBroadphaseProxy::isConvex(b)) return &plane_convex_;
      if (b == COMPOUND_SHAPE_PROXYTYPE) return &plane_compound_;
    }
    return btDefaultCollisionConfiguration::getCollisionAlgorithmCreateFunc(a, b);
  }

 private:
  BoxPlaneAlgorithm::CreateFunc box_plane_, plane_box_;
  SpherePlaneAlgorithm::CreateFunc sphere_plane_, plane_sphere_;
  ConvexPlaneAlgorithm::CreateFunc convex_plane_, plane_convex_;
  CompoundPlaneAlgorithm::CreateFunc compound_plane_, plane_compound_;
};

}  // namespace

std::unique_ptr<btCollisionConfiguration> make_collision_config() {
  return std::make_unique<CollisionConfig>();
}

}  // namespace physics
}  // namespace car_sim
