// The islands, their manifolds and the constraints reach the solver in Bullet's order (IslandWorld's IslandSort and
// ElementSort: keyed copies of Bullet's quicksort, and the last step's order taken again for an unchanged input): in
// box_house, four seed cars drive, one pushes unit_box, two meet head-on (islands join and split, manifolds come and
// go), and every state of the run and the union find's sorted elements equal, bit for bit, the run with Bullet's own
// sorts. Bullet's sort is not stable, so a stable sort by island gives another order (the test fails with one).
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include <BulletCollision/CollisionDispatch/btSimulationIslandManager.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>

#include "physics_fixtures.hpp"

using namespace car_sim;
using namespace car_sim::test_physics;

namespace {

struct Fleet : HousePhysics {
  std::vector<physics::Robot*> cars;
};

// [m], [rad], world frame: the pusher 1.9 m in front of unit_box's face, two cars facing each other 1 m apart,
// one circling in the open
Fleet fleet(bool own_sort) {
  physics::Options o = options();
  o.own_island_sort = own_sort;
  Fleet f;
  static_cast<HousePhysics&>(f) = box_house(o);
  const RobotModel car = seed_car();
  const double poses[4][3] = {{-7.27, 1.2, M_PI / 2}, {0.0, 3.0, 0.0}, {1.0, 3.0, M_PI}, {0.0, -3.0, 0.0}};
  for (int i = 0; i < 4; ++i) {
    physics::Robot& r =
        f.p->add_robot(car, "car" + std::to_string(i), pose(poses[i][0], poses[i][1], 0.0, poses[i][2]),
                       {"left2link", "right2link"});
    r.add_motor(r.joint("left2link"), 2.0);
    r.add_motor(r.joint("right2link"), 2.0);
    f.cars.push_back(&r);
  }
  return f;
}

// [rad/s] wheel speeds: the three straight cars drive on, the last circles
void drive(Fleet& f) {
  for (int i = 0; i < 4; ++i) {
    MotorTarget left, right;
    left.velocity = 10.0;
    right.velocity = i == 3 ? 5.0 : 10.0;
    f.cars[i]->set_motor(0, left);
    f.cars[i]->set_motor(1, right);
  }
}

// Every car's root state and wheel joints, and unit_box's state, every 100 steps of 6 s.
std::vector<std::vector<double>> history(bool own_sort, double* pushed, double* gap) {
  Fleet f = fleet(own_sort);
  drive(f);
  const Eigen::Vector3d start = f.p->world_model_state("unit_box")->pose.translation();
  std::vector<std::vector<double>> h;
  for (int step = 0; step <= 6000; ++step) {
    if (step % 100 == 0) {
      std::vector<double> v;
      for (physics::Robot* r : f.cars) {
        push_state(v, r->root_state());
        for (const char* j : {"left2link", "right2link"}) {
          v.push_back(r->joint_position(r->joint(j)));
          v.push_back(r->joint_velocity(r->joint(j)));
        }
      }
      push_state(v, *f.p->world_model_state("unit_box"));
      // the union find's elements as the island build left them: (island, collision object) sorted by island
      btUnionFind& uf = f.p->bullet().getSimulationIslandManager()->getUnionFind();
      for (int i = 0; i < uf.getNumElements(); ++i) {
        v.push_back(uf.getElement(i).m_id);
        v.push_back(uf.getElement(i).m_sz);
      }
      h.push_back(v);
    }
    f.p->step(kDt);
  }
  *pushed = (f.p->world_model_state("unit_box")->pose.translation() - start).norm();
  *gap = (f.cars[1]->root_state().pose.translation() - f.cars[2]->root_state().pose.translation()).norm();
  return h;
}

}  // namespace

TEST(IslandSort, FourCarsInBoxHouseStepAsWithBulletsSortBitForBit) {
  double pushed_own = 0, pushed_bullet = 0, gap_own = 0, gap_bullet = 0;
  const auto own = history(true, &pushed_own, &gap_own);
  const auto bullet = history(false, &pushed_bullet, &gap_bullet);
  // the scenario did what it is for: the box was pushed, the two cars met (their bases 1 m apart at the start,
  // driving at each other, they stay in contact: closer than two car lengths)
  EXPECT_GT(pushed_bullet, 0.2) << "[m] unit_box pushed";
  EXPECT_LT(gap_bullet, 0.5) << "[m] the two cars driving at each other";
  ASSERT_EQ(own.size(), bullet.size());
  for (size_t k = 0; k < own.size(); ++k) {
    ASSERT_EQ(own[k].size(), bullet[k].size());
    ASSERT_EQ(0, std::memcmp(own[k].data(), bullet[k].data(), own[k].size() * sizeof(double)))
        << "states or elements differ at step " << 100 * k;
  }
}
