// gazebo_plugins' GazeboRos (include/gazebo_plugins/gazebo_ros_utils.h) in a model plug-in of ours
// (test/utils_probe.cc) loaded by car's world, checked against upstream's behaviour (gazebo_ros_pkgs noetic-devel,
// gazebo_ros_utils.h/.cpp): the namespace is <robotNamespace> or the model's name, with "/" added; getParameter takes
// the element or the default with a warning; an options map maps the text; getJoint throws for a joint the model
// lacks; isInitialized is quiet once ros::init has run; resolveTF puts the tf_prefix found upwards from the namespace in
// front (gazebo_ros_utils.test sets rover_tf/tf_prefix "pre"). Run by rostest: the node handle needs a ROS master.
#include <gtest/gtest.h>
#include <ros/ros.h>

#include <cstdlib>
#include <string>

#include "car_sim/world.hpp"

using namespace car_sim;

namespace {

// A box with a wheel on the continuous joint axle, the probe with the given elements, spawned as `name`; what the
// probe printed.
std::string probe(const std::string& elements, const std::string& name, std::unique_ptr<World>* keep = nullptr) {
  const std::string urdf = R"(<?xml version="1.0"?>
<robot name="box">
  <link name="body">
    <inertial><mass value="2"/><inertia ixx="0.5" iyy="0.5" izz="0.5" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <link name="wheel">
    <inertial><mass value="1"/><inertia ixx="0.5" iyy="0.5" izz="0.5" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="axle" type="continuous"><parent link="body"/><child link="wheel"/><axis xyz="0 0 1"/></joint>
  <gazebo><plugin name="probe" filename=")" CAR_UTILS_PROBE R"(">)" + elements + R"(</plugin></gazebo>
</robot>)";
  auto w = std::make_unique<World>(empty_world());
  testing::internal::CaptureStdout();
  w->spawn(load_urdf_string(urdf, name), name, Eigen::Isometry3d::Identity());
  std::string out = testing::internal::GetCapturedStdout();
  // the probe's line only (rosconsole's INFO lines go to stdout too)
  const size_t at = out.find("info=");
  if (keep) *keep = std::move(w);
  return at == std::string::npos ? "<no line in: " + out + ">" : out.substr(at, out.find('\n', at) - at);
}

}  // namespace

// No elements: the model's name as namespace, every default, and a warning per missing element. (The warnings are
// checked in a fresh process, gtest's EXPECT_EXIT: rosconsole's lines of a plug-in loaded a second time in one
// process do not reach a captured stderr.)
TEST(GazeboRos, DefaultsAndTheModelsNameWithoutElements) {
  EXPECT_EQ(probe("", "rover"),
            "info=UtilsProbe(ns = rover/) ns=/rover rate=50 topic=cmd_vel tf=1 source=1 joint=axle frame=odom");
}

TEST(GazeboRos, AMissingElementWarnsWithItsDefault) {
  EXPECT_EXIT(
      {
        probe("", "rover");
        std::exit(0);
      },
      testing::ExitedWithCode(0),
      "UtilsProbe\\(ns = rover/\\): missing <updateRate> default is 50.*"
      "UtilsProbe\\(ns = rover/\\): missing <publishTf> default is true");
}

// Every element given: their values; <robotNamespace> r1 is the namespace /r1.
TEST(GazeboRos, TheElementsValues) {
  EXPECT_EQ(probe("<robotNamespace>r1</robotNamespace><updateRate>20.5</updateRate><commandTopic>drive</commandTopic>"
                  "<publishTf>FALSE</publishTf><odometrySource>encoder</odometrySource><leftJoint>axle</leftJoint>",
                  "rover"),
            "info=UtilsProbe(ns = r1/) ns=/r1 rate=20.5 topic=drive tf=0 source=0 joint=axle frame=odom");
}

// An empty <robotNamespace> is the model's name, as an absent one.
TEST(GazeboRos, AnEmptyNamespaceIsTheModelsName) {
  EXPECT_EQ(probe("<robotNamespace></robotNamespace>", "rover").substr(0, 46),
            "info=UtilsProbe(ns = rover/) ns=/rover rate=50");
}

// A value the options map lacks and a boolean that is neither: warnings, and the defaults kept.
TEST(GazeboRos, UnknownOptionAndBadBooleanKeepTheDefaults) {
  EXPECT_EQ(probe("<odometrySource>gps</odometrySource><publishTf>maybe</publishTf>", "rover"),
            "info=UtilsProbe(ns = rover/) ns=/rover rate=50 topic=cmd_vel tf=1 source=1 joint=axle frame=odom");
  EXPECT_EXIT(
      {
        probe("<odometrySource>gps</odometrySource><publishTf>maybe</publishTf>", "rover");
        std::exit(0);
      },
      testing::ExitedWithCode(0),
      "UtilsProbe\\(ns = rover/\\): <publishTf> must be either true or false but is 'maybe'.*"
      "UtilsProbe\\(ns = rover/\\): <odometrySource> no matching key to gps");
}

// getJoint for a joint the model lacks throws (gzthrow): the plug-in does not load, with upstream's text.
TEST(GazeboRos, AMissingJointFailsTheLoad) {
  std::unique_ptr<World> w;
  testing::internal::CaptureStderr();
  probe("<leftJoint>nope</leftJoint>", "rover", &w);
  testing::internal::GetCapturedStderr();
  std::vector<std::string> errors;
  for (const auto& d : w->robot("rover").config.diagnostics)
    if (d.code == "plugin-not-loaded") errors.push_back(d.message);
  EXPECT_EQ(errors, std::vector<std::string>{"plug-in 'probe' of model 'rover' failed to load: Load threw: "
                                             "UtilsProbe(ns = rover/): couldn't get wheel hinge joint named nope; "
                                             "the model goes on without it"});
}

// tf_prefix "pre" in the namespace rover_tf: resolveTF("odom") is "pre/odom".
TEST(GazeboRos, ResolveTFPutsTheTfPrefixInFront) {
  EXPECT_EQ(probe("", "rover_tf"),
            "info=UtilsProbe(ns = rover_tf/) ns=/rover_tf rate=50 topic=cmd_vel tf=1 source=1 joint=axle frame=pre/odom");
}

// After ros::init, isInitialized says nothing (upstream logs a FATAL line only without it).
TEST(GazeboRos, IsInitializedIsQuietOnceRosIsUp) {
  ASSERT_TRUE(ros::isInitialized());
  testing::internal::CaptureStderr();
  probe("", "rover");
  EXPECT_EQ(testing::internal::GetCapturedStderr().find("has not been initialized"), std::string::npos);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  // a death test's fresh process runs the binary again: its own node name
  testing::FLAGS_gtest_death_test_style = "threadsafe";
  // as car's node does before it loads a plug-in
  ros::init(argc, argv, "test_gazebo_ros_utils", ros::init_options::AnonymousName);
  return RUN_ALL_TESTS();
}
