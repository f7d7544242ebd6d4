// How each plug-in file reads <robotNamespace> after the spawn's injection (docs/COMPAT-plugins.md "Namespaces"):
// absent, present but empty, explicit; a robot-level plug-in and a sensor plug-in of each rule. The topics are
// what the ROS adapters advertise: plugin_robot_namespace + the plug-in's topic key, joined as topic_in does.
#include <gtest/gtest.h>

#include <map>

#include "car_sim/model.hpp"
#include "car_sim/plugin.hpp"
#include "car_sim/plugins.hpp"

using namespace car_sim;

namespace {

// Model "bot": robot-level p3d (AsWritten), joint_state_publisher (ModelName), gazebo_ros_control
// (AbsentIsModel); sensor plug-ins range, bumper, block_laser (AsWritten), laser, camera (EmptyIsModel),
// imu_sensor (AbsentIsModel). NS stands for the <robotNamespace> element of every plug-in.
const char* kBot = R"(<robot name="bot">
  <link name="base"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>
    </inertial><collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
  <link name="wheel"><inertial><mass value="0.1"/><inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/>
    </inertial></link>
  <joint name="wheel_joint" type="continuous"><parent link="base"/><child link="wheel"/><axis xyz="0 1 0"/></joint>
  <gazebo><plugin name="p3d" filename="libgazebo_ros_p3d.so">NS<bodyName>base</bodyName>
    <topicName>ground_truth</topicName></plugin></gazebo>
  <gazebo><plugin name="jsp" filename="libgazebo_ros_joint_state_publisher.so">NS<jointName>wheel_joint</jointName>
    </plugin></gazebo>
  <gazebo><plugin name="control" filename="libgazebo_ros_control.so">NS</plugin></gazebo>
  <gazebo reference="base">
    <sensor type="ray" name="sonar"><ray><scan><horizontal><samples>3</samples><min_angle>-0.1</min_angle>
      <max_angle>0.1</max_angle></horizontal></scan><range><min>0.05</min><max>2</max></range></ray>
      <plugin name="range" filename="libgazebo_ros_range.so">NS<topicName>sonar</topicName></plugin></sensor>
    <sensor type="ray" name="block"><ray><scan><horizontal><samples>3</samples><min_angle>-0.1</min_angle>
      <max_angle>0.1</max_angle></horizontal></scan><range><min>0.05</min><max>2</max></range></ray>
      <plugin name="block" filename="libgazebo_ros_block_laser.so">NS<topicName>cloud</topicName></plugin></sensor>
    <sensor type="contact" name="bump"><contact><collision>base_collision</collision></contact>
      <plugin name="bumper" filename="libgazebo_ros_bumper.so">NS<bumperTopicName>bumps</bumperTopicName></plugin>
    </sensor>
    <sensor type="ray" name="lidar"><ray><scan><horizontal><samples>3</samples><min_angle>-0.1</min_angle>
      <max_angle>0.1</max_angle></horizontal></scan><range><min>0.05</min><max>2</max></range></ray>
      <plugin name="laser" filename="libgazebo_ros_laser.so">NS<topicName>scan</topicName></plugin></sensor>
    <sensor type="camera" name="cam"><camera><horizontal_fov>1</horizontal_fov><image><width>8</width>
      <height>6</height></image><clip><near>0.05</near><far>10</far></clip></camera>
      <plugin name="camera" filename="libgazebo_ros_camera.so">NS<cameraName>cam</cameraName></plugin></sensor>
    <sensor type="imu" name="imu">
      <plugin name="imu" filename="libgazebo_ros_imu_sensor.so">NS<topicName>imu</topicName><frameName>base</frameName></plugin></sensor>
  </gazebo>
</robot>)";

// The resolved plug-ins of "bot" with `ns_element` in every plug-in, spawned with `spawn_ns` ("" = a model of a
// world file or a service call with robot_namespace '': nothing injected).
ModelConfig bot(const std::string& ns_element, const std::string& spawn_ns) {
  std::string xml = kBot;
  for (size_t i = xml.find("NS"); i != std::string::npos; i = xml.find("NS", i + ns_element.size()))
    xml.replace(i, 2, ns_element);
  RobotModel m = load_urdf_string(xml, "bot.urdf");
  apply_robot_namespace(&m, spawn_ns);
  return resolve_plugins(m);
}

// The relative topic (or service) `rel` of plug-in `name`, as its adapter resolves it (topic_in).
std::string topic(const ModelConfig& mc, const std::string& name, const std::string& rel) {
  for (const auto& c : mc.plugins) {
    if (c.name != name) continue;
    const std::string ns = plugin_robot_namespace(c, "bot");
    return ns.empty() ? "/" + rel : "/" + ns + "/" + rel;
  }
  ADD_FAILURE() << "no plug-in " << name;
  return "";
}

const char* kEmpty = "<robotNamespace></robotNamespace>";
const char* kExplicit = "<robotNamespace>/r2</robotNamespace>";

}  // namespace

// --- AsWritten (HasElement ? value + "/" : ""): p3d (plug-in), range, bumper, block_laser (sensors) ---

TEST(PluginNamespace, AsWrittenAbsentIsGlobal) {
  const ModelConfig mc = bot("", "");
  EXPECT_EQ(topic(mc, "p3d", "ground_truth"), "/ground_truth");
  EXPECT_EQ(topic(mc, "range", "sonar"), "/sonar");
}

TEST(PluginNamespace, AsWrittenEmptyIsGlobal) {
  // "" + "/" = NodeHandle("/"): the global namespace, not the model's name
  const ModelConfig mc = bot(kEmpty, "/r1/");
  EXPECT_EQ(topic(mc, "p3d", "ground_truth"), "/ground_truth");
  EXPECT_EQ(topic(mc, "range", "sonar"), "/sonar");
  EXPECT_EQ(topic(mc, "bumper", "bumps"), "/bumps");
  EXPECT_EQ(topic(mc, "block", "cloud"), "/cloud");
}

TEST(PluginNamespace, AsWrittenExplicitIsKept) {
  const ModelConfig mc = bot(kExplicit, "/r1/");
  EXPECT_EQ(topic(mc, "p3d", "ground_truth"), "/r2/ground_truth");
  EXPECT_EQ(topic(mc, "range", "sonar"), "/r2/sonar");
  EXPECT_EQ(topic(mc, "bumper", "bumps"), "/r2/bumps");
}

// --- ModelName (GazeboRos model constructor; joint_state_publisher's own copy of it) ---

TEST(PluginNamespace, ModelNameAbsentIsTheModelName) {
  EXPECT_EQ(topic(bot("", ""), "jsp", "joint_states"), "/bot/joint_states");
}

TEST(PluginNamespace, ModelNameEmptyIsTheModelName) {
  EXPECT_EQ(topic(bot(kEmpty, "/r1/"), "jsp", "joint_states"), "/bot/joint_states");
}

TEST(PluginNamespace, ModelNameExplicitIsKept) {
  EXPECT_EQ(topic(bot(kExplicit, "/r1/"), "jsp", "joint_states"), "/r2/joint_states");
}

TEST(PluginNamespace, ModelNameExplicitSlashIsGlobal) {
  // "/" + "/" = NodeHandle("//") = the global namespace; the model name fills in only an empty value
  EXPECT_EQ(topic(bot("<robotNamespace>/</robotNamespace>", ""), "jsp", "joint_states"), "/joint_states");
}

// --- EmptyIsModel (GetRobotNamespace: laser, camera_utils): sensors only ---

TEST(PluginNamespace, EmptyIsModelAbsentIsGlobal) {
  const ModelConfig mc = bot("", "");
  EXPECT_EQ(topic(mc, "laser", "scan"), "/scan");
  EXPECT_EQ(topic(mc, "camera", "cam/image_raw"), "/cam/image_raw");
}

TEST(PluginNamespace, EmptyIsModelEmptyIsTheModelName) {
  const ModelConfig mc = bot(kEmpty, "/r1/");
  EXPECT_EQ(topic(mc, "laser", "scan"), "/bot/scan");
  EXPECT_EQ(topic(mc, "camera", "cam/image_raw"), "/bot/cam/image_raw");
}

TEST(PluginNamespace, EmptyIsModelExplicitIsKept) {
  const ModelConfig mc = bot(kExplicit, "/r1/");
  EXPECT_EQ(topic(mc, "laser", "scan"), "/r2/scan");
  EXPECT_EQ(topic(mc, "camera", "cam/image_raw"), "/r2/cam/image_raw");
}

// --- AbsentIsModel (gazebo_ros_control's Load; imu_sensor's LoadParameters: "/" + model + "/") ---

TEST(PluginNamespace, AbsentIsModelAbsentIsTheModelName) {
  const ModelConfig mc = bot("", "");
  EXPECT_EQ(topic(mc, "control", "controller_manager/list_controllers"), "/bot/controller_manager/list_controllers");
  EXPECT_EQ(topic(mc, "imu", "imu"), "/bot/imu");
}

TEST(PluginNamespace, AbsentIsModelEmptyIsGlobal) {
  const ModelConfig mc = bot(kEmpty, "/r1/");
  EXPECT_EQ(topic(mc, "control", "controller_manager/list_controllers"), "/controller_manager/list_controllers");
  EXPECT_EQ(topic(mc, "imu", "imu"), "/imu");
}

TEST(PluginNamespace, AbsentIsModelExplicitIsKept) {
  const ModelConfig mc = bot(kExplicit, "/r1/");
  EXPECT_EQ(topic(mc, "control", "controller_manager/list_controllers"), "/r2/controller_manager/list_controllers");
  EXPECT_EQ(topic(mc, "imu", "imu"), "/r2/imu");
}

// --- the spawn's injection comes first: with spawn_model nothing is absent ---

TEST(PluginNamespace, SpawnNamespaceReplacesAbsentForEveryRule) {
  const ModelConfig mc = bot("", "/r1/");
  EXPECT_EQ(topic(mc, "p3d", "ground_truth"), "/r1/ground_truth");
  EXPECT_EQ(topic(mc, "jsp", "joint_states"), "/r1/joint_states");
  EXPECT_EQ(topic(mc, "laser", "scan"), "/r1/scan");
  EXPECT_EQ(topic(mc, "imu", "imu"), "/r1/imu");
}

TEST(PluginNamespace, RootSpawnNamespaceIsGlobalForEveryRule) {
  // spawn_model at the root injects "/": GazeboRos and imu_sensor no longer fall back on the model's name
  const ModelConfig mc = bot("", "/");
  EXPECT_EQ(topic(mc, "jsp", "joint_states"), "/joint_states");
  EXPECT_EQ(topic(mc, "imu", "imu"), "/imu");
  EXPECT_EQ(topic(mc, "camera", "cam/image_raw"), "/cam/image_raw");
}

// How each Gazebo file car serves reads <robotNamespace>, from upstream's Load (gazebo_ros_pkgs noetic-devel
// gazebo_plugins/src, hector_gazebo_plugins, velodyne_simulator), written here independently of the kinds' own
// tables. A kind that serves a file with no row here fails: read its upstream Load and add the row.
const std::map<std::string, NamespaceRule> kUpstreamRules = {
    // `if (HasElement("robotNamespace")) ns = value + "/"`, else ""
    {"libgazebo_ros_block_laser.so", NamespaceRule::AsWritten},
    {"libgazebo_ros_bumper.so", NamespaceRule::AsWritten},
    {"libgazebo_ros_f3d.so", NamespaceRule::AsWritten},
    {"libgazebo_ros_force.so", NamespaceRule::AsWritten},
    {"libgazebo_ros_ft_sensor.so", NamespaceRule::AsWritten},
    {"libgazebo_ros_hand_of_god.so", NamespaceRule::AsWritten},
    {"libgazebo_ros_joint_pose_trajectory.so", NamespaceRule::AsWritten},
    {"libgazebo_ros_p3d.so", NamespaceRule::AsWritten},
    {"libgazebo_ros_planar_move.so", NamespaceRule::AsWritten},
    {"libgazebo_ros_range.so", NamespaceRule::AsWritten},
    {"libgazebo_ros_skid_steer_drive.so", NamespaceRule::AsWritten},
    {"libgazebo_ros_imu.so", NamespaceRule::AsWritten},
    {"libhector_gazebo_ros_gps.so", NamespaceRule::AsWritten},
    {"libhector_gazebo_ros_imu.so", NamespaceRule::AsWritten},
    {"libhector_gazebo_ros_magnetic.so", NamespaceRule::AsWritten},
    {"libhector_gazebo_ros_sonar.so", NamespaceRule::AsWritten},
    // velodyne: the key's default "/" (global); an empty value is NodeHandle("") (global)
    {"libgazebo_ros_velodyne_laser.so", NamespaceRule::AsWritten},
    {"libgazebo_ros_velodyne_gpu_laser.so", NamespaceRule::AsWritten},
    // GazeboRos (gazebo_ros_utils.cpp): absent or empty -> the model's name
    {"libgazebo_ros_diff_drive.so", NamespaceRule::ModelName},
    {"libgazebo_ros_joint_state_publisher.so", NamespaceRule::ModelName},
    {"libgazebo_ros_tricycle_drive.so", NamespaceRule::ModelName},
    // GetRobotNamespace (gazebo_ros_utils.h), used by camera_utils and the lasers: empty -> the model's name
    {"libgazebo_ros_camera.so", NamespaceRule::EmptyIsModel},
    {"libgazebo_ros_depth_camera.so", NamespaceRule::EmptyIsModel},
    {"libgazebo_ros_openni_kinect.so", NamespaceRule::EmptyIsModel},
    {"libgazebo_ros_multicamera.so", NamespaceRule::EmptyIsModel},
    {"libgazebo_ros_triggered_camera.so", NamespaceRule::EmptyIsModel},
    {"libgazebo_ros_laser.so", NamespaceRule::EmptyIsModel},
    {"libgazebo_ros_gpu_laser.so", NamespaceRule::EmptyIsModel},
    // gazebo_ros_control_plugin.cpp and gazebo_ros_imu_sensor.cpp: absent -> the model's name, empty -> global
    {"libgazebo_ros_control.so", NamespaceRule::AbsentIsModel},
    {"libgazebo_ros_imu_sensor.so", NamespaceRule::AbsentIsModel},
};

// Every file name a registered kind serves reads <robotNamespace> as upstream's Load does.
TEST(PluginNamespace, EveryRegisteredFileReadsItAsUpstream) {
  for (const PluginKind* k : plugin_kinds())
    for (const auto& f : k->filenames) {
      const auto row = kUpstreamRules.find(f);
      if (row == kUpstreamRules.end()) {
        ADD_FAILURE() << k->name << ": " << f << " has no row in kUpstreamRules";
        continue;
      }
      NamespaceRule r;
      ASSERT_TRUE(namespace_rule(f, &r)) << f;
      EXPECT_EQ(r, row->second) << k->name << ": " << f;
    }
}

// A file no kind serves has no rule; its namespace is read as written.
TEST(PluginNamespace, UnknownFileHasNoRule) {
  NamespaceRule r;
  EXPECT_FALSE(namespace_rule("libmy_plugin.so", &r));
  EXPECT_EQ(r, NamespaceRule::AsWritten);
}

// The two imu files read it differently (gazebo_ros_imu.cpp vs gazebo_ros_imu_sensor.cpp).
TEST(PluginNamespace, ImuModelPluginAbsentIsGlobal) {
  NamespaceRule model_plugin, sensor_plugin;
  ASSERT_TRUE(namespace_rule("libgazebo_ros_imu.so", &model_plugin));
  ASSERT_TRUE(namespace_rule("libgazebo_ros_imu_sensor.so", &sensor_plugin));
  EXPECT_EQ(model_plugin, NamespaceRule::AsWritten);
  EXPECT_EQ(sensor_plugin, NamespaceRule::AbsentIsModel);
}

// The files issue 18 names, on a configuration written by hand (robotNamespace absent = from its default).
TEST(PluginNamespace, NamedFilesReadAsUpstream) {
  auto ns = [](const std::string& file, const char* value) {
    PluginConfig c;
    c.filename = file;
    c.params.push_back({"robotNamespace", value ? value : "", "", value == nullptr});
    return plugin_robot_namespace(c, "bot");
  };
  // range, bumper, block_laser: empty -> global
  for (const char* f : {"libgazebo_ros_range.so", "libgazebo_ros_bumper.so", "libgazebo_ros_block_laser.so"}) {
    EXPECT_EQ(ns(f, ""), "") << f;
    EXPECT_EQ(ns(f, nullptr), "") << f;
    EXPECT_EQ(ns(f, "r2"), "r2") << f;
  }
  // joint_state_publisher, tricycle_drive (GazeboRos): absent -> the model's name
  for (const char* f : {"libgazebo_ros_joint_state_publisher.so", "libgazebo_ros_tricycle_drive.so"}) {
    EXPECT_EQ(ns(f, nullptr), "bot") << f;
    EXPECT_EQ(ns(f, ""), "bot") << f;
    EXPECT_EQ(ns(f, "/r2/"), "r2") << f;
  }
  // multicamera (camera_utils GetRobotNamespace): absent -> global, empty -> the model's name
  EXPECT_EQ(ns("libgazebo_ros_multicamera.so", nullptr), "");
  EXPECT_EQ(ns("libgazebo_ros_multicamera.so", ""), "bot");
  // velodyne: absent -> its default "/" (global), empty -> NodeHandle("") (global)
  EXPECT_EQ(ns("libgazebo_ros_velodyne_laser.so", nullptr), "");
  EXPECT_EQ(ns("libgazebo_ros_velodyne_laser.so", ""), "");
}
