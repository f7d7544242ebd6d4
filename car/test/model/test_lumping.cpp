// Fixed-joint lumping, massless-link dropping and world anchoring as sdformat's URDF reader does them
// (docs/COMPAT-spawn.md). Every expected value is worked out by hand from test/data/zoo/lumping.urdf.
#include <gtest/gtest.h>

#include "car_sim/model.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

const RobotModel& lumped() {
  static const RobotModel m = load_urdf_file(data_path("zoo/lumping.urdf"));
  return m;
}

const Diagnostic* diag(const RobotModel& m, const std::string& code, const std::string& element) {
  for (const auto& d : m.diagnostics)
    if (d.code == code && d.element == element) return &d;
  return nullptr;
}

void expect_at(const Eigen::Vector3d& v, double x, double y, double z) {
  EXPECT_NEAR(v.x(), x, 1e-12);
  EXPECT_NEAR(v.y(), y, 1e-12);
  EXPECT_NEAR(v.z(), z, 1e-12);
}

}  // namespace

TEST(Lumping, KeptLinksAreTheRootMovingChildAndPreservedOnes) {
  // camera_link, imu_link, tool lumped; flap (+ flap_tip) dropped; wheel, bumper, mast kept
  std::vector<std::string> names;
  for (const auto& l : lumped().links) names.push_back(l.name);
  EXPECT_EQ(names, (std::vector<std::string>{"base", "wheel", "bumper", "mast"}));
  std::vector<std::string> joints;
  for (const auto& j : lumped().joints) joints.push_back(j.name);
  EXPECT_EQ(joints, (std::vector<std::string>{"wheel_joint", "bumper_joint", "mast_joint"}));
}

TEST(Lumping, MassComAndInertiaCombined) {
  const Link* b = lumped().find_link("base");
  ASSERT_TRUE(b && b->inertial);
  // m = 2 (base) + 0 (camera_link, no inertial) + 1 (imu_link) + 0 (tool) = 3 kg
  EXPECT_DOUBLE_EQ(b->inertial->mass, 3.0);
  // com = (2 (0,0,0) + 1 (0,0.3,0)) / 3 = (0, 0.1, 0)
  expect_at(b->inertial->origin.translation(), 0.0, 0.1, 0.0);
  // parallel axis about the com: base d = (0,-0.1,0) adds 2 * 0.01 to ixx and izz; imu d = (0,0.2,0) adds
  // 1 * 0.04 to ixx and izz: ixx = 0.1 + 0.01 + 0.02 + 0.04 = 0.17, iyy = 0.2 + 0.01 = 0.21,
  // izz = 0.3 + 0.01 + 0.02 + 0.04 = 0.37, no products
  const Eigen::Matrix3d I = b->inertial->origin.linear() * b->inertial->inertia * b->inertial->origin.linear().transpose();
  EXPECT_NEAR(I(0, 0), 0.17, 1e-12);
  EXPECT_NEAR(I(1, 1), 0.21, 1e-12);
  EXPECT_NEAR(I(2, 2), 0.37, 1e-12);
  EXPECT_NEAR(I(0, 1), 0.0, 1e-12);
}

TEST(Lumping, MasslessCameraCollisionMovesWithComposedPose) {
  const Link* b = lumped().find_link("base");
  ASSERT_EQ(b->collisions.size(), 2u);  // its own box, then camera_link's
  const Shape& c = b->collisions[1];
  EXPECT_EQ(c.lumped_from, "camera_link");
  // camera_joint origin (0.1, 0, 0.05) * collision origin identity
  expect_at(c.origin.translation(), 0.1, 0.0, 0.05);
  EXPECT_DOUBLE_EQ(c.size.x(), 0.02);
}

TEST(Lumping, GazeboBlockOfLumpedLinkAppliesToItsShapesOnly) {
  const Link* b = lumped().find_link("base");
  // <gazebo reference="camera_link"><mu1>0.2</mu1>: camera_link's box gets 0.2, base's own box keeps the default
  EXPECT_EQ(lumped().surface(*b, b->collisions[1]).mu1, std::optional<double>(0.2));
  EXPECT_FALSE(lumped().surface(*b, b->collisions[0]).mu1.has_value());
}

TEST(Lumping, TwiceLumpedVisualComposesBothJoints) {
  const Link* b = lumped().find_link("base");
  const Visual* tool = nullptr;
  for (const auto& v : b->visuals)
    if (v.shape.lumped_from == "tool") tool = &v;
  ASSERT_TRUE(tool);
  // imu_joint (0, 0.3, 0) * tool_joint (0.05, 0, 0) = (0.05, 0.3, 0)
  expect_at(tool->shape.origin.translation(), 0.05, 0.3, 0.0);
}

TEST(Lumping, SensorMovesToParentWithComposedPose) {
  ASSERT_EQ(lumped().sensors.size(), 1u);
  const SensorSpec& s = lumped().sensors[0];
  EXPECT_EQ(s.link, "base");
  EXPECT_EQ(s.lumped_from, "camera_link");
  // camera_joint (0.1, 0, 0.05) * sensor pose (0, 0, 0.01) = (0.1, 0, 0.06)
  expect_at(s.pose.translation(), 0.1, 0.0, 0.06);
  // the sensor plug-in's frameName (a TF frame for its messages) is left as written
  EXPECT_EQ(*find_param(s.plugins[0].params, "frameName"), "camera_link");
}

TEST(Lumping, MovingJointBelowLumpedLinkHangsFromParent) {
  const Joint* j = lumped().find_joint("wheel_joint");
  ASSERT_TRUE(j);
  EXPECT_EQ(j->parent, "base");
  // camera_joint (0.1, 0, 0.05) * wheel_joint (0, 0, -0.1) = (0.1, 0, -0.05)
  expect_at(j->origin.translation(), 0.1, 0.0, -0.05);
}

TEST(Lumping, LumpedLinksStayResolvableAsFrames) {
  std::string link;
  Eigen::Isometry3d T;
  ASSERT_TRUE(lumped().resolve_frame("camera_link", &link, &T));
  EXPECT_EQ(link, "base");
  expect_at(T.translation(), 0.1, 0.0, 0.05);
  ASSERT_TRUE(lumped().resolve_frame("tool", &link, &T));
  EXPECT_EQ(link, "base");
  expect_at(T.translation(), 0.05, 0.3, 0.0);
  expect_at(lumped().link_pose_in_root("tool").translation(), 0.05, 0.3, 0.0);
  EXPECT_FALSE(lumped().resolve_frame("flap", &link, &T));
}

TEST(Lumping, RobotPluginBodyNameOfLumpedLinkBecomesTheParent) {
  // sdformat ReduceSDFExtensionPluginFrameReplace: <bodyName>imu_link</bodyName> -> base
  ASSERT_EQ(lumped().plugins.size(), 1u);
  EXPECT_EQ(*find_param(lumped().plugins[0].params, "bodyName"), "base");
  EXPECT_EQ(*find_param(lumped().plugins[0].params, "frameName"), "world");
}

TEST(Lumping, OneLogLinePerLumpedLink) {
  const Diagnostic* d = diag(lumped(), "link-lumped", "link[camera_link]");
  ASSERT_TRUE(d);
  EXPECT_EQ(d->severity, Severity::Info);
  EXPECT_EQ(d->message,
            "link 'camera_link' lumped into 'base' (fixed joint 'camera_joint'): 1 collision, 1 visual, 1 sensor, "
            "mass 0 kg");
  EXPECT_EQ(d->line, 9);
  EXPECT_TRUE(diag(lumped(), "link-lumped", "link[imu_link]"));
  EXPECT_TRUE(diag(lumped(), "link-lumped", "link[tool]"));
  EXPECT_EQ(lumped().lumped.size(), 3u);
}

TEST(Lumping, MasslessLinkOnMovingJointDroppedWithSubtree) {
  const Diagnostic* d = diag(lumped(), "link-dropped", "link[flap]");
  ASSERT_TRUE(d);
  EXPECT_EQ(d->severity, Severity::Warning);
  EXPECT_EQ(d->message,
            "link 'flap' has no mass (no <inertial> or mass 0) on revolute joint 'flap_joint': Gazebo does not "
            "model it; dropped with its joint and the links below it (flap_tip)");
  ASSERT_EQ(lumped().dropped.size(), 1u);
  EXPECT_EQ(lumped().dropped[0].subtree, std::vector<std::string>{"flap_tip"});
  EXPECT_FALSE(lumped().find_joint("flap_tip_joint"));
}

TEST(Lumping, PreserveAndDisableOptionsKeepTheFixedJoint) {
  // <preserveFixedJoint>true</...> and the attribute form <disableFixedJointLumping value="true"/>
  EXPECT_EQ(lumped().preserved_fixed_joints, (std::set<std::string>{"bumper_joint", "mast_joint"}));
  ASSERT_TRUE(lumped().find_joint("mast_joint"));
  EXPECT_EQ(lumped().find_joint("mast_joint")->type, JointType::Fixed);
}

TEST(Lumping, OffKeepsLinksAsWritten) {
  LoadOptions o;
  o.lump_fixed_joints = false;
  const RobotModel m = load_urdf_file(data_path("zoo/lumping.urdf"), o);
  EXPECT_EQ(m.links.size(), 9u);
  EXPECT_TRUE(m.lumped.empty());
}

TEST(Lumping, MasslessRootIsAnErrorNamingIt) {
  try {
    load_urdf_string("<robot name='r'><link name='a'/><link name='b'/><joint name='j' type='continuous'>"
                     "<parent link='a'/><child link='b'/><axis xyz='0 0 1'/></joint></robot>",
                     "test.urdf");
    FAIL() << "no error";
  } catch (const LoadError& e) {
    EXPECT_EQ(e.element(), "link[a]");
    EXPECT_NE(std::string(e.what()).find("root link 'a' has no mass"), std::string::npos) << e.what();
  }
}

TEST(Lumping, MasslessRootGetsTheMassOfItsFixedChild) {
  // base_footprint (no inertial) -fixed-> base_link (1 kg, 0.1 m up): the root carries 1 kg at z = 0.1
  const RobotModel m = load_urdf_string(
      "<robot name='r'><link name='base_footprint'/><link name='base_link'><inertial><mass value='1'/>"
      "<inertia ixx='0.01' ixy='0' ixz='0' iyy='0.01' iyz='0' izz='0.01'/></inertial></link>"
      "<joint name='j' type='fixed'><parent link='base_footprint'/><child link='base_link'/>"
      "<origin xyz='0 0 0.1'/></joint></robot>");
  ASSERT_EQ(m.links.size(), 1u);
  ASSERT_TRUE(m.links[0].inertial);
  EXPECT_DOUBLE_EQ(m.links[0].inertial->mass, 1.0);
  expect_at(m.links[0].inertial->origin.translation(), 0.0, 0.0, 0.1);
}

TEST(WorldAnchor, FixedJointFromWorldAnchorsAndIsNotLumped) {
  const RobotModel m = load_urdf_string(
      "<robot name='arm'><link name='world'/><link name='base'><inertial><mass value='1'/>"
      "<inertia ixx='0.01' ixy='0' ixz='0' iyy='0.01' iyz='0' izz='0.01'/></inertial></link>"
      "<joint name='fix' type='fixed'><parent link='world'/><child link='base'/></joint></robot>");
  EXPECT_TRUE(m.anchored());
  EXPECT_EQ(m.world_joints, std::vector<std::string>{"fix"});
  EXPECT_EQ(m.root_link, "world");
  EXPECT_TRUE(m.find_link("base"));  // sdformat skips lumping into `world`
  EXPECT_TRUE(m.lumped.empty());
  EXPECT_TRUE(diag(m, "world-anchor", "joint[fix]"));
}

// ---- a robot-level plug-in's offsets at a lumping: sdformat 9's ReduceSDFExtensionPluginFrameReplace ----------

namespace {

// base with imu_link on a fixed joint at `origin` (an <origin> element), and one robot-level plug-in with `keys`:
// the plug-in's keys after loading.
ParamList plugin_after_lumping(const std::string& origin, const std::string& keys) {
  const RobotModel m = load_urdf_string(
      "<robot name='r'><link name='base'><inertial><mass value='1'/><inertia ixx='0.01' iyy='0.01' izz='0.01' "
      "ixy='0' ixz='0' iyz='0'/></inertial></link><link name='imu_link'/><joint name='j' type='fixed'>"
      "<parent link='base'/><child link='imu_link'/>" + origin + "</joint><gazebo><plugin name='p' "
      "filename='libgazebo_ros_imu.so'>" + keys + "</plugin></gazebo></robot>",
      "r.urdf");
  return m.plugins.at(0).params;
}

}  // namespace

// bodyName only, no offsets given: the offset is the identity through inverseTransformToParentFrame,
// R^-1 (0, 0, 0) - t = -t.
TEST(Lumping, PluginOffsetIsMinusTheJointsTranslation) {
  const ParamList p = plugin_after_lumping("<origin xyz='-0.032 0 0.068'/>", "<bodyName>imu_link</bodyName>");
  EXPECT_EQ(*find_param(p, "bodyName"), "base");
  EXPECT_EQ(*find_param(p, "xyzOffset"), "0.032 0 -0.068");
  // urdfdom's getRPY: pitch = asin(-2 (xz - wy)) = asin(-0) = -0
  EXPECT_EQ(*find_param(p, "rpyOffset"), "0 -0 0");
}

// bodyName and frameName both name the link (TurtleBot3's IMU): the rewrite runs twice, the second reading the
// first's result, so the translation counts twice.
TEST(Lumping, PluginOffsetIsRewrittenForBodyNameAndAgainForFrameName) {
  const ParamList p = plugin_after_lumping("<origin xyz='-0.032 0 0.068'/>",
                                           "<bodyName>imu_link</bodyName><frameName>imu_link</frameName>");
  EXPECT_EQ(*find_param(p, "frameName"), "base");
  EXPECT_EQ(*find_param(p, "xyzOffset"), "0.064 0 -0.136");
}

// A turned joint: the rotation written is the joint's inverse, yaw -90 deg, in radians to 6 digits.
TEST(Lumping, PluginRotationIsTheJointsInverse) {
  const ParamList p = plugin_after_lumping("<origin rpy='0 0 1.5707963267948966'/>", "<bodyName>imu_link</bodyName>");
  EXPECT_EQ(*find_param(p, "rpyOffset"), "0 0 -1.5708");
}

// sdformat 9 reads a given rpyOffset in degrees: 90 becomes pi/2.
TEST(Lumping, PluginRpyOffsetIsReadInDegrees) {
  const ParamList p =
      plugin_after_lumping("<origin xyz='0 0 0'/>", "<bodyName>imu_link</bodyName><rpyOffset>0 0 90</rpyOffset>");
  EXPECT_EQ(*find_param(p, "rpyOffset"), "0 -0 1.5708");
}

// A plug-in naming another link keeps its keys as written.
TEST(Lumping, PluginOfAnotherLinkKeepsItsOffsets) {
  const ParamList p = plugin_after_lumping("<origin xyz='1 2 3'/>", "<bodyName>base</bodyName><xyzOffset>0.5 0 0"
                                                                    "</xyzOffset>");
  EXPECT_EQ(*find_param(p, "xyzOffset"), "0.5 0 0");
  EXPECT_EQ(find_param(p, "rpyOffset"), nullptr);
}
