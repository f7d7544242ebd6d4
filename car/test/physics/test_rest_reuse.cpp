// The step's reuse of an object's unchanged results (IslandWorld: the predicted transform of a body at rest and the
// bounding box of a collider whose inputs did not change) gives Bullet's own passes bit for bit: box_house's boxes
// fall asleep, a seed car wakes one by pushing it, another is teleported while asleep and then set to its own
// state, then pushed; every state of the run with the reuse, and Bullet's predicted transform of each box, equals
// the run without it.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include <btBulletDynamicsCommon.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>

#include "physics_fixtures.hpp"

using namespace car_sim;
using namespace car_sim::test_physics;

namespace {

const char* const kBoxes[] = {"unit_box", "unit_box_1"};

struct House : HousePhysics {
  physics::Robot* car = nullptr;
  int left = 0, right = 0;
};

House house(bool reuse) {
  physics::Options o = options();
  o.reuse_at_rest = reuse;
  House r;
  static_cast<HousePhysics&>(r) = box_house(o);
  // [m], world frame: 1.9 m in front of unit_box's face, facing it (+y)
  r.car = &r.p->add_robot(seed_car(), "car", pose(-7.27, 1.2, 0.0, M_PI / 2), {"left2link", "right2link"});
  r.left = r.car->add_motor(r.car->joint("left2link"), 2.0);
  r.right = r.car->add_motor(r.car->joint("right2link"), 2.0);
  return r;
}

void drive(House& r, double wheel_speed) {
  MotorTarget t;
  t.velocity = wheel_speed;  // [rad/s]
  r.car->set_motor(r.left, t);
  r.car->set_motor(r.right, t);
}

// Every dynamic box's state and Bullet's predicted transform of it (its interpolation transform), the car's root
// state and its joints.
std::vector<double> state(House& r) {
  std::vector<double> v;
  for (const char* b : kBoxes) {
    push_state(v, *r.p->world_model_state(b));
    const btTransform& T = r.p->world_model_body(b, 0)->getInterpolationWorldTransform();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) v.push_back(T.getBasis()[i][j]);
    for (int i = 0; i < 3; ++i) v.push_back(T.getOrigin()[i]);
  }
  push_state(v, r.car->root_state());
  for (const char* j : {"left2link", "right2link", "front2link", "back2link"}) {
    v.push_back(r.car->joint_position(r.car->joint(j)));
    v.push_back(r.car->joint_velocity(r.car->joint(j)));
  }
  return v;
}

bool asleep(House& r, const char* box) { return r.p->world_model_body(box, 0)->getActivationState() == ISLAND_SLEEPING; }

// One run's states every 250 steps, with the events at the same steps in both runs.
std::vector<std::vector<double>> history(bool reuse, bool* slept, double* pushed) {
  House r = house(reuse);
  std::vector<std::vector<double>> h;
  const Eigen::Vector3d start = r.p->world_model_state("unit_box")->pose.translation();
  for (int step = 0; step <= 7000; ++step) {
    if (step == 2500) {
      *slept = asleep(r, "unit_box") && asleep(r, "unit_box_1");
      drive(r, 20.0);
    }
    // a sleeping box lifted 0.3 m (it falls and settles), then set to its own state
    if (step == 3000) {
      ModelState s = *r.p->world_model_state("unit_box_1");
      s.pose.translation().z() += 0.3;
      r.p->set_world_model_state("unit_box_1", s);
    }
    // asleep again by then: set to its own state, then given a push of 0.2 m/s along x
    if (step == 6000) r.p->set_world_model_state("unit_box_1", *r.p->world_model_state("unit_box_1"));
    // a velocity written into the sleeping body without waking it (Bullet damps and predicts it all the same)
    if (step == 6250) r.p->world_model_body("unit_box_1", 0)->setLinearVelocity(btVector3(0.1, 0, 0));
    if (step == 6500) {
      ModelState s = *r.p->world_model_state("unit_box_1");
      s.linear = Eigen::Vector3d(0.2, 0, 0);
      r.p->set_world_model_state("unit_box_1", s);
    }
    if (step % 250 == 0 || step == 6251 || step == 6501) h.push_back(state(r));
    r.p->step(kDt);
  }
  *pushed = (r.p->world_model_state("unit_box")->pose.translation() - start).norm();
  return h;
}

}  // namespace

TEST(RestReuse, StepIsBulletsBitForBit) {
  bool slept_reuse = false, slept_bullet = false;
  double pushed = 0, pushed_bullet = 0;
  const auto a = history(true, &slept_reuse, &pushed), b = history(false, &slept_bullet, &pushed_bullet);
  // the run covers what it claims: both boxes asleep before the car moves, unit_box pushed by more than 5 cm
  EXPECT_TRUE(slept_reuse);
  EXPECT_GT(pushed, 0.05);
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(a[k].size(), b[k].size());
    EXPECT_EQ(std::memcmp(a[k].data(), b[k].data(), a[k].size() * sizeof(double)), 0) << "first at sample " << k << " (every 250 steps, and steps 6251 and 6501)";
    if (std::memcmp(a[k].data(), b[k].data(), a[k].size() * sizeof(double)) != 0) break;
  }
}

namespace {

// Every collider's box in the broad phase (its proxy's corners) after each 100 steps of 32 seed cars driving
// circles on a plane (161 colliders: their boxes are found on the threads, IslandWorld::updateAabbs).
std::vector<std::vector<double>> fleet_boxes(bool reuse) {
  physics::Options o = options();
  o.reuse_at_rest = reuse;
  const WorldDescription desc = flat();
  physics::Physics p(desc, o, {});
  const RobotModel car = seed_car();
  for (int i = 0; i < 32; ++i) {
    // [m], world frame: a 4 x 8 grid 1.5 m apart
    physics::Robot& r = p.add_robot(car, "car" + std::to_string(i), pose(1.5 * (i % 4), 1.5 * (i / 4), 0.0, 0.2 * i),
                                    {"left2link", "right2link"});
    MotorTarget left, right;
    left.velocity = 5.0 + 0.5 * i;  // [rad/s]
    right.velocity = 10.0;
    r.set_motor(r.add_motor(r.joint("left2link"), 2.0), left);
    r.set_motor(r.add_motor(r.joint("right2link"), 2.0), right);
  }
  std::vector<std::vector<double>> h;
  for (int step = 1; step <= 1000; ++step) {
    p.step(kDt);
    if (step % 100) continue;
    std::vector<double> v;
    const btCollisionObjectArray& objects = p.bullet().getCollisionObjectArray();
    for (int i = 0; i < objects.size(); ++i) {
      const btBroadphaseProxy* b = objects[i]->getBroadphaseHandle();
      for (int k = 0; k < 3; ++k) v.push_back(b->m_aabbMin[k]);
      for (int k = 0; k < 3; ++k) v.push_back(b->m_aabbMax[k]);
    }
    h.push_back(v);
  }
  return h;
}

}  // namespace

TEST(RestReuse, ManyCarsBoxesOnTheThreadsAreBulletsBitForBit) {
  const auto a = fleet_boxes(true), b = fleet_boxes(false);
  ASSERT_EQ(a.size(), 10u);
  ASSERT_EQ(a.size(), b.size());
  // 161 colliders: the ground and five per car
  ASSERT_EQ(a[0].size(), 161u * 6);
  // the cars moved: the boxes at 0.1 s and 1 s differ
  EXPECT_NE(0, std::memcmp(a[0].data(), a[9].data(), a[0].size() * sizeof(double)));
  for (size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(a[k].size(), b[k].size());
    ASSERT_EQ(0, std::memcmp(a[k].data(), b[k].data(), a[k].size() * sizeof(double))) << "boxes differ at step " << 100 * (k + 1);
  }
}
