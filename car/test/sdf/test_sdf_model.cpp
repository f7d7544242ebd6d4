// SDF robots (docs/COMPAT-sdf.md): an SDF model read into the RobotModel the URDF path fills. Expected values are
// worked out by hand from the documents below.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "car_sim/plugins.hpp"
#include "car_sim/sdf_model.hpp"
#include "car_sim/world.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

const double kHalfPi = M_PI / 2.0;

std::string sdf(const std::string& body, const std::string& version = "1.7") {
  return "<?xml version='1.0'?><sdf version='" + version + "'>" + body + "</sdf>";
}

const char* kInertial =
    "<inertial><mass>2</mass><inertia><ixx>0.1</ixx><iyy>0.2</iyy><izz>0.25</izz><ixy>0</ixy><ixz>0</ixz><iyz>0</iyz>"
    "</inertia></inertial>";

std::string lnk(const std::string& name, const std::string& inner = "") {
  return "<link name='" + name + "'>" + std::string(kInertial) + inner + "</link>";
}

std::string joint(const std::string& name, const std::string& type, const std::string& parent, const std::string& child,
                  const std::string& inner = "") {
  return "<joint name='" + name + "' type='" + type + "'><parent>" + parent + "</parent><child>" + child +
         "</child>" + inner + "</joint>";
}

// The robotNamespace values of a plug-in, in order ("<none>" when it has none).
std::string ns_of(const PluginSpec& p) {
  std::string out;
  int n = 0;
  for (const auto& kv : p.params)
    if (kv.first == "robotNamespace") out += (n++ ? "|" : "") + kv.second;
  return n ? out : "<none>";
}

}  // namespace

// SDF default (rule 3): no <inertial> = 1 kg with unit inertia at the link origin (URDF would make it massless).
TEST(SdfModel, LinkWithoutInertialHasOneKilogramAndUnitInertia) {
  const SdfRobot r = load_sdf_model_string(sdf("<model name='m'><link name='a'/></model>"));
  ASSERT_EQ(r.model.links.size(), 1u);
  ASSERT_TRUE(r.model.links[0].inertial.has_value());
  EXPECT_DOUBLE_EQ(r.model.links[0].inertial->mass, 1.0);
  EXPECT_TRUE(r.model.links[0].inertial->inertia.isApprox(Eigen::Matrix3d::Identity()));
  EXPECT_TRUE(r.model.links[0].inertial->origin.isApprox(Eigen::Isometry3d::Identity()));
  EXPECT_EQ(r.model.root_link, "a");
}

TEST(SdfModel, WrittenInertialIsKept) {
  const SdfRobot r = load_sdf_model_string(sdf("<model name='m'>" + lnk("a") + "</model>"));
  EXPECT_DOUBLE_EQ(r.model.links[0].inertial->mass, 2.0);
  EXPECT_DOUBLE_EQ(r.model.links[0].inertial->inertia(1, 1), 0.2);
  EXPECT_DOUBLE_EQ(r.model.links[0].inertial->inertia(2, 2), 0.25);
}

// Rule 4: b is 1 m along x of a and turned 90 deg about z; c is placed relative to a frame 2 m along y of a,
// 0.5 m above it. Joint origins are the child frames in the parent frames.
TEST(SdfModel, PosesRelativeToResolveThroughFrames) {
  const SdfRobot r = load_sdf_model_string(sdf(
      "<model name='m'>" + lnk("a", "<pose>0 0 1 0 0 0</pose>") +
      "<frame name='f'><pose relative_to='a'>0 2 0 0 0 0</pose></frame>" +
      "<link name='b'><pose relative_to='a'>1 0 0 0 0 1.5707963267948966</pose></link>" +
      "<link name='c'><pose relative_to='f'>0 0 0.5 0 0 0</pose></link>" + joint("ab", "fixed", "a", "b") +
      joint("ac", "fixed", "a", "c") + "</model>"));
  const Joint* ab = r.model.find_joint("ab");
  const Joint* ac = r.model.find_joint("ac");
  ASSERT_TRUE(ab && ac);
  EXPECT_TRUE(ab->origin.translation().isApprox(Eigen::Vector3d(1, 0, 0), 1e-12));
  EXPECT_TRUE(ab->origin.linear().isApprox(Eigen::AngleAxisd(kHalfPi, Eigen::Vector3d::UnitZ()).toRotationMatrix(),
                                           1e-12));
  EXPECT_TRUE(ac->origin.translation().isApprox(Eigen::Vector3d(0, 2, 0.5), 1e-12));
  // the root link a sits 1 m above the model frame
  EXPECT_TRUE(r.root_pose.translation().isApprox(Eigen::Vector3d(0, 0, 1), 1e-12));
}

// Rule 11: the spawn pose goes on top of the model's own pose: model at (1, 2, 0), spawned at (3, 0, 0) turned
// 90 deg: root at (3, 0, 0) + R(90)(1, 2, 0) = (3 - 2, 1, 0) = (1, 1, 0).
TEST(SdfModel, SpawnPoseComposesWithModelPose) {
  const SdfRobot r = load_sdf_model_string(sdf("<model name='m'><pose>1 2 0 0 0 0</pose>" + lnk("a") + "</model>"));
  World w(empty_world());
  w.spawn_sdf(r, "bot", at(3, 0, kHalfPi));
  const Eigen::Vector3d p = w.model_state("bot").pose.translation();
  EXPECT_NEAR(p.x(), 1.0, 1e-9);
  EXPECT_NEAR(p.y(), 1.0, 1e-9);
}

// Gazebo reports and sets a model's pose as its model frame (Model::WorldPose, SetWorldPose; gazebo_ros
// get/set_model_state), not its root link's. Root link 'a' at (0.5, 0, 0) turned 90 deg in the model; spawned at
// (3, 0, 0) turned 90 deg: the model frame is the spawn pose, the link at (3, 0) + R(90)(0.5, 0) = (3, 0.5), yaw 180.
// Reporting the link (car before) gives (3, 0.5), 0.5 m off.
TEST(SdfModel, ModelStateIsTheModelFrameNotTheRootLink) {
  const SdfRobot r =
      load_sdf_model_string(sdf("<model name='m'>" + lnk("a", "<pose>0.5 0 0 0 0 1.5707963267948966</pose>") +
                                "</model>"));
  World w(empty_world());
  w.spawn_sdf(r, "bot", at(3, 0, kHalfPi));
  const Eigen::Isometry3d model = w.model_state("bot").pose;
  EXPECT_NEAR(model.translation().x(), 3.0, 1e-9);
  EXPECT_NEAR(model.translation().y(), 0.0, 1e-9);
  EXPECT_NEAR(Eigen::AngleAxisd(model.linear()).angle(), kHalfPi, 1e-9);
  const Eigen::Isometry3d link = w.link_state({"bot", "a", true}).pose;
  EXPECT_NEAR(link.translation().x(), 3.0, 1e-9);
  EXPECT_NEAR(link.translation().y(), 0.5, 1e-9);
}

// set_model_state places the model frame: the same model set to (1, 2, 0) with no turn puts link 'a' at
// (1.5, 2, 0) turned 90 deg, and the model reads back (1, 2, 0). Setting the root link there instead (car before)
// puts link 'a' at (1, 2, 0).
TEST(SdfModel, SetModelStatePlacesTheModelFrame) {
  const SdfRobot r =
      load_sdf_model_string(sdf("<model name='m'>" + lnk("a", "<pose>0.5 0 0 0 0 1.5707963267948966</pose>") +
                                "</model>"));
  World w(empty_world());
  w.spawn_sdf(r, "bot", at(0, 0, 0));
  ModelState target;
  target.pose = at(1, 2, 0);
  w.set_model_state("bot", target);
  const Eigen::Isometry3d link = w.link_state({"bot", "a", true}).pose;
  EXPECT_NEAR(link.translation().x(), 1.5, 1e-9);
  EXPECT_NEAR(link.translation().y(), 2.0, 1e-9);
  EXPECT_NEAR(Eigen::AngleAxisd(link.linear()).angle(), kHalfPi, 1e-9);
  const Eigen::Vector3d back = w.model_state("bot").pose.translation();
  EXPECT_NEAR(back.x(), 1.0, 1e-9);
  EXPECT_NEAR(back.y(), 2.0, 1e-9);
}

TEST(SdfModel, JointTypesMapOntoTheCore) {
  const SdfRobot r = load_sdf_model_string(sdf(
      "<model name='m'>" + lnk("a") + lnk("b") + lnk("c") + lnk("d") + lnk("e") + lnk("f") +
      joint("rev", "revolute", "a", "b", "<axis><xyz>0 1 0</xyz><limit><lower>-0.5</lower><upper>0.7</upper>"
                                      "<effort>3</effort><velocity>4</velocity></limit><dynamics><damping>0.2"
                                      "</damping><friction>0.1</friction></dynamics></axis>") +
      joint("free", "revolute", "a", "c", "<axis><xyz>0 0 1</xyz></axis>") +
      joint("cont", "continuous", "a", "d", "<axis><xyz>1 0 0</xyz></axis>") +
      joint("pri", "prismatic", "a", "e", "<axis><xyz>0 0 2</xyz><limit><lower>0</lower><upper>0.3</upper></limit>"
                                       "</axis>") +
      joint("fix", "fixed", "a", "f") + "</model>"));
  const auto& m = r.model;
  EXPECT_EQ(m.find_joint("rev")->type, JointType::Revolute);
  EXPECT_TRUE(m.find_joint("rev")->axis.isApprox(Eigen::Vector3d(0, 1, 0)));
  ASSERT_TRUE(m.find_joint("rev")->limits.has_value());
  EXPECT_DOUBLE_EQ(m.find_joint("rev")->limits->lower, -0.5);
  EXPECT_DOUBLE_EQ(m.find_joint("rev")->limits->upper, 0.7);
  EXPECT_DOUBLE_EQ(m.find_joint("rev")->limits->effort, 3.0);
  EXPECT_DOUBLE_EQ(m.find_joint("rev")->limits->velocity, 4.0);
  EXPECT_DOUBLE_EQ(m.find_joint("rev")->damping, 0.2);
  EXPECT_DOUBLE_EQ(m.find_joint("rev")->friction, 0.1);
  // a revolute joint with SDF's default limits (-1e16, 1e16) turns freely
  EXPECT_EQ(m.find_joint("free")->type, JointType::Continuous);
  EXPECT_EQ(m.find_joint("cont")->type, JointType::Continuous);
  EXPECT_EQ(m.find_joint("pri")->type, JointType::Prismatic);
  EXPECT_TRUE(m.find_joint("pri")->axis.isApprox(Eigen::Vector3d(0, 0, 1)));  // (0 0 2) normalised
  EXPECT_EQ(m.find_joint("fix")->type, JointType::Fixed);
  // SDF keeps fixed joints (no lumping): six links
  EXPECT_EQ(m.links.size(), 6u);
}

// Rule 6: an axis written in the model frame is resolved into the child frame: child b turned 90 deg about z,
// model x = b's -y.
TEST(SdfModel, AxisExpressedInModelFrameIsResolvedIntoTheChild) {
  const SdfRobot r = load_sdf_model_string(sdf(
      "<model name='m'>" + lnk("a") + lnk("b", "<pose>0 0 0 0 0 1.5707963267948966</pose>") +
      joint("j", "revolute", "a", "b", "<axis><xyz expressed_in='__model__'>1 0 0</xyz><limit><lower>-1</lower>"
                                    "<upper>1</upper></limit></axis>") + "</model>"));
  EXPECT_TRUE(r.model.find_joint("j")->axis.isApprox(Eigen::Vector3d(0, -1, 0), 1e-12));
}

TEST(SdfModel, BallJointIsAClearError) {
  try {
    load_sdf_model_string(sdf("<model name='m'>" + lnk("a") + lnk("b") + joint("shoulder", "ball", "a", "b") +
                              "</model>"), "arm.sdf");
    FAIL() << "a ball joint must be refused";
  } catch (const LoadError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("arm.sdf"), std::string::npos) << what;
    EXPECT_NE(what.find("joint[shoulder]"), std::string::npos) << what;
    EXPECT_NE(what.find("'ball'"), std::string::npos) << what;
  }
}

TEST(SdfModel, UnknownJointTypeNamesFileAndReason) {
  try {
    load_sdf_model_string(sdf("<model name='m'>" + lnk("a") + lnk("b") + joint("j", "hinge", "a", "b") +
                              "</model>"), "bad_joint.sdf");
    FAIL() << "an unknown joint type must be refused";
  } catch (const LoadError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("bad_joint.sdf"), std::string::npos) << what;
    EXPECT_NE(what.find("hinge"), std::string::npos) << what;
  }
}

TEST(SdfModel, MalformedXmlNamesFileAndLine) {
  try {
    load_sdf_model_string("<?xml version='1.0'?>\n<sdf version='1.7'>\n<model name='m'>\n<link name='a'>\n</model>",
                          "broken.sdf");
    FAIL();
  } catch (const LoadError& e) {
    EXPECT_EQ(e.file(), "broken.sdf");
    EXPECT_GT(e.line(), 0);
    EXPECT_NE(std::string(e.what()).find("malformed XML"), std::string::npos) << e.what();
  }
}

TEST(SdfModel, SecondFreeBodyIsRefused) {
  try {
    load_sdf_model_string(sdf("<model name='m'>" + lnk("a") + lnk("loose") + "</model>"), "two.sdf");
    FAIL();
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("link[loose]"), std::string::npos) << e.what();
  }
}

// Rule 8: <surface> values land on the fields the URDF <gazebo reference> block fills.
TEST(SdfModel, SurfaceMapsOntoGazeboLinkFields) {
  const SdfRobot r = load_sdf_model_string(sdf(
      "<model name='m'><link name='a'><collision name='c'><geometry><box><size>1 2 3</size></box></geometry>"
      "<surface><friction><ode><mu>0.3</mu><mu2>0.4</mu2><fdir1>0 1 0</fdir1></ode></friction>"
      "<contact><ode><kp>1e5</kp><kd>20</kd><min_depth>0.002</min_depth><max_vel>0.5</max_vel></ode></contact>"
      "</surface></collision></link></model>"));
  const Link& l = r.model.links[0];
  ASSERT_EQ(l.collisions.size(), 1u);
  EXPECT_EQ(l.collisions[0].type, ShapeType::Box);
  EXPECT_TRUE(l.collisions[0].size.isApprox(Eigen::Vector3d(1, 2, 3)));
  EXPECT_DOUBLE_EQ(*l.gazebo.mu1, 0.3);
  EXPECT_DOUBLE_EQ(*l.gazebo.mu2, 0.4);
  EXPECT_TRUE(l.gazebo.fdir1->isApprox(Eigen::Vector3d(0, 1, 0)));
  EXPECT_DOUBLE_EQ(*l.gazebo.kp, 1e5);
  EXPECT_DOUBLE_EQ(*l.gazebo.kd, 20.0);
  EXPECT_DOUBLE_EQ(*l.gazebo.min_depth, 0.002);
  EXPECT_DOUBLE_EQ(*l.gazebo.max_vel, 0.5);
}

TEST(SdfModel, UnwrittenSurfaceKeepsGazeboDefaults) {
  const SdfRobot r = load_sdf_model_string(sdf(
      "<model name='m'><link name='a'><collision name='c'><geometry><sphere><radius>0.5</radius></sphere>"
      "</geometry></collision></link></model>"));
  EXPECT_FALSE(r.model.links[0].gazebo.mu1.has_value());
  EXPECT_FALSE(r.model.links[0].gazebo.kp.has_value());
  EXPECT_DOUBLE_EQ(r.model.links[0].collisions[0].radius, 0.5);
}

// Rule 1: an SDF 1.4 document is converted by sdformat; its defaults are the same.
TEST(SdfModel, Sdf14DocumentLoads) {
  const SdfRobot r = load_sdf_model_string(sdf(
      "<model name='m'><link name='a'><pose>0 0 0.5 0 0 0</pose></link><link name='b'/>"
      "<joint name='j' type='revolute'><parent>a</parent><child>b</child><axis><xyz>0 0 1</xyz>"
      "<limit><lower>-1</lower><upper>1</upper></limit></axis></joint></model>", "1.4"));
  EXPECT_DOUBLE_EQ(r.model.find_link("b")->inertial->mass, 1.0);
  EXPECT_EQ(r.model.find_joint("j")->type, JointType::Revolute);
  // b at the model origin, a 0.5 m up: b in a is 0.5 m down
  EXPECT_TRUE(r.model.find_joint("j")->origin.translation().isApprox(Eigen::Vector3d(0, 0, -0.5), 1e-12));
}

// Rule 12: a static model hangs from `world`.
TEST(SdfModel, StaticModelIsAnchored) {
  const SdfRobot r = load_sdf_model_string(sdf("<model name='m'><static>true</static>" + lnk("a") + "</model>"));
  EXPECT_TRUE(r.is_static);
  EXPECT_TRUE(r.model.anchored());
  EXPECT_EQ(r.model.root_link, "world");
}

const char* kRobot =
    "<model name='bot'><link name='base'><sensor name='scan' type='ray'><pose>0.1 0 0.2 0 0 0</pose>"
    "<update_rate>10</update_rate><ray><scan><horizontal><samples>90</samples><min_angle>-0.7</min_angle>"
    "<max_angle>0.7</max_angle></horizontal></scan><range><min>0.1</min><max>10</max></range></ray>"
    "<plugin name='laser' filename='libgazebo_ros_laser.so'>SENSOR_NS<topicName>scan</topicName>"
    "<frameName>base</frameName></plugin></sensor></link>"
    "<plugin name='p3d' filename='libgazebo_ros_p3d.so'>MODEL_NS<bodyName>base</bodyName><topicName>odom</topicName>"
    "<updateRate>10</updateRate></plugin></model>";

std::string robot_with(const std::string& model_ns, const std::string& sensor_ns) {
  std::string s = kRobot;
  s.replace(s.find("SENSOR_NS"), 9, sensor_ns);
  s.replace(s.find("MODEL_NS"), 8, model_ns);
  return sdf(s);
}

// Rule 10: plug-ins and sensors read into the same specs as the URDF path; the sensor pose and lines are SDF's.
TEST(SdfModel, PluginsAndSensorsAreRead) {
  const SdfRobot r = load_sdf_model_string(robot_with("", ""));
  ASSERT_EQ(r.model.plugins.size(), 1u);
  EXPECT_EQ(r.model.plugins[0].filename, "libgazebo_ros_p3d.so");
  EXPECT_EQ(*find_param(r.model.plugins[0].params, "bodyName"), "base");
  ASSERT_EQ(r.model.sensors.size(), 1u);
  const SensorSpec& s = r.model.sensors[0];
  EXPECT_EQ(s.type, "ray");
  EXPECT_EQ(s.link, "base");
  EXPECT_DOUBLE_EQ(s.update_rate, 10.0);
  EXPECT_TRUE(s.pose.translation().isApprox(Eigen::Vector3d(0.1, 0, 0.2)));
  EXPECT_EQ(*find_param(s.params, "ray/scan/horizontal/samples"), "90");
  ASSERT_EQ(s.plugins.size(), 1u);
  EXPECT_EQ(s.plugins[0].filename, "libgazebo_ros_laser.so");
}

TEST(SdfModel, PluginKindsResolveThroughTheRegistry) {
  World w(empty_world());
  w.spawn_sdf(load_sdf_model_string(robot_with("", "")), "bot", at(0, 0, 0), "/");
  std::set<std::string> kinds;
  for (const auto& p : w.plugins()) kinds.insert(p.config.kind);
  EXPECT_TRUE(kinds.count("p3d"));
  EXPECT_TRUE(kinds.count("laser"));
}

// Namespace rules (docs/COMPAT-sdf.md table), plug-in and sensor alike.
TEST(SdfNamespace, AbsentIsInjectedAtSpawn) {
  SdfRobot r = load_sdf_model_string(robot_with("", ""));
  apply_robot_namespace(&r.model, "/r1/");
  EXPECT_EQ(ns_of(r.model.plugins[0]), "/r1/");
  EXPECT_EQ(ns_of(r.model.sensors[0].plugins[0]), "/r1/");
}

TEST(SdfNamespace, EmptyIsReadByEachFilesRule) {
  SdfRobot r = load_sdf_model_string(robot_with("<robotNamespace></robotNamespace>", "<robotNamespace></robotNamespace>"));
  apply_robot_namespace(&r.model, "/r1/");
  // the spawn keeps an empty value; each file reads it (docs/COMPAT-plugins.md "Namespaces"): laser
  // (GetRobotNamespace) -> the model name, p3d ("" + "/") -> global
  EXPECT_EQ(ns_of(r.model.sensors[0].plugins[0]), "");
  EXPECT_EQ(ns_of(r.model.plugins[0]), "");
  const ModelConfig mc = resolve_plugins(r.model);
  int seen = 0;
  for (const auto& c : mc.plugins) {
    if (c.name != "laser" && c.name != "p3d") continue;
    EXPECT_EQ(plugin_robot_namespace(c, "bot"), c.name == "laser" ? "bot" : "");
    ++seen;
  }
  EXPECT_EQ(seen, 2);
}

TEST(SdfNamespace, ExplicitIsKept) {
  SdfRobot r = load_sdf_model_string(robot_with("<robotNamespace>/left</robotNamespace>",
                                                "<robotNamespace>right</robotNamespace>"));
  apply_robot_namespace(&r.model, "/r1/");
  EXPECT_EQ(ns_of(r.model.plugins[0]), "/left");
  EXPECT_EQ(ns_of(r.model.sensors[0].plugins[0]), "right");
}

// Rule 13: -database's wrapper includes model://NAME through GAZEBO_MODEL_PATH; a missing one names the folders.
TEST(SdfModel, DatabaseIncludeResolvesThroughGazeboModelPath) {
  ScopedEnv env{{"GAZEBO_MODEL_PATH", data_path("sdf/models")}};
  const SdfRobot r = load_sdf_model_string(
      "<sdf version='1.4'><world name='default'><include><uri>model://sdf_box_bot</uri></include></world></sdf>");
  EXPECT_EQ(r.model.name, "sdf_box_bot");
  // model.config's <sdf> names model.sdf; its link 'chassis' has no <inertial>: 1 kg
  EXPECT_DOUBLE_EQ(r.model.find_link("chassis")->inertial->mass, 1.0);
}

// A link's <gravity>false</gravity> holds also when one of its collisions has a <surface> (the surface used to
// replace the link's whole record, its gravity switch with it).
TEST(SdfModel, GravityOffSurvivesACollisionSurface) {
  const SdfRobot r = load_sdf_model_string(sdf(
      "<model name='m'>" +
      lnk("a", "<gravity>false</gravity><collision name='c'><geometry><box><size>1 1 1</size></box></geometry>"
               "<surface><friction><ode><mu>0.5</mu></ode></friction></surface></collision>") +
      "</model>"));
  ASSERT_TRUE(r.model.links[0].gazebo.gravity.has_value());
  EXPECT_FALSE(*r.model.links[0].gazebo.gravity);
  EXPECT_EQ(r.model.links[0].gazebo.mu1, 0.5);
}

// <laser_retro> of a collision is what ray sensors read as intensity: the first collision's that sets one.
TEST(SdfModel, LaserRetroIsTheFirstCollisionsThatSetsOne) {
  const std::string box = "<geometry><box><size>1 1 1</size></box></geometry>";
  const SdfRobot r = load_sdf_model_string(sdf(
      "<model name='m'>" +
      lnk("a", "<collision name='c0'>" + box + "</collision><collision name='c1'><laser_retro>150</laser_retro>" +
                   box + "</collision><collision name='c2'><laser_retro>20</laser_retro>" + box + "</collision>") +
      "</model>"));
  ASSERT_TRUE(r.model.links[0].gazebo.laser_retro.has_value());
  EXPECT_EQ(*r.model.links[0].gazebo.laser_retro, 150.0);
}
