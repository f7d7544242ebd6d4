#include "island_world.hpp"

#include <BulletCollision/CollisionDispatch/btSimulationIslandManager.h>
#include <omp.h>

#include <algorithm>

namespace car_sim {
namespace physics {

namespace {

// [-] manifolds + constraints of all awake islands from which a step solves them on several threads
constexpr int kParallelWork = 32;

// The island a constraint belongs to (Bullet's rule: the island of its first body that has one).
int island_of(const btTypedConstraint* c) {
  const int a = c->getRigidBodyA().getIslandTag();
  return a >= 0 ? a : c->getRigidBodyB().getIslandTag();
}
int island_of(const btMultiBodyConstraint* c) { return c->getIslandIdA() >= 0 ? c->getIslandIdA() : c->getIslandIdB(); }

// [first, count) of the entries of `island` in an array sorted by island (Bullet sorts both constraint arrays so).
template <class T>
void range_of(const btAlignedObjectArray<T*>& sorted, int island, int& first, int& count) {
  const int n = sorted.size();
  int lo = 0, hi = n;
  while (lo < hi) {
    const int mid = (lo + hi) / 2;
    if (island_of(sorted[mid]) < island) lo = mid + 1; else hi = mid;
  }
  first = lo;
  while (hi < n && island_of(sorted[hi]) == island) ++hi;
  count = hi - lo;
}

}  // namespace

// Bullet's island manager calls this once per awake island, in increasing island order; it copies the island's
// bodies and manifolds (Bullet's arrays are reused for the next island) and finds its constraints.
struct IslandWorld::Collector : btSimulationIslandManager::IslandCallback {
  IslandWorld* w = nullptr;
  void processIsland(btCollisionObject** bodies, int num_bodies, btPersistentManifold** manifolds, int num_manifolds,
                     int island) override {
    Island s{};
    s.bodies = w->bodies_.size();
    s.num_bodies = num_bodies;
    for (int i = 0; i < num_bodies; ++i) w->bodies_.push_back(bodies[i]);
    s.manifolds = w->manifolds_.size();
    s.num_manifolds = num_manifolds;
    for (int i = 0; i < num_manifolds; ++i) w->manifolds_.push_back(manifolds[i]);
    if (island < 0) {
      // islands not split: one problem with everything
      s.num_constraints = w->m_sortedConstraints.size();
      s.num_mb_constraints = w->m_sortedMultiBodyConstraints.size();
    } else {
      range_of(w->m_sortedConstraints, island, s.constraints, s.num_constraints);
      range_of(w->m_sortedMultiBodyConstraints, island, s.mb_constraints, s.num_mb_constraints);
    }
    w->islands_.push_back(s);
  }
};

IslandWorld::IslandWorld(btDispatcher* dispatcher, btBroadphaseInterface* broadphase, SurfaceSolver* solver,
                         btCollisionConfiguration* config)
    : btMultiBodyDynamicsWorld(dispatcher, broadphase, solver, config), collector_(std::make_unique<Collector>()) {
  collector_->w = this;
  solvers_.push_back(solver);
  const int threads = std::max(1, omp_get_max_threads());
  for (int t = 1; t < threads; ++t) {
    own_.push_back(std::make_unique<SurfaceSolver>());
    solvers_.push_back(own_.back().get());
  }
}

IslandWorld::~IslandWorld() = default;

void IslandWorld::solve_island(SurfaceSolver& solver, const Island& s, const btContactSolverInfo& info) {
  btCollisionObject** bodies = s.num_bodies ? &bodies_[s.bodies] : nullptr;
  btPersistentManifold** manifolds = s.num_manifolds ? &manifolds_[s.manifolds] : nullptr;
  btTypedConstraint** constraints = s.num_constraints ? &m_sortedConstraints[s.constraints] : nullptr;
  btMultiBodyConstraint** mb = s.num_mb_constraints ? &m_sortedMultiBodyConstraints[s.mb_constraints] : nullptr;
  solver.solveMultiBodyGroup(bodies, s.num_bodies, manifolds, s.num_manifolds, constraints, s.num_constraints, mb,
                             s.num_mb_constraints, info, m_debugDrawer, getDispatcher());
}

// Bullet's step of the constraints (btMultiBodyDynamicsWorld::solveConstraints) with the islands solved here:
// the free accelerations and the sorted constraint arrays (Bullet's), every awake island as a problem of its own
// (here), then Bullet's joint-feedback pass and velocity update (its island callback then holds nothing to solve).
void IslandWorld::solveConstraints(btContactSolverInfo& info) {
  solveExternalForces(info);
  bodies_.resize(0);
  manifolds_.resize(0);
  islands_.clear();
  m_islandManager->buildAndProcessIslands(getDispatcher(), this, collector_.get());
  const int n = static_cast<int>(islands_.size());
  // Threads only for enough work to pay for waking them: a single car among resting boxes (about 20 manifolds
  // and constraints) stays on this thread, four cars and more go parallel.
  int work = 0;
  for (const Island& s : islands_) work += s.num_manifolds + s.num_constraints + s.num_mb_constraints;
  const int threads = work >= kParallelWork ? std::min(n, static_cast<int>(solvers_.size())) : 1;
  if (threads > 1) {
    // Which thread takes which island changes nothing: the solvers are identical and keep no state between
    // problems. Islands share only static objects (read) and Bullet's fixed solver body (one per solver).
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
    for (int i = 0; i < n; ++i) solve_island(*solvers_[omp_get_thread_num()], islands_[i], info);
  } else {
    for (int i = 0; i < n; ++i) solve_island(*solvers_[0], islands_[i], info);
  }
  solveInternalConstraints(info);
}

}  // namespace physics
}  // namespace car_sim
