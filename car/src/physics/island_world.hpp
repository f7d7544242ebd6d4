// Bullet's multibody world with its simulation islands solved one by one, on every core OpenMP offers (private to
// the core; docs/COMPAT-physics.md "Islands"). Bullet solves all awake islands in one batch on one thread. Here
// each island (a robot and what it touches, a pile of boxes) is its own constraint problem, solved by one of a set
// of identical solvers: an island's result depends on nothing outside it, so it is the same bit for bit whichever
// thread solves it and however many there are (OMP_NUM_THREADS=1 gives the same trajectory as 2). The work Bullet
// does body by body (Featherstone's free accelerations, the joint-feedback pass, the integrated positions) is done
// in each multibody's island's task, and the narrow phase of settled pairs on the same threads: each multibody's
// and each pair's arithmetic is Bullet's own, on its own data and a scratch buffer of the thread's, so it too is
// the same bit for bit on any thread.
#pragma once

#include <btBulletDynamicsCommon.h>
#include <BulletCollision/CollisionDispatch/btActivatingCollisionAlgorithm.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <LinearMath/btQuaternion.h>

#include <memory>
#include <vector>

#include "surface.hpp"

namespace car_sim {
namespace physics {

// A collision algorithm of car's whose manifold is made with it and whose processCollision writes only that manifold
// (BoxPlaneAlgorithm): the dispatcher treats its pairs as settled, as Bullet's convex-plane algorithm's.
class SettledAlgorithm : public btActivatingCollisionAlgorithm {
 public:
  using btActivatingCollisionAlgorithm::btActivatingCollisionAlgorithm;
  // false while its next processCollision may make or free algorithms or manifolds (a compound's changed shape, or
  // a child whose algorithm may)
  virtual bool settled() const { return true; }
};

// Whether an algorithm's processCollision writes only manifolds made before it (Bullet's convex-plane algorithm, a
// settled SettledAlgorithm): its pair may collide on any thread.
bool writes_own_manifold(const btCollisionAlgorithm* a);

// Bullet's dispatcher, with the narrow phase of the pairs that can no longer allocate on the OpenMP threads: a
// convex shape or a compound of convex shapes on a static plane whose collision algorithms (and so their
// manifolds) exist, Bullet's convex-plane algorithm or a SettledAlgorithm (car's configuration gives every shape
// on a plane one of those). Every other pair is processed first, on the calling thread, in Bullet's order, so manifolds are
// made and freed in Bullet's order; each pair writes only its own manifolds, so the contacts are Bullet's bit for
// bit on any number of threads.
class IslandDispatcher : public btCollisionDispatcher {
 public:
  explicit IslandDispatcher(btCollisionConfiguration* config);
  void dispatchAllCollisionPairs(btOverlappingPairCache* pairs, const btDispatcherInfo& info,
                                 btDispatcher* dispatcher) override;

 private:
  int threads_;
  std::vector<btBroadphasePair*> settled_;
};

class IslandWorld : public btMultiBodyDynamicsWorld, public InverseMassSource {
 public:
  // `solver` solves on the calling thread; each other OpenMP thread gets a SurfaceSolver of its own.
  IslandWorld(btDispatcher* dispatcher, btBroadphaseInterface* broadphase, SurfaceSolver* solver,
              btCollisionConfiguration* config);
  ~IslandWorld() override;

  // How every solver of this world sets up its rows.
  void set_row_setup(RowSetup rows);
  // Whether predictUnconstraintMotion and updateAabbs reuse an object's unchanged results (Prediction, Box).
  void set_reuse_at_rest(bool on) { reuse_ = on; }
  // Whether islands, manifolds and constraints are sorted by car's copy of Bullet's sort (IslandSort) or Bullet's.
  void set_own_island_sort(bool on) { own_sort_ = on; }

  // Bullet's, with the multibodies integrated in their islands' tasks, or on the OpenMP threads.
  void integrateTransforms(btScalar dt) override;

  // Bullet's, without the multibodies' predicted transforms when no rigid body sweeps (CCD): those transforms
  // (btMultiBody::predictPositionsMultiDof, the colliders' interpolation transforms) are read by nothing else.
  void predictUnconstraintMotion(btScalar dt) override;

  // Bullet's, except that a collider whose bounding box would be computed from the same inputs as last step
  // (shape, transforms, thresholds: a static shape, a sleeping object) gets last step's box again. The box still
  // goes to the broad phase every step, as in Bullet, so the broad phase's order is Bullet's.
  void updateAabbs() override;

  // The mass matrix mb's free motion built and factored this step (free_motion), for the rows.
  const InverseMass* built(const btMultiBody* mb) const override;

 protected:
  void solveConstraints(btContactSolverInfo& info) override;

 private:
  // One island's share of the step: ranges into the flat arrays below.
  struct Island {
    int bodies, num_bodies;
    int manifolds, num_manifolds;
    int constraints, num_constraints;  // into m_sortedConstraints
    int mb_constraints, num_mb_constraints;  // into m_sortedMultiBodyConstraints
    int mbs, num_mbs;  // into island_mbs_
    int tag;           // Bullet's island id (-1: islands not split)
  };
  struct Collector;
  // One thread's scratch buffers for Bullet's multibody calls (Bullet's world keeps one set, for one thread).
  struct alignas(64) Scratch {
    btAlignedObjectArray<btScalar> r;
    btAlignedObjectArray<btVector3> v;
    btAlignedObjectArray<btMatrix3x3> m;
    btAlignedObjectArray<btQuaternion> world_to_local;
    btAlignedObjectArray<btVector3> local_origin;
  };

  void solve_island(SurfaceSolver& solver, const Island& island, const btContactSolverInfo& info);
  void collect_islands();
  bool assign_multibodies();
  void free_motion(int body, Scratch& s, const btContactSolverInfo& info);
  void constrained_motion(int body, Scratch& s, const btContactSolverInfo& info);
  void island_task(int k, SurfaceSolver& solver, Scratch& s, const btContactSolverInfo& info);
  void integrate(btMultiBody* b, Scratch& s, btScalar dt);
  bool ccd_bodies() const;
  void predict_rigid_bodies(btScalar dt);

  // A rigid body's predicted transform (btRigidBody::predictIntegratedTransform into its interpolation transform)
  // and what it came from. At zero velocity Bullet's damping changes no bit, so when the body's transform, its
  // zero velocities, dt and the prediction itself are what they were, predicting again is skipped: the same
  // function of the same bits. That is every sleeping object of a world at each step.
  struct Prediction {
    const btRigidBody* body = nullptr;
    btTransform from, to;
    btScalar dt = 0;
  };
  std::vector<Prediction> predictions_;  // per m_nonStaticRigidBodies index
  // A collider's last bounding box (btCollisionWorld::updateSingleAabb's, thresholds added) and its inputs.
  struct Box {
    const btCollisionObject* object = nullptr;
    const btCollisionShape* shape = nullptr;
    btTransform world, interpolation;
    btScalar threshold = 0;
    bool swept = false;  // the interpolation transform's box is part of it (Bullet's CCD rule)
    bool fixed = false;  // a static object (Bullet passes its box whatever its size)
    btVector3 min, max;
  };
  std::vector<Box> boxes_;  // per collision object index
  // Runs f(body, scratch) for every multibody, on one thread or on all (same result bit for bit).
  template <class F>
  void for_each_multibody(F&& f);

  std::vector<SurfaceSolver*> solvers_;  // [0] the world's own, then one per further thread
  std::vector<std::unique_ptr<SurfaceSolver>> own_;
  std::vector<Scratch> scratch_;  // one per solver (thread)
  std::unique_ptr<Collector> collector_;
  btAlignedObjectArray<btCollisionObject*> bodies_;
  btAlignedObjectArray<btPersistentManifold*> manifolds_;
  std::vector<Island> islands_;
  Island rest_{};                  // the multibodies in no awake island
  std::vector<int> island_of_tag_;  // Bullet's island id -> index into islands_, or -1
  // the constraints' sort by island, as Bullet's (island_world.cpp)
  struct ConstraintSort;
  std::unique_ptr<ConstraintSort> constraint_sort_;
  std::vector<char> awake_;         // per multibody: awake before the islands were built
  std::vector<int> owner_;          // per multibody: its island's index (islands_.size(): none)
  std::vector<int> island_mbs_;     // multibody indices grouped by island
  std::vector<int> island_count_;
  // Per multibody (its user index is its index in m_multiBodies): whether its free motion comes from its factored
  // mass matrix this step (no constraint of Bullet's reads the caches of Bullet's pass), and that matrix.
  struct FreeMotion {
    InverseMass inverse;
    uint64_t stamp = 0;  // the step it was built at (stamp_), if ok
    bool ok = false;
  };
  std::vector<char> factored_;
  std::vector<FreeMotion> free_;
  uint64_t stamp_ = 0;  // solveConstraints calls so far
  void mark_factored(const btContactSolverInfo& info);
  bool reuse_ = true;
  bool own_sort_ = true;
  bool integrated_ = false;  // this step's islands' tasks integrated the multibodies
};

}  // namespace physics
}  // namespace car_sim
