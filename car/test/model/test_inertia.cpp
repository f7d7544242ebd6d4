// Inertia as Gazebo 11 takes it (docs/COMPAT-validation.md "Inertia"): checked on the tensors the physics gets,
// after lumping; a tensor ODE cannot invert is simulated as the identity, with a warning; a negative mass stays an
// error. Values worked out by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "car_sim/description.hpp"
#include "car_sim/model.hpp"
#include "car_sim/sdf_model.hpp"
#include "car_sim/world.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

// One free link with the given <inertia> attributes, 2 kg, a 0.2 m cube.
std::string one_link(const std::string& inertia) {
  return "<robot name='r'><link name='body'><inertial><mass value='2'/><inertia " + inertia +
         "/></inertial><collision><geometry><box size='0.2 0.2 0.2'/></geometry></collision></link></robot>";
}

// A tensor whose principal moments are (1 - sqrt 2, 1, 1 + sqrt 2) x 0.01 kg m^2: the 3 x 3 tridiagonal matrix
// 0.01 [[1 1 0] [1 1 1] [0 1 1]] has eigenvalues 0.01 (1 + 2 cos(k pi / 4)), k = 1, 2, 3.
const char* kIndefinite = "ixx='0.01' ixy='0.01' ixz='0' iyy='0.01' iyz='0.01' izz='0.01'";

const Diagnostic* find_code(const std::vector<Diagnostic>& ds, const std::string& code) {
  for (const auto& d : ds)
    if (d.code == code) return &d;
  return nullptr;
}

// No gravity, no ground: a spawned body only turns under the torque applied to it.
const char* kSpace = "<sdf version='1.6'><world name='space'><gravity>0 0 0</gravity></world></sdf>";

// Angular velocity about z [rad/s] after 1 s of a torque 0.5 N m about z on the robot's link `body`.
double spin_after_one_second(const RobotModel& m) {
  World w(load_world_string(kSpace, "space.world"));
  w.spawn(m, "r", Eigen::Isometry3d::Identity());
  w.apply_wrench(w.find_link("r::body"), Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 0.5), 0.0, -1.0);
  w.step(static_cast<uint64_t>(std::llround(1.0 / w.dt())));
  return w.model_state("r").angular.z();
}

}  // namespace

TEST(Inertia, AnIndefiniteTensorLoadsWithAWarningNamingTheLinkAndMoments) {
  const RobotModel m = load_urdf_string(one_link(kIndefinite), "test.urdf");
  const Diagnostic* d = find_code(m.diagnostics, "inertia-not-positive-definite");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->severity, Severity::Warning);
  EXPECT_EQ(d->element, "link[body]/inertial/inertia");
  EXPECT_EQ(d->message,
            "principal moments (-0.00414214 0.01 0.0241421) kg m^2 are not all > 0: Gazebo 11 (ODE's dBodySetMass) "
            "cannot invert the tensor and simulates the body with 1 kg m^2 about every axis; car does the same");
}

TEST(Inertia, AnIndefiniteTensorTurnsAsTheIdentity) {
  // I = 1 kg m^2 about z: w = tau t / I = 0.5 N m x 1 s / 1 kg m^2 = 0.5 rad/s (with the written tensor, whose
  // z-z moment is 0.01 and which couples z to y, it would not be)
  EXPECT_NEAR(spin_after_one_second(load_urdf_string(one_link(kIndefinite), "test.urdf")), 0.5, 1e-9);
}

TEST(Inertia, AnAllZeroTensorTurnsAsTheIdentity) {
  const RobotModel m = load_urdf_string(one_link("ixx='0' ixy='0' ixz='0' iyy='0' iyz='0' izz='0'"), "test.urdf");
  const Diagnostic* d = find_code(m.diagnostics, "inertia-not-positive-definite");
  ASSERT_NE(d, nullptr);
  EXPECT_NE(d->message.find("principal moments (0 0 0) kg m^2 are not all > 0"), std::string::npos) << d->message;
  EXPECT_NEAR(spin_after_one_second(m), 0.5, 1e-9);
}

TEST(Inertia, AValidTensorTurnsAsWritten) {
  // the reference for the two above: izz 0.25 kg m^2 -> 0.5 / 0.25 = 2 rad/s
  const RobotModel m = load_urdf_string(one_link("ixx='0.25' ixy='0' ixz='0' iyy='0.25' iyz='0' izz='0.25'"), "t.urdf");
  EXPECT_EQ(find_code(m.diagnostics, "inertia-not-positive-definite"), nullptr);
  EXPECT_NEAR(spin_after_one_second(m), 2.0, 1e-9);
}

TEST(Inertia, AZeroTensorOnALumpedLinkIsNoFinding) {
  // the plate (0.5 kg, tensor 0) is lumped into the body 0.1 m along x: the body's tensor stays positive definite
  const std::string xml =
      "<robot name='r'><link name='body'><inertial><mass value='2'/>"
      "<inertia ixx='0.01' ixy='0' ixz='0' iyy='0.01' iyz='0' izz='0.01'/></inertial></link>"
      "<joint name='fix' type='fixed'><parent link='body'/><child link='plate'/><origin xyz='0.1 0 0'/></joint>"
      "<link name='plate'><inertial><mass value='0.5'/><inertia ixx='0' ixy='0' ixz='0' iyy='0' iyz='0' izz='0'/>"
      "</inertial></link></robot>";
  const RobotModel m = load_urdf_string(xml, "test.urdf");
  for (const auto& d : m.diagnostics) EXPECT_NE(d.severity, Severity::Error) << d.element << ": " << d.message;
  EXPECT_EQ(find_code(m.diagnostics, "inertia-not-positive-definite"), nullptr);
  ASSERT_EQ(m.links.size(), 1u);
  // parallel axis: com at 0.02 m; izz = 0.01 + 2 (0.02)^2 + 0.5 (0.08)^2 = 0.014 kg m^2
  EXPECT_NEAR(m.links[0].inertial->inertia(2, 2), 0.014, 1e-12);
}

TEST(Inertia, TheTriangleInequalityBrokenWarnsAndIsSimulatedAsWritten) {
  const RobotModel m = load_urdf_string(one_link("ixx='0.1' ixy='0' ixz='0' iyy='0.1' iyz='0' izz='0.25'"), "t.urdf");
  const Diagnostic* d = find_code(m.diagnostics, "inertia-triangle");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->severity, Severity::Warning);
  EXPECT_EQ(d->message,
            "principal moments (0.1 0.1 0.25) kg m^2 break the triangle inequality I1 + I2 >= I3 (no rigid body has "
            "them); simulated as written, as in Gazebo 11");
  // izz 0.25 kg m^2 as written: 0.5 / 0.25 = 2 rad/s
  EXPECT_NEAR(spin_after_one_second(m), 2.0, 1e-9);
}

TEST(Inertia, ANegativeMassStaysAnError) {
  try {
    load_urdf_string(
        "<robot name='r'><link name='body'><inertial><mass value='-1'/>"
        "<inertia ixx='0.1' ixy='0' ixz='0' iyy='0.1' iyz='0' izz='0.1'/></inertial></link></robot>",
        "test.urdf");
    FAIL() << "a negative mass loaded";
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("link[body]/inertial/mass: mass -1 kg is not > 0"), std::string::npos)
        << e.what();
  }
}

TEST(Inertia, AnSdfRobotsIndefiniteTensorWarnsAndLoads) {
  const std::string sdf =
      "<sdf version='1.6'><model name='m'><link name='body'><inertial><mass>2</mass><inertia><ixx>0.01</ixx>"
      "<ixy>0.01</ixy><ixz>0</ixz><iyy>0.01</iyy><iyz>0.01</iyz><izz>0.01</izz></inertia></inertial></link>"
      "</model></sdf>";
  const SdfRobot r = load_sdf_model_string(sdf, "m.sdf");
  const Diagnostic* d = find_code(r.model.diagnostics, "inertia-not-positive-definite");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->element, "model[m]/link[body]/inertial/inertia");
  EXPECT_NE(d->message.find("(-0.00414214 0.01 0.0241421)"), std::string::npos) << d->message;
}

TEST(Inertia, AWorldModelsIndefiniteTensorWarnsAndTurnsAsTheIdentity) {
  // libsdformat 12's DOM says LINK_INERTIA_INVALID and "Failed to load a world." but keeps the world; Gazebo 11
  // (sdformat 9's element tree) loads it, and so does car, with its own warning
  const std::string world =
      "<sdf version='1.6'><world name='space'><gravity>0 0 0</gravity><model name='crate'><link name='body'>"
      "<inertial><mass>2</mass><inertia><ixx>0.01</ixx><ixy>0.01</ixy><ixz>0</ixz><iyy>0.01</iyy><iyz>0.01</iyz>"
      "<izz>0.01</izz></inertia></inertial></link></model></world></sdf>";
  WorldDescription desc = load_world_string(world, "crate.world");
  const Diagnostic* d = find_code(desc.diagnostics, "inertia-not-positive-definite");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->element, "model[crate]/link[body]/inertial/inertia");
  World w(std::move(desc));
  w.apply_wrench(w.find_link("crate::body"), Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 0.5), 0.0, -1.0);
  w.step(static_cast<uint64_t>(std::llround(1.0 / w.dt())));
  EXPECT_NEAR(w.model_state("crate").angular.z(), 0.5, 1e-9);
}
