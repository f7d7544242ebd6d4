// The factored mass matrix (src/physics/inverse_mass.hpp) against Bullet's own Featherstone pass: for robots of
// every joint layout car builds (floating base with wheels, a fixed base with a chain of revolute and prismatic
// joints, a tree), posed away from their zero configuration and moving, M^-1 f equals
// btMultiBody::calcAccelerationDeltasMultiDof(f) for random f to 1e-9 of its size; the free accelerations equal
// Bullet's articulated-body pass, the contact Jacobians its fillContactJacobianMultiDof.
#include <gtest/gtest.h>

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraint.h>

#include <random>

#include "../../src/physics/inverse_mass.hpp"
#include "physics_fixtures.hpp"

using namespace car_sim;
using namespace car_sim::test_physics;

namespace {

// A link of mass m with an off-diagonal-free inertia and a box collision, its centre of mass offset from the joint.
std::string link(const std::string& name, double m, const std::string& com) {
  return "<link name=\"" + name + "\"><inertial><origin xyz=\"" + com + "\" rpy=\"0.3 -0.2 0.1\"/>" +
         fmt("<mass value=\"%g\"/>", m) +
         "<inertia ixx=\"0.02\" iyy=\"0.03\" izz=\"0.04\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial>"
         "<collision><geometry><box size=\"0.1 0.1 0.1\"/></geometry></collision></link>";
}

std::string joint(const std::string& type, const std::string& parent, const std::string& child, const std::string& xyz,
                  const std::string& axis) {
  return "<joint name=\"" + child + "_joint\" type=\"" + type + "\"><parent link=\"" + parent + "\"/><child link=\"" +
         child + "\"/><origin xyz=\"" + xyz + "\" rpy=\"0.2 0.1 -0.3\"/><axis xyz=\"" + axis + "\"/>" +
         (type == "prismatic" || type == "revolute" ? "<limit lower=\"-5\" upper=\"5\" effort=\"10\" velocity=\"10\"/>"
                                                    : "") +
         "</joint>";
}

// A floating tree: base, two wheels, an arm of a revolute and a prismatic joint.
RobotModel tree() {
  return load_urdf_string("<robot name=\"tree\">" + link("base", 2.0, "0.05 -0.02 0.01") +
                              link("left", 0.1, "0 0 0") + joint("continuous", "base", "left", "0 0.2 0", "0 1 0") +
                              link("right", 0.1, "0 0.01 0") + joint("continuous", "base", "right", "0 -0.2 0", "0 1 0") +
                              link("upper", 0.5, "0 0 0.15") + joint("revolute", "base", "upper", "0.1 0 0.1", "1 0 0") +
                              link("slider", 0.3, "0.02 0 0.1") +
                              joint("prismatic", "upper", "slider", "0 0 0.3", "0 0.6 0.8") + "</robot>",
                          "tree.urdf");
}

// The same arm on a fixed base (a world joint).
RobotModel fixed_arm() {
  return load_urdf_string("<robot name=\"arm\"><link name=\"world\"/>" + link("base", 2.0, "0 0 0.1") +
                              "<joint name=\"anchor\" type=\"fixed\"><parent link=\"world\"/><child link=\"base\"/>"
                              "<origin xyz=\"0 0 1\"/></joint>" +
                              link("upper", 0.5, "0 0 0.15") + joint("revolute", "base", "upper", "0.1 0 0.1", "1 0 0") +
                              link("fore", 0.4, "0.1 0 0.1") + joint("revolute", "upper", "fore", "0 0 0.3", "0 1 0") +
                              link("slider", 0.3, "0.02 0 0.1") +
                              joint("prismatic", "fore", "slider", "0 0 0.3", "0 0.6 0.8") + "</robot>",
                          "arm.urdf");
}

// The tree falling and turning with its arm bent (frames away from identity).
btMultiBody* moving_tree(physics::Physics& p) {
  physics::Robot& r = p.add_robot(tree(), "tree", pose(0.3, -0.2, 0.5, 0.7, 0.2), {});
  r.set_joint_position(r.joint("upper_joint"), 0.6);
  r.set_joint_position(r.joint("slider_joint"), 0.05);
  r.set_root_velocity(Eigen::Vector3d(0.3, -0.1, 0.2), Eigen::Vector3d(0.5, 0.2, -0.4));
  run(p, 50);
  return r.multibody();
}

// The fixed arm swinging under gravity from a bent pose.
btMultiBody* swinging_arm(physics::Physics& p) {
  physics::Robot& r = p.add_robot(fixed_arm(), "arm", pose(0, 0, 0), {});
  r.set_joint_position(r.joint("upper_joint"), 0.4);
  r.set_joint_position(r.joint("fore_joint"), -0.9);
  run(p, 50);
  return r.multibody();
}

// The seed car sliding and turning on the ground.
btMultiBody* moving_car(physics::Physics& p) {
  physics::Robot& r = p.add_robot(load_urdf_file(std::string(CAR_SOURCE_DIR) + "/test/data/car_camera_lidar04.urdf"),
                                  "car", pose(0, 0, 0.05, 0.4), {});
  r.set_root_velocity(Eigen::Vector3d(0.2, 0.1, 0), Eigen::Vector3d(0, 0, 1.0));
  run(p, 200);
  return r.multibody();
}

// Largest |bullet - ours| over n entries, relative to the largest |bullet|.
double relative_error(const btScalar* bullet, const btScalar* ours, int n) {
  double scale = 0, err = 0;
  for (int i = 0; i < n; ++i) {
    scale = std::max(scale, std::abs(bullet[i]));
    err = std::max(err, std::abs(bullet[i] - ours[i]));
  }
  return err / scale;
}

// Largest |M^-1 f - Bullet's f response| over random f, relative to the largest entry of Bullet's response.
double worst_error(btMultiBody* mb) {
  btAlignedObjectArray<btScalar> r;
  btAlignedObjectArray<btVector3> v;
  btAlignedObjectArray<btMatrix3x3> m;
  // refresh Bullet's cached frames and articulated inertias for the present configuration
  mb->computeAccelerationsArticulatedBodyAlgorithmMultiDof(kDt, r, v, m, false, false, false);
  physics::InverseMass inv;
  EXPECT_TRUE(inv.build(*mb));
  const int n = 6 + mb->getNumDofs();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<btScalar> f(n), bullet(n), ours(n);
  double worst = 0;
  for (int trial = 0; trial < 20; ++trial) {
    for (auto& x : f) x = u(rng);
    mb->calcAccelerationDeltasMultiDof(f.data(), bullet.data(), r, v);
    inv.solve(f.data(), ours.data());
    worst = std::max(worst, relative_error(bullet.data(), ours.data(), n));
  }
  return worst;
}

}  // namespace

TEST(InverseMass, FloatingTreeMatchesBulletsPass) {
  physics::Physics p(flat(), options(), {});
  EXPECT_LT(worst_error(moving_tree(p)), 1e-9);
}

TEST(InverseMass, FixedBaseArmMatchesBulletsPass) {
  physics::Physics p(flat(), options(), {});
  btMultiBody* mb = swinging_arm(p);
  ASSERT_TRUE(mb->isBaseStaticOrKinematic());
  EXPECT_LT(worst_error(mb), 1e-9);
}

TEST(InverseMass, SeedCarMatchesBulletsPass) {
  physics::Physics p(flat(), options(), {});
  EXPECT_LT(worst_error(moving_car(p)), 1e-9);
}

namespace {

// Largest |InverseMass::free_acceleration - Bullet's free-motion pass| over the accelerations, relative to the
// largest of Bullet's, with a force and a torque on every body and an effort on every joint (seeded).
double free_motion_error(btMultiBody* mb) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto vec = [&] { return btVector3(u(rng), u(rng), u(rng)); };
  mb->addBaseForce(vec() + btVector3(0, 0, -9.81 * mb->getBaseMass()));
  mb->addBaseTorque(vec());
  for (int i = 0; i < mb->getNumLinks(); ++i) {
    mb->addLinkForce(i, vec());
    mb->addLinkTorque(i, vec());
    if (mb->getLink(i).m_dofCount == 1) mb->addJointTorque(i, u(rng));
  }
  btAlignedObjectArray<btScalar> r;
  btAlignedObjectArray<btVector3> v;
  btAlignedObjectArray<btMatrix3x3> m;
  // dt 0: Bullet's pass leaves the velocities alone; its accelerations follow the dofs' "Y" entries in r
  mb->computeAccelerationsArticulatedBodyAlgorithmMultiDof(0, r, v, m, false, false, false);
  const int n = 6 + mb->getNumDofs();
  std::vector<btScalar> ours(n);
  physics::InverseMass inv;
  EXPECT_TRUE(physics::InverseMass::free_motion_supported(*mb));
  EXPECT_TRUE(inv.build(*mb));
  inv.free_acceleration(*mb, ours.data());
  mb->clearForcesAndTorques();
  return relative_error(&r[mb->getNumDofs()], ours.data(), n);
}

}  // namespace

TEST(InverseMass, FreeMotionOfAFloatingTreeIsBulletsPass) {
  physics::Physics p(flat(), options(), {});
  btMultiBody* mb = moving_tree(p);
  // the joints moving too: every velocity-product term of the tree counts
  for (int i = 0; i < mb->getNumLinks(); ++i) mb->setJointVel(i, 0.7 - 0.45 * i);
  EXPECT_LT(free_motion_error(mb), 1e-9);
}

TEST(InverseMass, FreeMotionOfAFixedBaseArmIsBulletsPass) {
  physics::Physics p(flat(), options(), {});
  btMultiBody* mb = swinging_arm(p);
  for (int i = 0; i < mb->getNumLinks(); ++i) mb->setJointVel(i, 1.1 - 0.6 * i);
  EXPECT_LT(free_motion_error(mb), 1e-9);
}

TEST(InverseMass, FreeMotionWithDampingAndNoGyroscopicTermIsBulletsPass) {
  physics::Physics p(flat(), options(), {});
  physics::Robot& r = p.add_robot(tree(), "tree", pose(0.3, -0.2, 0.5, 0.7, 0.2), {});
  r.set_root_velocity(Eigen::Vector3d(0.3, -0.1, 0.2), Eigen::Vector3d(0.5, 0.2, -0.4));
  run(p, 20);
  btMultiBody* mb = r.multibody();
  for (int i = 0; i < mb->getNumLinks(); ++i) mb->setJointVel(i, 0.4 + 0.3 * i);
  mb->setLinearDamping(0.04);
  mb->setAngularDamping(0.07);
  mb->setUseGyroTerm(false);
  EXPECT_LT(free_motion_error(mb), 1e-9);
}

TEST(InverseMass, FreeMotionOfTheSeedCarIsBulletsPass) {
  physics::Physics p(flat(), options(), {});
  btMultiBody* mb = moving_car(p);
  for (int i = 0; i < mb->getNumLinks(); ++i) mb->setJointVel(i, 3.0 - 1.5 * i);
  EXPECT_LT(free_motion_error(mb), 1e-9);
}

namespace {

// Largest |InverseMass::contact_jacobian - Bullet's fillContactJacobianMultiDof| over every link of mb (and the
// base) at seeded points and normals, relative to the largest entry of Bullet's.
double contact_jacobian_error(btMultiBody* mb) {
  btAlignedObjectArray<btScalar> r;
  btAlignedObjectArray<btVector3> v;
  btAlignedObjectArray<btMatrix3x3> m;
  mb->computeAccelerationsArticulatedBodyAlgorithmMultiDof(0, r, v, m, false, false, false);
  physics::InverseMass inv;
  EXPECT_TRUE(inv.build(*mb));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 6 + mb->getNumDofs();
  std::vector<btScalar> bullet(n), ours(n);
  btMultiBodyJacobianData data;
  double worst = 0;
  for (int link = -1; link < mb->getNumLinks(); ++link)
    for (int trial = 0; trial < 5; ++trial) {
      const btVector3 p = mb->getBasePos() + btVector3(u(rng), u(rng), u(rng));
      const btVector3 normal = btVector3(u(rng), u(rng), u(rng)).normalized();
      mb->fillContactJacobianMultiDof(link, p, normal, bullet.data(), data.scratch_r, data.scratch_v, data.scratch_m);
      EXPECT_TRUE(inv.contact_jacobian(link, p, normal, ours.data()));
      worst = std::max(worst, relative_error(bullet.data(), ours.data(), n));
    }
  return worst;
}

}  // namespace

TEST(InverseMass, ContactJacobianOfAFloatingTreeIsBullets) {
  physics::Physics p(flat(), options(), {});
  EXPECT_LT(contact_jacobian_error(moving_tree(p)), 1e-12);
}

TEST(InverseMass, ContactJacobianOfAFixedBaseArmIsBullets) {
  physics::Physics p(flat(), options(), {});
  EXPECT_LT(contact_jacobian_error(swinging_arm(p)), 1e-12);
}
