// Car's row set-up (docs/COMPAT-physics.md "Row set-up"). With Bullet's Featherstone pass for the responses
// (RowSetup::car_exact) car's set-up of contact and motor rows is Bullet's to the bit: cars driving into
// box_house's boxes and walls, a fixed arm on its joint limits, a caster robot, every body's pose, velocity and joint
// state equal bit for bit after 3 s. With the factored mass matrix (the default) the responses differ from Bullet's
// by rounding only (1e-15 relative, test_inverse_mass.cpp): a car driving a circle on the ground stays within
// 1e-9 m and 1e-9 rad of the exact run after 3 s.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "physics_fixtures.hpp"

using namespace car_sim;
using namespace car_sim::test_physics;

namespace {

std::string data(const std::string& f) { return std::string(CAR_SOURCE_DIR) + "/test/data/" + f; }

struct Scene {
  std::unique_ptr<physics::Physics> p;
  std::vector<physics::Robot*> robots;
};

// Six seed cars in box_house, driving at different wheel speeds into its boxes and walls, an arm hanging on its
// joint limits and a caster robot.
Scene house(physics::RowSetup rows) {
  physics::Options o = options();
  o.rows = rows;
  Scene s;
  s.p = std::make_unique<physics::Physics>(load_world_file(std::string(CAR_SOURCE_DIR) + "/worlds/box_house.world"), o,
                                           std::set<std::string>{});
  const RobotModel car = load_urdf_file(data("car_camera_lidar04.urdf"));
  for (int i = 0; i < 6; ++i) {
    physics::Robot& r =
        s.p->add_robot(car, "car" + std::to_string(i), pose(-2.0 + 0.8 * i, -1.0 + 0.3 * i, 0.0, 0.5 * i), {"left2link", "right2link"});
    const int left = r.add_motor(r.joint("left2link"), 2.0), right = r.add_motor(r.joint("right2link"), 2.0);
    MotorTarget t;
    t.velocity = 10.0 + 3.0 * i;
    r.set_motor(left, t);
    t.velocity = 14.0 - 2.0 * i;
    r.set_motor(right, t);
    s.robots.push_back(&r);
  }
  s.robots.push_back(&s.p->add_robot(load_urdf_file(data("zoo/arm.urdf")), "arm", pose(3, 3, 0.3), {}));
  s.robots.push_back(&s.p->add_robot(load_urdf_file(data("zoo/caster_bot.urdf")), "caster", pose(-3, 3, 0.05), {}));
  return s;
}

// Every robot's root pose and velocity, then its joints' positions and velocities.
std::vector<double> state(const Scene& s, const std::vector<std::vector<std::string>>& joints) {
  std::vector<double> v;
  for (size_t k = 0; k < s.robots.size(); ++k) {
    const ModelState m = s.robots[k]->root_state();
    const Eigen::Quaterniond q(m.pose.linear());
    for (double x : {m.pose.translation().x(), m.pose.translation().y(), m.pose.translation().z(), q.w(), q.x(), q.y(),
                     q.z(), m.linear.x(), m.linear.y(), m.linear.z(), m.angular.x(), m.angular.y(), m.angular.z()})
      v.push_back(x);
    for (const auto& j : joints[k]) {
      v.push_back(s.robots[k]->joint_position(s.robots[k]->joint(j)));
      v.push_back(s.robots[k]->joint_velocity(s.robots[k]->joint(j)));
    }
  }
  return v;
}

const std::vector<std::vector<std::string>> kJoints = {
    {"left2link", "right2link", "front2link", "back2link"}, {"left2link", "right2link"}, {"left2link", "right2link"},
    {"left2link", "right2link"}, {"left2link", "right2link"}, {"left2link", "right2link"}, {"shoulder", "slide"},
    {"left_wheel_joint", "right_wheel_joint"}};

}  // namespace

TEST(RowSetup, CarsRowsAreBulletsBitForBit) {
  Scene bullet = house(physics::RowSetup::bullet), exact = house(physics::RowSetup::car_exact);
  run(*bullet.p, 3000);
  run(*exact.p, 3000);
  const std::vector<double> a = state(bullet, kJoints), b = state(exact, kJoints);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0);
  // the cars did drive (3 s at 0.4 m/s and more, until a box or wall stops them)
  EXPECT_GT(std::abs(a[0] + 2.0) + std::abs(a[1] + 1.0), 0.3);
}

TEST(RowSetup, FactoredMassStaysWithinRoundingOfBullets) {
  auto drive = [](physics::RowSetup rows) {
    physics::Options o = options();
    o.rows = rows;
    physics::Physics p(flat(), o, {});
    physics::Robot& r = p.add_robot(load_urdf_file(data("car_camera_lidar04.urdf")), "car", pose(0, 0, 0.0),
                                    {"left2link", "right2link"});
    const int left = r.add_motor(r.joint("left2link"), 2.0), right = r.add_motor(r.joint("right2link"), 2.0);
    MotorTarget t;
    t.velocity = 12.0;
    r.set_motor(left, t);
    t.velocity = 18.0;
    r.set_motor(right, t);
    run(p, 3000);
    return r.root_state();
  };
  const ModelState exact = drive(physics::RowSetup::car_exact), factored = drive(physics::RowSetup::factored);
  // it turned: 3 s of a circle
  EXPECT_GT((exact.pose.translation() - Eigen::Vector3d::Zero()).norm(), 0.3);
  EXPECT_LT((exact.pose.translation() - factored.pose.translation()).norm(), 1e-9);
  EXPECT_LT(Eigen::AngleAxisd(exact.pose.linear().transpose() * factored.pose.linear()).angle(), 1e-9);
}
