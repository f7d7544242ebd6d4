// The guard (first_non_finite) finds every kind of value it watches when that value alone is not finite: a world
// object's position, velocity and angular velocity, a robot base's position, velocity and angular velocity, and a
// joint's coordinate and rate. Each is set to infinity or NaN straight in Bullet's state, and the guard runs
// without a step (a step would carry a bad velocity into the position and hide a missed check).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>

#include <btBulletDynamicsCommon.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>

#include "../../src/physics/guard.hpp"
#include "physics_fixtures.hpp"

using namespace car_sim;
using namespace car_sim::test_physics;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
const double kNaN = std::nan("");

struct Scene : HousePhysics {
  btMultiBody* car = nullptr;
  btRigidBody* box = nullptr;
};

Scene scene() {
  Scene s;
  static_cast<HousePhysics&>(s) = box_house(options());
  s.p->add_robot(seed_car(), "car", pose(0, 0, 0), {});
  run(*s.p, 10);
  s.car = s.p->bullet().getMultiBody(0);
  s.box = s.p->world_model_body("unit_box", 0);
  return s;
}

// The guard's report after `spoil` wrote one bad value into a fresh scene.
std::string report(const std::function<void(Scene&)>& spoil) {
  Scene s = scene();
  EXPECT_EQ(physics::first_non_finite(s.p->bullet(), {}), "") << "the scene is finite before";
  spoil(s);
  return physics::first_non_finite(s.p->bullet(), {});
}

}  // namespace

TEST(Guard, FindsAWorldObjectsPosition) {
  const std::string r = report([](Scene& s) {
    btTransform T = s.box->getWorldTransform();
    T.getOrigin().setZ(kNaN);
    s.box->setWorldTransform(T);
  });
  EXPECT_NE(r.find(": position"), std::string::npos) << r;
}

TEST(Guard, FindsAWorldObjectsVelocity) {
  const std::string r = report([](Scene& s) { s.box->setLinearVelocity(btVector3(0, kInf, 0)); });
  EXPECT_NE(r.find(": velocity"), std::string::npos) << r;
}

TEST(Guard, FindsAWorldObjectsAngularVelocity) {
  const std::string r = report([](Scene& s) { s.box->setAngularVelocity(btVector3(kNaN, 0, 0)); });
  EXPECT_NE(r.find(": angular velocity"), std::string::npos) << r;
}

TEST(Guard, FindsARobotBasesPosition) {
  const std::string r = report([](Scene& s) { s.car->setBasePos(btVector3(kInf, 0, 0)); });
  EXPECT_NE(r.find(": position"), std::string::npos) << r;
}

TEST(Guard, FindsARobotBasesVelocity) {
  const std::string r = report([](Scene& s) { s.car->setBaseVel(btVector3(0, 0, -kInf)); });
  EXPECT_NE(r.find(": velocity"), std::string::npos) << r;
}

TEST(Guard, FindsARobotBasesAngularVelocity) {
  const std::string r = report([](Scene& s) { s.car->setBaseOmega(btVector3(0, kNaN, 0)); });
  EXPECT_NE(r.find(": angular velocity"), std::string::npos) << r;
}

TEST(Guard, FindsAJointCoordinate) {
  const std::string r = report([](Scene& s) { s.car->setJointPos(0, kNaN); });
  EXPECT_NE(r.find(": joint coordinate nan"), std::string::npos) << r;
}

TEST(Guard, FindsAJointRate) {
  const std::string r = report([](Scene& s) { s.car->setJointVel(1, kInf); });
  EXPECT_NE(r.find(", rate inf (link 2)"), std::string::npos) << r;
}
