// Core model loading: values worked out by hand from the seed's xacro files (urdf/car.xacro & co).
#include <gtest/gtest.h>

#include <cmath>

#include "car_sim/model.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

const RobotModel& car() {
  // The seed's full car, expanded by xacro (test_fixtures.py keeps this file equal to a fresh expansion).
  // Links as written (no lumping): these tests check what the reader reads; test_lumping.cpp checks the merge.
  LoadOptions o;
  o.lump_fixed_joints = false;
  static const RobotModel m = load_urdf_string(read_text("test/data/car_camera_lidar04.urdf"), "car04", o);
  return m;
}

bool has_diag(const RobotModel& m, const std::string& code, const std::string& element) {
  for (const auto& d : m.diagnostics)
    if (d.code == code && d.element == element) return true;
  return false;
}

std::string load_error_of(const std::string& xml) {
  try {
    load_urdf_string(xml, "test.urdf");
  } catch (const LoadError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Model, SeedCarHasNineLinksInDocumentOrder) {
  const std::vector<std::string> expected = {"base_footprint", "base_link", "left_wheel", "right_wheel",
                                             "front_wheel", "back_wheel", "camera", "support", "laser"};
  ASSERT_EQ(car().links.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(car().links[i].name, expected[i]);
  EXPECT_EQ(car().root_link, "base_footprint");
  EXPECT_EQ(car().name, "mycar");
}

TEST(Model, BaseLinkMassAndIzzFromCylinderMacro) {
  const Link* l = car().find_link("base_link");
  ASSERT_TRUE(l && l->inertial);
  EXPECT_DOUBLE_EQ(l->inertial->mass, 2.0);
  // izz = m r^2 / 2 = 2 * 0.1^2 / 2
  EXPECT_NEAR(l->inertial->inertia(2, 2), 0.01, 1e-12);
  // ixx = m (3 r^2 + h^2) / 12 = 2 (0.03 + 0.0064) / 12
  EXPECT_NEAR(l->inertial->inertia(0, 0), 2.0 * (3 * 0.01 + 0.0064) / 12.0, 1e-12);
}

TEST(Model, LeftWheelJointOrigin) {
  const Joint* j = car().find_joint("left2link");
  ASSERT_TRUE(j);
  EXPECT_EQ(j->type, JointType::Continuous);
  EXPECT_EQ(j->parent, "base_link");
  EXPECT_EQ(j->child, "left_wheel");
  // (0, 0.1 * flag, wheel_radius - (base_length/2 + lidi)) = (0, 0.1, 0.0325 - 0.055)
  EXPECT_NEAR(j->origin.translation().x(), 0.0, 1e-12);
  EXPECT_NEAR(j->origin.translation().y(), 0.1, 1e-12);
  EXPECT_NEAR(j->origin.translation().z(), -0.0225, 1e-12);
  EXPECT_TRUE(j->axis.isApprox(Eigen::Vector3d::UnitY()));
}

TEST(Model, CasterAxisIsNormalisedAndReported) {
  const Joint* j = car().find_joint("front2link");
  ASSERT_TRUE(j);
  const double c = 1.0 / std::sqrt(3.0);
  EXPECT_NEAR(j->axis.x(), c, 1e-12);
  EXPECT_NEAR(j->axis.y(), c, 1e-12);
  EXPECT_NEAR(j->axis.z(), c, 1e-12);
  EXPECT_TRUE(j->axis_as_written.isApprox(Eigen::Vector3d(1, 1, 1)));
  EXPECT_TRUE(has_diag(car(), "axis-normalised", "joint[front2link]/axis"));
  EXPECT_TRUE(has_diag(car(), "axis-normalised", "joint[back2link]/axis"));
}

TEST(Model, CameraColourOutOfRangeIsReported) {
  EXPECT_TRUE(has_diag(car(), "colour-range", "link[camera]/visual/material[no]/color"));
  // urdfdom drops the colour; the core keeps no rgba for that visual.
  const Link* cam = car().find_link("camera");
  ASSERT_TRUE(cam);
  ASSERT_EQ(cam->visuals.size(), 1u);
  EXPECT_FALSE(cam->visuals[0].material.has_rgba);
}

TEST(Model, AxisOnFixedJointIsOnlyAnInfo) {
  for (const auto& d : car().diagnostics) {
    if (d.element == "joint[camera2baselink]/axis") EXPECT_EQ(d.severity, Severity::Info);
  }
  EXPECT_TRUE(has_diag(car(), "axis-ignored", "joint[camera2baselink]/axis"));
}

TEST(Model, LaserPoseInRootFollowsFixedJoints) {
  // base_footprint -> base_link z 0.055, -> support z 0.04 + 0.075, -> laser z 0.075 + 0.025
  const Eigen::Isometry3d T = car().link_pose_in_root("laser");
  EXPECT_NEAR(T.translation().z(), 0.055 + 0.115 + 0.1, 1e-12);
}

TEST(Model, GazeboMaterialsAndDefaultFriction) {
  const Link* l = car().find_link("left_wheel");
  ASSERT_TRUE(l);
  EXPECT_EQ(l->gazebo.material, "Gazebo/Red");
  EXPECT_FALSE(l->gazebo.mu1.has_value());  // no <mu1>: Gazebo's default 1 applies
  EXPECT_EQ(car().find_link("base_link")->gazebo.material, "Gazebo/Yellow");
}

TEST(Model, WheelCollisionIsCylinderRotatedAboutX) {
  const Link* l = car().find_link("right_wheel");
  ASSERT_TRUE(l);
  ASSERT_EQ(l->collisions.size(), 1u);
  const Shape& s = l->collisions[0];
  EXPECT_EQ(s.type, ShapeType::Cylinder);
  EXPECT_DOUBLE_EQ(s.radius, 0.0325);
  EXPECT_DOUBLE_EQ(s.length, 0.015);
  // rpy (pi/2, 0, 0): the cylinder's z axis lies along the link's -y... +y up to sign
  EXPECT_NEAR(std::abs((s.origin.linear() * Eigen::Vector3d::UnitZ()).y()), 1.0, 1e-6);
}

TEST(Model, RobotPluginAndSensorsFound) {
  ASSERT_EQ(car().plugins.size(), 1u);
  EXPECT_EQ(car().plugins[0].filename, "libgazebo_ros_diff_drive.so");
  ASSERT_EQ(car().sensors.size(), 2u);
  EXPECT_EQ(car().sensors[0].name, "rplidar");
  EXPECT_EQ(car().sensors[0].link, "laser");
  EXPECT_DOUBLE_EQ(car().sensors[0].update_rate, 5.5);
  EXPECT_EQ(car().sensors[1].name, "camera");
  EXPECT_EQ(car().sensors[1].type, "depth");
}

TEST(Model, DuplicateSensorKeepsTheLaterOne) {
  // camera01.xacro and kinect.xacro both define depth sensor "camera" on "support"; kinect's comes last.
  EXPECT_TRUE(has_diag(car(), "sensor-duplicate", "gazebo[support]/sensor[camera]"));
  const auto& s = car().sensors[1];
  ASSERT_EQ(s.plugins.size(), 1u);
  EXPECT_EQ(*find_param(s.plugins[0].params, "frameName"), "support_depth");
}

// ---- bad input: each error names the file, the element and the reason ------------------------------

TEST(ModelErrors, MissingFile) {
  try {
    load_urdf_file("/nonexistent/car.urdf");
    FAIL() << "no error";
  } catch (const LoadError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/car.urdf: cannot open file");
  }
}

TEST(ModelErrors, MalformedXmlNamesTheLine) {
  try {
    load_urdf_file(data_path("bad/malformed.urdf"));
    FAIL() << "no error";
  } catch (const LoadError& e) {
    EXPECT_EQ(e.file(), data_path("bad/malformed.urdf"));
    // tinyxml2 names the element left open: <link> on line 3
    EXPECT_EQ(e.line(), 3);
    EXPECT_EQ(e.reason(), "malformed XML: mismatched element: XMLElement name=link");
  }
}

// A document without a source name (a SpawnModel request with an empty model_name; test/fuzz/fuzz_spawn's first
// finding) is named "<string>" in its error, never "": the message keeps FILE[:LINE]: ELEMENT: REASON.
TEST(ModelErrors, AnUnnamedDocumentIsNamedStringInItsError) {
  try {
    load_urdf_string("", "");
    FAIL() << "no error";
  } catch (const LoadError& e) {
    EXPECT_EQ(e.file(), "<string>");
    EXPECT_STREQ(e.what(), "<string>: malformed XML: empty document");
  }
}

TEST(ModelErrors, ANulInTheDocumentsNameIsWrittenOutNotCutAt) {
  // a SpawnModel model_name may hold a NUL (test/fuzz/fuzz_spawn): the message goes on past it
  try {
    load_urdf_string("", std::string("r\0bot", 5));
    FAIL() << "no error";
  } catch (const LoadError& e) {
    EXPECT_EQ(e.file(), "r\\x00bot");
    EXPECT_STREQ(e.what(), "r\\x00bot: malformed XML: empty document");
  }
}

TEST(ModelErrors, ZeroMassNamesTheLink) {
  try {
    load_urdf_file(data_path("bad/zero_mass.urdf"));
    FAIL() << "no error";
  } catch (const LoadError& e) {
    // mass 0 is massless for Gazebo (sdformat CreateSDF): a massless root leaves nothing to model
    EXPECT_EQ(e.element(), "link[base_link]");
    EXPECT_EQ(e.reason(), "root link 'base_link' has no mass (no <inertial> or mass 0), also after lumping the links "
                          "fixed to it; Gazebo models nothing of this robot");
    EXPECT_EQ(e.line(), 3);
  }
}

TEST(ModelErrors, ZeroAxisNamesTheJoint) {
  try {
    load_urdf_file(data_path("bad/zero_axis.urdf"));
    FAIL() << "no error";
  } catch (const LoadError& e) {
    EXPECT_EQ(e.element(), "joint[wheel_joint]/axis");
    EXPECT_EQ(e.reason(), "axis has zero length; a continuous joint needs a direction");
  }
}

TEST(ModelErrors, NotARobot) {
  EXPECT_EQ(load_error_of("<sdf version='1.7'><world name='w'/></sdf>"),
            "test.urdf:1: sdf: root element is not <robot>; is this a URDF?");
}

TEST(ModelErrors, UrdfdomRejectionSaysWhy) {
  const std::string msg = load_error_of(
      "<robot name='r'><link name='a'/><joint name='j' type='fixed'><parent link='a'/><child link='b'/></joint>"
      "</robot>");
  EXPECT_NE(msg.find("test.urdf: robot: "), std::string::npos) << msg;
  EXPECT_NE(msg.find("b"), std::string::npos) << msg;
}

TEST(ModelErrors, KeepAllFindingsWhenAsked) {
  LoadOptions o;
  o.throw_on_error = false;
  const RobotModel m = load_urdf_file(data_path("bad/zero_mass.urdf"), o);
  ASSERT_EQ(m.diagnostics.size(), 1u);
  EXPECT_EQ(m.diagnostics[0].severity, Severity::Error);
  // mass 0 is "massless" (Gazebo does not model the link); on the root, nothing of the robot is left
  EXPECT_EQ(m.diagnostics[0].code, "root-massless");
}
