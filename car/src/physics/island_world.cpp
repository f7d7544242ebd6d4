#include "island_world.hpp"

#include <BulletCollision/CollisionDispatch/btConvexPlaneCollisionAlgorithm.h>
#include <BulletCollision/CollisionDispatch/btSimulationIslandManager.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyInplaceSolverIslandCallback.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include "car_sim/parallel.hpp"

#include <algorithm>
#include <cstring>
#include <new>
#include <typeinfo>
#include <vector>

namespace car_sim {
namespace physics {

namespace {

// [-] manifolds + constraints of all awake islands from which a step solves them on several threads
constexpr int kParallelWork = 32;
// [-] multibodies from which an island's work (about 25 us per car and step) runs on several threads
constexpr int kParallelBodies = 4;
// [-] multibodies from which the integrated positions (about 1 us per car and step) do, when not in the tasks
constexpr int kParallelPositions = 16;
// [-] collision objects from which their bounding boxes (about 0.3 us each) are found on several threads
constexpr int kParallelBoxes = 128;

// Bullet's test (btMultiBodyDynamicsWorld): a multibody with any collider in a sleeping island is asleep.
bool sleeping(const btMultiBody* b) {
  if (b->getBaseCollider() && b->getBaseCollider()->getActivationState() == ISLAND_SLEEPING) return true;
  for (int i = 0; i < b->getNumLinks(); ++i)
    if (b->getLink(i).m_collider && b->getLink(i).m_collider->getActivationState() == ISLAND_SLEEPING) return true;
  return false;
}

// The island a constraint belongs to (Bullet's rule: the island of its first body that has one).
int island_of(const btTypedConstraint* c) {
  const int a = c->getRigidBodyA().getIslandTag();
  return a >= 0 ? a : c->getRigidBodyB().getIslandTag();
}
int island_of(const btMultiBodyConstraint* c) { return c->getIslandIdA() >= 0 ? c->getIslandIdA() : c->getIslandIdB(); }

// The island of a manifold (Bullet's getIslandId: its first body's, if that has one).
int island_of(const btPersistentManifold* m) {
  const int a = m->getBody0()->getIslandTag();
  return a >= 0 ? a : m->getBody1()->getIslandTag();
}

// Bullet's btAlignedObjectArray::quickSortInternal on (island, item) pairs: the same partitions, so items of one
// island end in the same order as Bullet's sort leaves them (the sort is not stable, and that order is the order
// of the solver's rows); the islands are found once, not twice per comparison through calls.
template <class T>
void quicksort_keyed(std::vector<std::pair<int, T>>& a, int lo, int hi) {
  int i = lo, j = hi;
  const int x = a[(lo + hi) / 2].first;
  do {
    while (a[i].first < x) i++;
    while (x < a[j].first) j--;
    if (i <= j) {
      std::swap(a[i], a[j]);
      i++;
      j--;
    }
  } while (i <= j);
  if (lo < j) quicksort_keyed(a, lo, j);
  if (i < hi) quicksort_keyed(a, i, hi);
}

// Bullet's quicksort by island of (island, item) pairs, in place. The order is a function of the input alone, so
// an input equal to the last one (robots driving on without new contacts: the same objects, manifolds and islands,
// step after step) takes the last order without sorting.
template <class T>
class KeyedSort {
 public:
  void sort(std::vector<std::pair<int, T>>& keyed) {
    const int n = static_cast<int>(keyed.size());
    if (n < 2) return;
    if (keyed != last_in_) {
      last_in_ = keyed;
      quicksort_keyed(keyed, 0, n - 1);
      last_out_ = keyed;
    } else {
      keyed = last_out_;
    }
  }

 private:
  std::vector<std::pair<int, T>> last_in_, last_out_;
};

// Sorts arrays by island as Bullet's quickSort with its island predicate does (btSortConstraintOnIslandPredicate2,
// btSortMultiBodyConstraintOnIslandPredicate, btPersistentManifoldSortPredicate).
template <class T>
class IslandSort {
 public:
  void sort(btAlignedObjectArray<T*>& array) {
    const int n = array.size();
    keyed_.resize(n);
    for (int i = 0; i < n; ++i) keyed_[i] = {island_of(array[i]), array[i]};
    sort_.sort(keyed_);
    for (int i = 0; i < n; ++i) array[i] = keyed_[i].second;
  }
  // the island of entry i of the array as the last sort left it
  int island(int i) const { return keyed_[i].first; }
  // [first, count) of the entries of `island` in the array as the last sort left it
  void range(int island, int& first, int& count) const {
    const auto lo = std::lower_bound(keyed_.begin(), keyed_.end(), island,
                                     [](const std::pair<int, T*>& e, int id) { return e.first < id; });
    auto hi = lo;
    while (hi != keyed_.end() && hi->first == island) ++hi;
    first = static_cast<int>(lo - keyed_.begin());
    count = static_cast<int>(hi - lo);
  }

 private:
  std::vector<std::pair<int, T*>> keyed_;
  KeyedSort<T*> sort_;
};

// btUnionFind::sortIslands: each element's island (its root, with Bullet's path compression), then the elements
// (island, collision object index) sorted by island with Bullet's quicksort (btUnionFindElementSortPredicate).
class ElementSort {
 public:
  void sort(btUnionFind& uf) {
    const int n = uf.getNumElements();
    keyed_.resize(n);
    for (int i = 0; i < n; ++i) {
      uf.getElement(i).m_id = uf.find(i);
#ifndef STATIC_SIMULATION_ISLAND_OPTIMIZATION
      uf.getElement(i).m_sz = i;
#endif
      keyed_[i] = {uf.getElement(i).m_id, uf.getElement(i).m_sz};
    }
    sort_.sort(keyed_);
    for (int i = 0; i < n; ++i) {
      uf.getElement(i).m_id = keyed_[i].first;
      uf.getElement(i).m_sz = keyed_[i].second;
    }
  }

 private:
  std::vector<std::pair<int, int>> keyed_;
  KeyedSort<int> sort_;
};

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

// The island of a multibody: that of its first non-static collider (Bullet unites them all), -1 if none.
int island_tag(const btMultiBody* b) {
  const btCollisionObject* c = nullptr;
  if (b->getBaseCollider() && !b->getBaseCollider()->isStaticOrKinematicObject()) c = b->getBaseCollider();
  for (int l = 0; !c && l < b->getNumLinks(); ++l)
    if (b->getLink(l).m_collider && !b->getLink(l).m_collider->isStaticOrKinematicObject()) c = b->getLink(l).m_collider;
  return c ? c->getIslandTag() : -1;
}

// [-] settled pairs from which the narrow phase runs on several threads (a car on the ground has about eight)
constexpr int kParallelPairs = 32;

// A pair whose narrow phase makes and frees nothing: its algorithm exists and writes only manifolds made before
// (writes_own_manifold: Bullet's convex-on-plane one, car's plane algorithms, a compound's against a plane among
// them while its shape is unchanged).
bool settled(const btBroadphasePair& p) { return p.m_algorithm && writes_own_manifold(p.m_algorithm); }

// The same bits in the nine entries of the basis and the three of the origin (not the padding).
bool same(const btTransform& a, const btTransform& b) {
  for (int r = 0; r < 3; ++r)
    if (std::memcmp(a.getBasis()[r].m_floats, b.getBasis()[r].m_floats, 3 * sizeof(btScalar)) != 0) return false;
  return std::memcmp(a.getOrigin().m_floats, b.getOrigin().m_floats, 3 * sizeof(btScalar)) == 0;
}

// All three components +0.0, bit for bit (what Bullet writes into a sleeping body's velocities).
bool positive_zero(const btVector3& v) {
  static const btScalar zero[3] = {0, 0, 0};
  return std::memcmp(v.m_floats, zero, sizeof zero) == 0;
}

// Whether btCollisionDispatcher::needsCollision refuses the pair whatever the objects' activation: either object's
// checkCollideWith refuses the other. car's colliders decide that at spawn (SurfaceCollider: one robot's bodies,
// self_collide, the joint between them) and nothing changes it later, so the answer is kept in the pair's
// m_internalTmpValue (0 when Bullet makes the pair; it travels with the pair when Bullet moves it in the array):
// 1 collides, 2 never. The pair's algorithm, if any, is then never called, as in Bullet.
bool never_collides(btBroadphasePair& p) {
  if (p.m_internalTmpValue == 0) {
    const auto* a = static_cast<const btCollisionObject*>(p.m_pProxy0->m_clientObject);
    const auto* b = static_cast<const btCollisionObject*>(p.m_pProxy1->m_clientObject);
    p.m_internalTmpValue = a->checkCollideWith(b) && b->checkCollideWith(a) ? 1 : 2;
  }
  return p.m_internalTmpValue == 2;
}

}  // namespace

bool writes_own_manifold(const btCollisionAlgorithm* a) {
  // The kind of each dynamic type found once per thread: two dynamic_casts per pair and step (each comparing type
  // names along the class chain) cost the dispatcher's serial loop more than a settled pair's narrow phase.
  enum Kind { kOther, kConvexPlane, kSettled };
  struct Seen {
    const std::type_info* type;
    Kind kind;
  };
  thread_local std::vector<Seen> seen;
  const std::type_info* type = &typeid(*a);
  Kind kind = kOther;
  auto it = std::find_if(seen.begin(), seen.end(), [&](const Seen& s) { return s.type == type; });
  if (it != seen.end()) {
    kind = it->kind;
  } else {
    if (dynamic_cast<const btConvexPlaneCollisionAlgorithm*>(a))
      kind = kConvexPlane;
    else if (dynamic_cast<const SettledAlgorithm*>(a))
      kind = kSettled;
    seen.push_back({type, kind});
  }
  if (kind == kConvexPlane) return true;
  return kind == kSettled && static_cast<const SettledAlgorithm*>(a)->settled();
}

IslandDispatcher::IslandDispatcher(btCollisionConfiguration* config)
    : btCollisionDispatcher(config), threads_(parallel_threads()) {}

// Bullet's dispatch (btCollisionPairCallback over the pair array, in order, through the near callback), split in
// two: the unsettled pairs here in array order, then the settled ones on the threads.
void IslandDispatcher::dispatchAllCollisionPairs(btOverlappingPairCache* pairs, const btDispatcherInfo& info,
                                                 btDispatcher* dispatcher) {
  if (threads_ < 2 || info.m_deterministicOverlappingPairs || getNearCallback() != &defaultNearCallback ||
      pairs->getNumOverlappingPairs() < kParallelPairs) {
    btCollisionDispatcher::dispatchAllCollisionPairs(pairs, info, dispatcher);
    return;
  }
  btBroadphasePairArray& all = pairs->getOverlappingPairArray();
  settled_.clear();
  for (int i = 0; i < all.size(); ++i) {
    btBroadphasePair& p = all[i];
    // a pair needsCollision always refuses (a robot's own bodies without self-collision) makes and writes nothing
    if (never_collides(p)) continue;
    if (settled(p))
      settled_.push_back(&p);
    else
      defaultNearCallback(p, *this, info);
  }
  const int n = static_cast<int>(settled_.size());
  if (n < kParallelPairs) {
    for (int i = 0; i < n; ++i) defaultNearCallback(*settled_[i], *this, info);
    return;
  }
  // chunks of 8 pairs claimed as threads come free (car's pool: a thread the OS runs late is not waited for)
  parallel_for_threads(
      (n + 7) / 8,
      [&](int c, int) {
        for (int i = 8 * c; i < std::min(n, 8 * c + 8); ++i) defaultNearCallback(*settled_[i], *this, info);
      },
      threads_);
}

// The constraint arrays' sorts by island (solveConstraints), whose keys give each island's range.
struct IslandWorld::ConstraintSort {
  IslandSort<btTypedConstraint> rigid;
  IslandSort<btMultiBodyConstraint> multibody;
  bool current = false;  // both sorted this step (their ranges are the arrays')
};

// Bullet's island manager calls this once per awake island, in increasing island order; it copies the island's
// bodies and manifolds (Bullet's arrays are reused for the next island) and finds its constraints.
struct IslandWorld::Collector : btSimulationIslandManager::IslandCallback {
  IslandWorld* w = nullptr;
  void processIsland(btCollisionObject** bodies, int num_bodies, btPersistentManifold** manifolds, int num_manifolds,
                     int island) override {
    Island s{};
    s.tag = island;
    if (island >= 0 && island < static_cast<int>(w->island_of_tag_.size()))
      w->island_of_tag_[island] = static_cast<int>(w->islands_.size());
    s.bodies = w->bodies_.size();
    s.num_bodies = num_bodies;
    for (int i = 0; i < num_bodies; ++i) w->bodies_.push_back(bodies[i]);
    // a manifold with no contact point makes no row; it may join this island to a sleeping object (islands are
    // joined by contact, ContactIslands), whose velocities a solve must not touch
    s.manifolds = w->manifolds_.size();
    for (int i = 0; i < num_manifolds; ++i)
      if (manifolds[i]->getNumContacts() > 0) w->manifolds_.push_back(manifolds[i]);
    s.num_manifolds = w->manifolds_.size() - s.manifolds;
    if (island < 0) {
      // islands not split: one problem with everything
      s.num_constraints = w->m_sortedConstraints.size();
      s.num_mb_constraints = w->m_sortedMultiBodyConstraints.size();
    } else {
      if (w->constraint_sort_->current) {
        w->constraint_sort_->rigid.range(island, s.constraints, s.num_constraints);
        w->constraint_sort_->multibody.range(island, s.mb_constraints, s.num_mb_constraints);
      } else {
        range_of(w->m_sortedConstraints, island, s.constraints, s.num_constraints);
        range_of(w->m_sortedMultiBodyConstraints, island, s.mb_constraints, s.num_mb_constraints);
      }
    }
    w->islands_.push_back(s);
  }
};

// Simulation islands joined by contact, as ODE joins them (Gazebo): two objects are one island when a manifold
// between them holds a contact point, not, as in Bullet's findUnions, when their bounding boxes overlap. So a
// resting object is woken by a touch (ODE's auto-enable through a contact joint), not by a robot passing by.
// Tags as Bullet's updateActivationState gives them (STATIC_SIMULATION_ISLAND_OPTIMIZATION: static and kinematic
// objects get none).
class ContactIslands : public btSimulationIslandManager {
 public:
  void updateActivationState(btCollisionWorld* world, btDispatcher* dispatcher) override {
    int index = 0;
    const btCollisionObjectArray& objects = world->getCollisionObjectArray();
    for (int i = 0; i < objects.size(); ++i) {
      btCollisionObject* o = objects[i];
      if (!o->isStaticOrKinematicObject()) o->setIslandTag(index++);
      o->setCompanionId(-1);
      o->setHitFraction(btScalar(1.));
    }
    initUnionFind(index);
    for (int i = 0; i < dispatcher->getNumManifolds(); ++i) {
      const btPersistentManifold* m = dispatcher->getManifoldByIndexInternal(i);
      if (m->getNumContacts() == 0) continue;
      const btCollisionObject *a = m->getBody0(), *b = m->getBody1();
      if (a && a->mergesSimulationIslands() && b && b->mergesSimulationIslands())
        getUnionFind().unite(a->getIslandTag(), b->getIslandTag());
    }
  }

  // Bullet's buildAndProcessIslands (3.24: buildIslands, then processIslands), with the island manifolds sorted
  // by IslandSort: the same sleeping states, islands, manifolds and order. Bullet's sort called a function
  // twice per comparison; with many robots it was the largest part of the step's serial share.
  void build_and_process(btDispatcher* dispatcher, btCollisionWorld* world, IslandCallback* callback) {
    if (!getSplitIslands() || world->getDispatchInfo().m_deterministicOverlappingPairs) {
      buildAndProcessIslands(dispatcher, world, callback);
      return;
    }
    btCollisionObjectArray& objects = world->getCollisionObjectArray();
    btUnionFind& uf = getUnionFind();
    element_sort_.sort(uf);
    const int num = uf.getNumElements();
    // an island all of whose tagged objects are neither active nor kept awake sleeps; a sleeping object of an
    // awake island wants deactivation from now
    for (int start = 0, end = 0; start < num; start = end) {
      const int id = uf.getElement(start).m_id;
      for (end = start + 1; end < num && uf.getElement(end).m_id == id; ++end) {
      }
      bool all_sleeping = true;
      for (int k = start; k < end && all_sleeping; ++k) {
        const btCollisionObject* o = objects[uf.getElement(k).m_sz];
        if (o->getIslandTag() == id &&
            (o->getActivationState() == ACTIVE_TAG || o->getActivationState() == DISABLE_DEACTIVATION))
          all_sleeping = false;
      }
      for (int k = start; k < end; ++k) {
        btCollisionObject* o = objects[uf.getElement(k).m_sz];
        if (o->getIslandTag() != id) continue;
        if (all_sleeping) {
          o->setActivationState(ISLAND_SLEEPING);
        } else if (o->getActivationState() == ISLAND_SLEEPING) {
          o->setActivationState(WANTS_DEACTIVATION);
          o->setDeactivationTime(0.f);
        }
      }
    }
    // the manifolds with an awake body; a kinematic body wakes what it touches
    manifolds_.resize(0);
    for (int i = 0; i < dispatcher->getNumManifolds(); ++i) {
      btPersistentManifold* m = dispatcher->getManifoldByIndexInternal(i);
      const btCollisionObject* a = m->getBody0();
      const btCollisionObject* b = m->getBody1();
      if (!((a && a->getActivationState() != ISLAND_SLEEPING) || (b && b->getActivationState() != ISLAND_SLEEPING)))
        continue;
      if (a->isKinematicObject() && a->getActivationState() != ISLAND_SLEEPING && a->hasContactResponse())
        b->activate();
      if (b->isKinematicObject() && b->getActivationState() != ISLAND_SLEEPING && b->hasContactResponse())
        a->activate();
      if (dispatcher->needsResponse(a, b)) manifolds_.push_back(m);
    }
    sort_.sort(manifolds_);
    // each island with its bodies and manifolds, unless all its bodies sleep
    const int num_manifolds = manifolds_.size();
    int first_manifold = 0;
    for (int start = 0, end = 0; start < num; start = end) {
      const int id = uf.getElement(start).m_id;
      bool sleeping = true;
      bodies_.resize(0);
      for (end = start; end < num && uf.getElement(end).m_id == id; ++end) {
        btCollisionObject* o = objects[uf.getElement(end).m_sz];
        bodies_.push_back(o);
        if (o->isActive()) sleeping = false;
      }
      int count = 0;
      while (first_manifold + count < num_manifolds && sort_.island(first_manifold + count) == id) ++count;
      if (!sleeping)
        callback->processIsland(&bodies_[0], bodies_.size(), count ? &manifolds_[first_manifold] : nullptr, count, id);
      first_manifold += count;
    }
  }

 private:
  btAlignedObjectArray<btPersistentManifold*> manifolds_;
  btAlignedObjectArray<btCollisionObject*> bodies_;
  IslandSort<btPersistentManifold> sort_;
  ElementSort element_sort_;
};

IslandWorld::IslandWorld(btDispatcher* dispatcher, btBroadphaseInterface* broadphase, SurfaceSolver* solver,
                         btCollisionConfiguration* config)
    : btMultiBodyDynamicsWorld(dispatcher, broadphase, solver, config), collector_(std::make_unique<Collector>()),
      constraint_sort_(std::make_unique<ConstraintSort>()) {
  collector_->w = this;
  // Bullet's world made its island manager with btAlignedAlloc and placement new, and frees it so
  m_islandManager->~btSimulationIslandManager();
  btAlignedFree(m_islandManager);
  m_islandManager = new (btAlignedAlloc(sizeof(ContactIslands), 16)) ContactIslands();
  solvers_.push_back(solver);
  const int threads = parallel_threads();
  for (int t = 1; t < threads; ++t) {
    own_.push_back(std::make_unique<SurfaceSolver>());
    solvers_.push_back(own_.back().get());
  }
  for (SurfaceSolver* s : solvers_) s->set_inverse_source(this);
  scratch_.resize(solvers_.size());
}

IslandWorld::~IslandWorld() = default;

void IslandWorld::set_row_setup(RowSetup rows) {
  for (SurfaceSolver* s : solvers_) s->set_row_setup(rows);
}

void IslandWorld::solve_island(SurfaceSolver& solver, const Island& s, const btContactSolverInfo& info) {
  btCollisionObject** bodies = s.num_bodies ? &bodies_[s.bodies] : nullptr;
  btPersistentManifold** manifolds = s.num_manifolds ? &manifolds_[s.manifolds] : nullptr;
  btTypedConstraint** constraints = s.num_constraints ? &m_sortedConstraints[s.constraints] : nullptr;
  btMultiBodyConstraint** mb = s.num_mb_constraints ? &m_sortedMultiBodyConstraints[s.mb_constraints] : nullptr;
  solver.solveMultiBodyGroup(bodies, s.num_bodies, manifolds, s.num_manifolds, constraints, s.num_constraints, mb,
                             s.num_mb_constraints, info, m_debugDrawer, getDispatcher());
}

template <class F>
void IslandWorld::for_each_multibody(F&& f) {
  const int n = m_multiBodies.size();
  const int threads = n >= kParallelPositions ? static_cast<int>(scratch_.size()) : 1;
  if (threads > 1) {
    // Which thread takes which body changes nothing: f touches only that body (and its colliders) and the
    // thread's scratch, which Bullet's calls size and fill before they read it.
    parallel_for_threads(
        (n + 3) / 4,
        [&](int c, int t) {
          for (int i = 4 * c; i < std::min(n, 4 * c + 4); ++i) f(m_multiBodies[i], scratch_[t]);
        },
        threads);
  } else {
    for (int i = 0; i < n; ++i) f(m_multiBodies[i], scratch_[0]);
  }
}

// Which multibodies take their free motion from their factored mass matrix this step (docs/COMPAT-physics.md "Free
// motion"): all, when the solvers set up every row with factored matrices, except a multibody that a constraint of
// Bullet's rows touches (a joint limit: its rows read the caches of Bullet's free-motion pass), one with joint
// feedback or a joint of several degrees of freedom (Bullet's pass for those).
void IslandWorld::mark_factored(const btContactSolverInfo& info) {
  const int nmb = m_multiBodies.size();
  free_.resize(nmb);
  const bool factored = solvers_[0]->factored_free_motion(info);
  factored_.assign(nmb, factored ? 1 : 0);
  if (!factored) return;
  for (int i = 0; i < nmb; ++i)
    if (m_multiBodies[i]->getUserIndex() != i) m_multiBodies[i]->setUserIndex(i);
  for (int i = 0; i < m_multiBodyConstraints.size(); ++i) {
    btMultiBodyConstraint* c = m_multiBodyConstraints[i];
    btMultiBody *a = c->getMultiBodyA(), *b = c->getMultiBodyB();
    // car's motor on its own multibody sets its rows up with SurfaceSolver::response (JointMotor is final: its
    // type compared, not searched along the class chain as a dynamic_cast does)
    if (a == b && c->getConstraintType() == MULTIBODY_CONSTRAINT_1DOF_JOINT_MOTOR && typeid(*c) == typeid(JointMotor))
      continue;
    if (a) factored_[a->getUserIndex()] = 0;
    if (b) factored_[b->getUserIndex()] = 0;
  }
  for (int i = 0; i < nmb; ++i)
    if (factored_[i] && !InverseMass::free_motion_supported(*m_multiBodies[i])) factored_[i] = 0;
}

const InverseMass* IslandWorld::built(const btMultiBody* mb) const {
  const int i = mb->getUserIndex();
  if (i < 0 || i >= static_cast<int>(free_.size()) || m_multiBodies[i] != mb) return nullptr;
  const FreeMotion& f = free_[i];
  return f.stamp == stamp_ && f.ok ? &f.inverse : nullptr;
}

// A multibody's share of btMultiBodyDynamicsWorld::solveExternalForces: forward kinematics, constraint forces
// cleared and, if it was awake before the islands were built, its free accelerations added to its velocities: from
// its factored mass matrix (mark_factored), else Featherstone's articulated-body algorithm, Bullet's pass (gravity was
// added in applyGravity and the forces are cleared in clearForces, as Bullet 3.24 builds with
// BT_USE_VIRTUAL_CLEARFORCES_AND_GRAVITY).
void IslandWorld::free_motion(int body, Scratch& s, const btContactSolverInfo& info) {
  btMultiBody* b = m_multiBodies[body];
  b->forwardKinematics(s.world_to_local, s.local_origin);
  b->clearConstraintForces();
  if (!awake_[body]) return;
  if (factored_[body]) {
    // M q'' = tau - c from the matrix the rows use (built once for both), then Bullet's velocity update
    FreeMotion& f = free_[body];
    f.stamp = stamp_;
    f.ok = f.inverse.build(*b);
    if (f.ok) {
      s.r.resize(6 + b->getNumDofs());
      f.inverse.free_acceleration(*b, &s.r[0]);
      b->applyDeltaVeeMultiDof(&s.r[0], info.m_timeStep);
      return;
    }
  }
  s.r.resize(b->getNumLinks() + 1);
  s.v.resize(b->getNumLinks() + 1);
  s.m.resize(b->getNumLinks() + 1);
  b->computeAccelerationsArticulatedBodyAlgorithmMultiDof(info.m_timeStep, s.r, s.v, s.m, false,
                                                          getSolverInfo().m_jointFeedbackInWorldSpace,
                                                          getSolverInfo().m_jointFeedbackInJointFrame);
}

// A multibody's share of btMultiBodyDynamicsWorld::solveInternalConstraints: the joint-feedback pass (the
// accelerations again, with the constraint forces, if it reports joint forces and is awake now) and the velocity
// update.
void IslandWorld::constrained_motion(int body, Scratch& s, const btContactSolverInfo& info) {
  btMultiBody* b = m_multiBodies[body];
  if (!sleeping(b)) {
    s.r.resize(b->getNumLinks() + 1);
    s.v.resize(b->getNumLinks() + 1);
    s.m.resize(b->getNumLinks() + 1);
    if (b->internalNeedsJointFeedback())
      b->computeAccelerationsArticulatedBodyAlgorithmMultiDof(info.m_timeStep, s.r, s.v, s.m, true,
                                                              getSolverInfo().m_jointFeedbackInWorldSpace,
                                                              getSolverInfo().m_jointFeedbackInJointFrame);
  }
  b->processDeltaVeeMultiDof2();
}

// Island k's work (k == islands_.size(): the multibodies in no awake island): its multibodies' free motion, the
// island's constraint problem, its multibodies' constrained motion and (with integrated_) their new positions.
void IslandWorld::island_task(int k, SurfaceSolver& solver, Scratch& s, const btContactSolverInfo& info) {
  const Island& is = k < static_cast<int>(islands_.size()) ? islands_[k] : rest_;
  for (int i = 0; i < is.num_mbs; ++i) free_motion(island_mbs_[is.mbs + i], s, info);
  if (k < static_cast<int>(islands_.size())) solve_island(solver, is, info);
  for (int i = 0; i < is.num_mbs; ++i) constrained_motion(island_mbs_[is.mbs + i], s, info);
  if (integrated_)
    for (int i = 0; i < is.num_mbs; ++i) integrate(m_multiBodies[island_mbs_[is.mbs + i]], s, info.m_timeStep);
}

// A multibody's share of btMultiBodyDynamicsWorld::integrateTransforms: its positions and its colliders'
// transforms (a sleeping one: velocities cleared).
void IslandWorld::integrate(btMultiBody* b, Scratch& s, btScalar dt) {
  if (sleeping(b)) {
    b->clearVelocities();
    return;
  }
  b->addSplitV();
  if (!b->isPosUpdated()) {
    b->stepPositionsMultiDof(dt);
  } else {
    // RK4's position delta, stored after the velocities (Bullet's layout)
    btScalar* delta =
        const_cast<btScalar*>(b->getVelocityVector()) + 6 + b->getNumDofs() + b->getNumDofs() * b->getNumDofs();
    b->stepPositionsMultiDof(1, 0, delta);
    b->setPosUpdated(false);
  }
  s.world_to_local.resize(b->getNumLinks() + 1);
  s.local_origin.resize(b->getNumLinks() + 1);
  b->updateCollisionObjectWorldTransforms(s.world_to_local, s.local_origin);
  b->substractSplitV();
}

// btMultiBodyDynamicsWorld::integrateTransforms: rigid bodies first (Bullet's, on this thread), then the
// multibodies, unless the islands' tasks did them already (see solveConstraints).
void IslandWorld::integrateTransforms(btScalar dt) {
  btDiscreteDynamicsWorld::integrateTransforms(dt);
  if (integrated_) {
    integrated_ = false;
    return;
  }
  for_each_multibody([this, dt](btMultiBody* b, Scratch& s) { integrate(b, s, dt); });
}

// Bullet's step of the constraints (btMultiBodyDynamicsWorld::solveConstraints) with each island's work done as
// one task: Bullet runs free motion for every multibody, then the islands (merged into batches), then constrained
// motion for every multibody. A multibody's free and constrained motion touch only that body, and an island's
// problem only its own bodies, so doing an island's three parts together, island by island, gives Bullet's
// numbers while each island's data stay in the cache, and the islands go to the threads with no barrier between
// the parts. Two rules keep it so: a multibody's free motion depends on whether it was awake before the islands
// were built (building them puts islands to sleep and wakes others), so that is taken first; and a manifold on a
// static multibody collider (a fixed base), which any island may touch, makes the step run in Bullet's order.
void IslandWorld::solveConstraints(btContactSolverInfo& info) {
  const int nmb = m_multiBodies.size();
  // no matrix of an earlier step is found (built)
  ++stamp_;
  constraint_sort_->current = false;
  bool rk4 = false;
  for (int i = 0; i < nmb; ++i) rk4 = rk4 || m_multiBodies[i]->isUsingRK4Integration();
  if (rk4) {
    // Bullet's own passes (car uses no RK4), islands on this thread
    btMultiBodyDynamicsWorld::solveExternalForces(info);
    collect_islands();
    for (const Island& is : islands_) solve_island(*solvers_[0], is, info);
    btMultiBodyDynamicsWorld::solveInternalConstraints(info);
    return;
  }
  // btMultiBodyDynamicsWorld::solveExternalForces's bookkeeping (its island callback is not used)
  m_sortedConstraints.resize(m_constraints.size());
  for (int i = 0; i < m_constraints.size(); ++i) m_sortedConstraints[i] = m_constraints[i];
  if (own_sort_)
    constraint_sort_->rigid.sort(m_sortedConstraints);
  else
    m_sortedConstraints.quickSort(btSortConstraintOnIslandPredicate2());
  m_sortedMultiBodyConstraints.resize(m_multiBodyConstraints.size());
  for (int i = 0; i < m_multiBodyConstraints.size(); ++i) m_sortedMultiBodyConstraints[i] = m_multiBodyConstraints[i];
  if (own_sort_)
    constraint_sort_->multibody.sort(m_sortedMultiBodyConstraints);
  else
    m_sortedMultiBodyConstraints.quickSort(btSortMultiBodyConstraintOnIslandPredicate());
  constraint_sort_->current = own_sort_;
  m_constraintSolver->prepareSolve(getNumCollisionObjects(), getDispatcher()->getNumManifolds());
  awake_.assign(nmb, 0);
  for (int i = 0; i < nmb; ++i) awake_[i] = !sleeping(m_multiBodies[i]);
  mark_factored(info);
  collect_islands();
  const bool in_order = assign_multibodies();
  const int n = static_cast<int>(islands_.size());
  // Threads only for enough work to pay for waking them: a single car among resting boxes (about 20 manifolds
  // and constraints) stays on this thread, four cars and more go parallel.
  int work = 0;
  for (const Island& is : islands_) work += is.num_manifolds + is.num_constraints + is.num_mb_constraints;
  const int threads =
      !in_order && (work >= kParallelWork || nmb >= kParallelBodies) ? static_cast<int>(solvers_.size()) : 1;
  // Bullet integrates the rigid bodies before the multibodies, and a rigid body's CCD sweep reads the colliders:
  // with no CCD the multibodies' positions are integrated in their islands' tasks (integrateTransforms then skips
  // them), one pass fewer over all bodies.
  integrated_ = !in_order && !ccd_bodies();
  if (in_order) {
    for (int i = 0; i < nmb; ++i) free_motion(i, scratch_[0], info);
    for (const Island& is : islands_) solve_island(*solvers_[0], is, info);
    for (int i = 0; i < nmb; ++i) constrained_motion(i, scratch_[0], info);
  } else if (threads > 1) {
    // Which thread takes which island changes nothing: the solvers are identical and keep no state between
    // problems, the scratch buffers are sized and filled before they are read. Islands share only static
    // objects (read) and Bullet's fixed solver body (one per solver).
    parallel_for_threads(n + 1, [&](int k, int t) { island_task(k, *solvers_[t], scratch_[t], info); }, threads);
  } else {
    for (int k = 0; k <= n; ++k) island_task(k, *solvers_[0], scratch_[0], info);
  }
  m_constraintSolver->allSolved(info, m_debugDrawer);
}

// btMultiBodyDynamicsWorld::predictUnconstraintMotion: the rigid bodies' predicted transforms (Bullet's), then each
// multibody's (predictMultiBodyTransforms) only if a rigid body may sweep; a sleeping multibody's velocities are
// cleared either way, as Bullet's pass does. The predicted positions go to the *_interpolate members and the
// colliders' interpolation transforms, which only a rigid body's CCD sweep reads: without one the step is the same
// bit for bit.
void IslandWorld::predictUnconstraintMotion(btScalar dt) {
  if (ccd_bodies()) {
    btMultiBodyDynamicsWorld::predictUnconstraintMotion(dt);
    return;
  }
  predict_rigid_bodies(dt);
  for (int i = 0; i < m_multiBodies.size(); ++i)
    if (sleeping(m_multiBodies[i])) m_multiBodies[i]->clearVelocities();
}

// btDiscreteDynamicsWorld::predictUnconstraintMotion (damping, then the predicted transform), skipping a body at rest
// whose prediction is already in place (Prediction). The damping of +0 velocities is +0 again (Bullet clamps the
// damping to [0, 1], so the factor is finite and non-negative; car never turns on Bullet's additional damping).
void IslandWorld::predict_rigid_bodies(btScalar dt) {
  if (!reuse_) {
    btDiscreteDynamicsWorld::predictUnconstraintMotion(dt);
    return;
  }
  predictions_.resize(m_nonStaticRigidBodies.size());
  for (int i = 0; i < m_nonStaticRigidBodies.size(); ++i) {
    btRigidBody* body = m_nonStaticRigidBodies[i];
    if (body->isStaticOrKinematicObject()) continue;
    Prediction& p = predictions_[i];
    const bool rest = positive_zero(body->getLinearVelocity()) && positive_zero(body->getAngularVelocity());
    if (rest && p.body == body && p.dt == dt && same(p.from, body->getWorldTransform()) &&
        same(p.to, body->getInterpolationWorldTransform()))
      continue;
    body->applyDamping(dt);
    body->predictIntegratedTransform(dt, body->getInterpolationWorldTransform());
    // only a prediction from +0 velocities can be reused (a body falls asleep with the velocities of its last step)
    p.body = rest ? body : nullptr;
    p.dt = dt;
    p.from = body->getWorldTransform();
    p.to = body->getInterpolationWorldTransform();
  }
}

// btCollisionWorld::updateAabbs and updateSingleAabb, with last step's box where its inputs are the same (Box).
void IslandWorld::updateAabbs() {
  if (!reuse_) {
    btCollisionWorld::updateAabbs();
    return;
  }
  const int n = m_collisionObjects.size();
  boxes_.resize(n);
  const btScalar threshold = gContactBreakingThreshold;
  const btVector3 margin(threshold, threshold, threshold);
  auto skipped = [&](const btCollisionObject* o) { return !m_forceUpdateAllAabbs && !o->isActive(); };
  // an object's box, from its inputs unless they are the last step's; left without its object if the box
  // overflows (Bullet's rule below)
  auto refresh = [&](int i) {
    const btCollisionObject* o = m_collisionObjects[i];
    if (skipped(o)) return;
    const bool swept = getDispatchInfo().m_useContinuous && o->getInternalType() == btCollisionObject::CO_RIGID_BODY &&
                       !o->isStaticOrKinematicObject();
    const bool fixed = o->isStaticObject();
    Box& b = boxes_[i];
    if (b.object == o && b.shape == o->getCollisionShape() && b.threshold == threshold && b.swept == swept &&
        b.fixed == fixed && same(b.world, o->getWorldTransform()) &&
        (!swept || same(b.interpolation, o->getInterpolationWorldTransform())))
      return;
    b.object = nullptr;
    o->getCollisionShape()->getAabb(o->getWorldTransform(), b.min, b.max);
    b.min -= margin;
    b.max += margin;
    if (swept) {
      btVector3 min, max;
      o->getCollisionShape()->getAabb(o->getInterpolationWorldTransform(), min, max);
      min -= margin;
      max += margin;
      b.min.setMin(min);
      b.max.setMax(max);
    }
    if (!fixed && !((b.max - b.min).length2() < btScalar(1e12))) return;
    b.object = o;
    b.shape = o->getCollisionShape();
    b.world = o->getWorldTransform();
    b.interpolation = o->getInterpolationWorldTransform();
    b.threshold = threshold;
    b.swept = swept;
    b.fixed = fixed;
  };
  // the boxes on the threads for many objects (each writes only its own), then the broad phase in object order
  const int threads = n >= kParallelBoxes ? static_cast<int>(solvers_.size()) : 1;
  if (threads > 1)
    parallel_for_threads(
        (n + 31) / 32,
        [&](int c, int) {
          for (int i = 32 * c; i < std::min(n, 32 * c + 32); ++i) refresh(i);
        },
        threads);
  else
    for (int i = 0; i < n; ++i) refresh(i);
  for (int i = 0; i < n; ++i) {
    btCollisionObject* o = m_collisionObjects[i];
    if (skipped(o)) continue;
    const Box& b = boxes_[i];
    // Bullet's overflow rule: a moving object over 1e6 m across is disabled, with a report
    if (b.object != o)
      updateSingleAabb(o);
    else
      m_broadphasePairCache->setAabb(o->getBroadphaseHandle(), b.min, b.max, m_dispatcher1);
  }
}

// Whether a rigid body may sweep (Bullet's test in btDiscreteDynamicsWorld::integrateTransforms).
bool IslandWorld::ccd_bodies() const {
  if (!getDispatchInfo().m_useContinuous) return false;
  for (int i = 0; i < m_nonStaticRigidBodies.size(); ++i)
    if (m_nonStaticRigidBodies[i]->getCcdSquareMotionThreshold() != 0) return true;
  return false;
}

void IslandWorld::collect_islands() {
  bodies_.resize(0);
  manifolds_.resize(0);
  islands_.clear();
  island_of_tag_.assign(getNumCollisionObjects(), -1);
  if (own_sort_)
    static_cast<ContactIslands*>(m_islandManager)->build_and_process(getDispatcher(), this, collector_.get());
  else
    m_islandManager->buildAndProcessIslands(getDispatcher(), this, collector_.get());
}

// Sorts the multibodies into their islands (island_mbs_, each island's mbs range; rest_: those in no awake
// island). A multibody's non-static colliders are all in one island (Bullet unites them); its island is the one
// of the first. Returns true if the step must run in Bullet's order (see solveConstraints).
bool IslandWorld::assign_multibodies() {
  const int nmb = m_multiBodies.size();
  const int n = static_cast<int>(islands_.size());
  owner_.assign(nmb, n);
  bool in_order = false;
  for (const Island& is : islands_) in_order = in_order || is.tag < 0;  // islands not split: one problem
  for (int i = 0; i < nmb; ++i) {
    const int tag = island_tag(m_multiBodies[i]);
    if (tag >= 0 && tag < static_cast<int>(island_of_tag_.size()) && island_of_tag_[tag] >= 0)
      owner_[i] = island_of_tag_[tag];
  }
  for (int m = 0; m < manifolds_.size() && !in_order; ++m) {
    for (const btCollisionObject* o : {manifolds_[m]->getBody0(), manifolds_[m]->getBody1()})
      if (btMultiBodyLinkCollider::upcast(o) && o->isStaticOrKinematicObject()) in_order = true;
  }
  // a multibody constraint on a multibody of another island or of none
  for (const Island& is : islands_) {
    for (int c = 0; c < is.num_mb_constraints && !in_order; ++c) {
      btMultiBodyConstraint* mc = m_sortedMultiBodyConstraints[is.mb_constraints + c];
      for (const btMultiBody* b : {mc->getMultiBodyA(), mc->getMultiBodyB()})
        if (b && island_tag(b) != is.tag) in_order = true;
    }
  }
  // counting sort by island, in multibody order within an island
  std::vector<int>& count = island_count_;
  count.assign(n + 2, 0);
  for (int i = 0; i < nmb; ++i) ++count[owner_[i] + 1];
  for (int k = 0; k <= n; ++k) count[k + 1] += count[k];
  for (int k = 0; k < n; ++k) {
    islands_[k].mbs = count[k];
    islands_[k].num_mbs = count[k + 1] - count[k];
  }
  rest_ = Island{};
  rest_.mbs = count[n];
  rest_.num_mbs = count[n + 1] - count[n];
  island_mbs_.resize(nmb);
  for (int i = 0; i < nmb; ++i) island_mbs_[count[owner_[i]]++] = i;
  return in_order;
}

}  // namespace physics
}  // namespace car_sim
