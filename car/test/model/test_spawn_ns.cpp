// The spawn service's namespace rule (gazebo_ros_api_plugin walkChildAddRobotNamespace; docs/COMPAT-spawn.md)
// on a model with a robot-level plug-in and a sensor plug-in.
#include <gtest/gtest.h>

#include "car_sim/model.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

RobotModel robot(const std::string& drive_ns_element, const std::string& sensor_ns_element) {
  return load_urdf_string(
      "<robot name='r'><link name='base'><inertial><mass value='1'/>"
      "<inertia ixx='0.01' ixy='0' ixz='0' iyy='0.01' iyz='0' izz='0.01'/></inertial></link>"
      "<gazebo><plugin name='drive' filename='libgazebo_ros_diff_drive.so'>" + drive_ns_element +
          "<commandTopic>cmd_vel</commandTopic></plugin></gazebo>"
          "<gazebo reference='base'><sensor name='imu' type='imu'><plugin name='imu_plugin' "
          "filename='libgazebo_ros_imu_sensor.so'>" + sensor_ns_element + "<topicName>imu</topicName></plugin>"
          "</sensor></gazebo></robot>");
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

TEST(SpawnNamespace, RootNamespaceIsAddedWhereNoneIsWritten) {
  // spawn_model at the root: -robot_namespace defaults to rospy.get_namespace() = "/"
  RobotModel m = robot("", "");
  apply_robot_namespace(&m, "/");
  EXPECT_EQ(ns_of(m.plugins[0]), "/");
  EXPECT_EQ(ns_of(m.sensors[0].plugins[0]), "/");
}

TEST(SpawnNamespace, GroupNamespaceIsAddedWhereNoneIsWritten) {
  // inside <group ns="r1">: rospy.get_namespace() = "/r1/"
  RobotModel m = robot("", "");
  apply_robot_namespace(&m, "/r1/");
  EXPECT_EQ(ns_of(m.plugins[0]), "/r1/");
  EXPECT_EQ(ns_of(m.sensors[0].plugins[0]), "/r1/");
}

TEST(SpawnNamespace, ExplicitNamespaceIsKept) {
  RobotModel m = robot("<robotNamespace>/left</robotNamespace>", "<robotNamespace>right</robotNamespace>");
  apply_robot_namespace(&m, "/r1/");
  EXPECT_EQ(ns_of(m.plugins[0]), "/left");
  EXPECT_EQ(ns_of(m.sensors[0].plugins[0]), "right");
}

TEST(SpawnNamespace, EmptySpawnNamespaceAddsNothing) {
  // the service called with robot_namespace "" (not spawn_model's default): plug-ins fall back on their own
  RobotModel m = robot("", "");
  apply_robot_namespace(&m, "");
  EXPECT_EQ(ns_of(m.plugins[0]), "<none>");
  EXPECT_EQ(ns_of(m.sensors[0].plugins[0]), "<none>");
}

TEST(SpawnNamespace, ExplicitlyEmptyNamespaceIsKept) {
  // the spawn neither replaces nor fills an empty value: each file reads it by its own rule when it loads
  // (imu_sensor: "" + "/" = global; diff_drive: the model name; test_plugin_namespace.cpp)
  RobotModel m = robot("<robotNamespace></robotNamespace>", "<robotNamespace></robotNamespace>");
  apply_robot_namespace(&m, "/");
  EXPECT_EQ(ns_of(m.plugins[0]), "");
  EXPECT_EQ(ns_of(m.sensors[0].plugins[0]), "");
}
