// Bullet's multibody world with its simulation islands solved one by one, on every core OpenMP offers (private to
// the core; docs/COMPAT-physics.md "Islands"). Bullet solves all awake islands in one batch on one thread. Here
// each island (a robot and what it touches, a pile of boxes) is its own constraint problem, solved by one of a set
// of identical solvers: an island's result depends on nothing outside it, so it is the same bit for bit whichever
// thread solves it and however many there are (OMP_NUM_THREADS=1 gives the same trajectory as 2).
#pragma once

#include <btBulletDynamicsCommon.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>

#include <memory>
#include <vector>

#include "surface.hpp"

namespace car_sim {
namespace physics {

class IslandWorld : public btMultiBodyDynamicsWorld {
 public:
  // `solver` solves on the calling thread; each other OpenMP thread gets a SurfaceSolver of its own.
  IslandWorld(btDispatcher* dispatcher, btBroadphaseInterface* broadphase, SurfaceSolver* solver,
              btCollisionConfiguration* config);
  ~IslandWorld() override;

 protected:
  void solveConstraints(btContactSolverInfo& info) override;

 private:
  // One island's share of the step: ranges into the flat arrays below.
  struct Island {
    int bodies, num_bodies;
    int manifolds, num_manifolds;
    int constraints, num_constraints;  // into m_sortedConstraints
    int mb_constraints, num_mb_constraints;  // into m_sortedMultiBodyConstraints
  };
  struct Collector;

  void solve_island(SurfaceSolver& solver, const Island& island, const btContactSolverInfo& info);

  std::vector<SurfaceSolver*> solvers_;  // [0] the world's own, then one per further thread
  std::vector<std::unique_ptr<SurfaceSolver>> own_;
  std::unique_ptr<Collector> collector_;
  btAlignedObjectArray<btCollisionObject*> bodies_;
  btAlignedObjectArray<btPersistentManifold*> manifolds_;
  std::vector<Island> islands_;
};

}  // namespace physics
}  // namespace car_sim
