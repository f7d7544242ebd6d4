// Gazebo's sensors API (docs/PLUGINS.md "Sensors"): sensor plug-ins and a model plug-in of car's own
// (test/gazebo/plugins/sensor_probe.cc, sensor_finder.cc), built as .so files by the test build, read the sensor
// classes that car feeds from its own kinds. Values by hand; dt = 0.001 s.
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <string>

#include "car_sim/world.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

const std::string kDir = CAR_GAZEBO_TEST_PLUGINS;

// The search path set to the test plug-ins' folder alone for one test, and put back after; the probe's record
// cleared.
class GazeboSensors : public ::testing::Test {
 protected:
  ScopedEnv env_{{"GAZEBO_PLUGIN_PATH", kDir}, {"CMAKE_PREFIX_PATH", "/nowhere/a"}, {"LD_LIBRARY_PATH", "/nowhere/b"}};
  void SetUp() override {
    if (void* h = dlopen((kDir + "/libsensor_probe.so").c_str(), RTLD_LAZY | RTLD_NOLOAD)) {
      reinterpret_cast<void (*)()>(dlsym(h, "car_test_probe_clear"))();
      dlclose(h);
    }
  }
};

// What the probe recorded under "SENSOR/WHAT"; NaN when nothing.
double probe(const std::string& key) {
  void* h = dlopen((kDir + "/libsensor_probe.so").c_str(), RTLD_LAZY | RTLD_NOLOAD);
  if (!h) return std::nan("");
  const double v = reinterpret_cast<double (*)(const char*)>(dlsym(h, "car_test_probe_value"))(key.c_str());
  dlclose(h);
  return v;
}

// A 2 kg box of 0.2 m on a link "base", with `sensors` in its <gazebo reference="base"> and `plugins` in its
// <gazebo>.
std::string box(const std::string& sensors, const std::string& plugins = "") {
  return R"(<?xml version="1.0"?>
<robot name="box">
  <link name="base">
    <inertial><mass value="2"/><inertia ixx="0.02" iyy="0.02" izz="0.02" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  </link>
  <gazebo reference="base">)" + sensors + R"(</gazebo>
  <gazebo>)" + plugins + R"(</gazebo>
</robot>)";
}

// A world without gravity or ground whose only model is a static wall 0.2 m thick and 2 m wide, centred at
// x = 2 m, z = 0.5 m: its near face is the plane x = 1.9 m, for |y| <= 1 m and 0 <= z <= 1 m. `background`: the
// scene's background colour.
WorldDescription wall_world(const std::string& background = "0.7 0.7 0.7 1") {
  return load_world_string(R"(<?xml version="1.0"?>
<sdf version="1.6"><world name="lab">
  <gravity>0 0 0</gravity>
  <scene><background>)" + background + R"(</background></scene>
  <model name="wall"><static>true</static><pose>2 0 0.5 0 0 0</pose>
    <link name="link"><collision name="c"><geometry><box><size>0.2 2 1</size></box></geometry></collision></link>
  </model>
</world></sdf>)");
}

// A pose at (x, y, z) [m], not turned.
Eigen::Isometry3d translated(double x, double y, double z) {
  Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
  p.translation() = Eigen::Vector3d(x, y, z);
  return p;
}

// A ray sensor of 3 beams over [-0.1, 0.1] rad, range [0.05, 10] m, at 10 Hz, 0.15 m ahead of the box's centre
// (outside its own box, whose face is at 0.1 m), with the probe (`extra` in its <plugin>, `noise` in its <ray>).
std::string ray_sensor(const std::string& name = "front", const std::string& extra = "",
                       const std::string& noise = "", const std::string& filename = "libsensor_probe.so") {
  return R"(<sensor type="ray" name=")" + name + R"("><update_rate>10</update_rate><pose>0.15 0 0 0 0 0</pose>
      <ray><scan><horizontal><samples>3</samples><min_angle>-0.1</min_angle><max_angle>0.1</max_angle></horizontal></scan>
        <range><min>0.05</min><max>10</max></range>)" + noise + R"(</ray>
      <plugin name="probe" filename=")" + filename + R"(">)" + extra + R"(</plugin></sensor>)";
}

// An 8 x 6 R8G8B8 camera "cam" at 10 Hz looking straight down (pitch -90 deg), hfov 1 rad, with the plug-in `filename`.
std::string down_camera(const std::string& filename) {
  return R"(<sensor type="camera" name="cam"><update_rate>10</update_rate><pose>0 0 0 0 -1.5707963 0</pose>
      <camera><horizontal_fov>1.0</horizontal_fov><image><width>8</width><height>6</height><format>R8G8B8</format></image>
        <clip><near>0.1</near><far>100</far></clip></camera>
      <plugin name="probe" filename=")" + filename + R"("/></sensor>)";
}

// A 9 x 7 depth camera "depth" at 10 Hz facing +x, hfov 1 rad, with the plug-in `filename`.
std::string depth_camera(const std::string& filename) {
  return R"(<sensor type="depth" name="depth"><update_rate>10</update_rate>
      <camera><horizontal_fov>1.0</horizontal_fov><image><width>9</width><height>7</height></image>
        <clip><near>0.1</near><far>100</far></clip></camera>
      <plugin name="probe" filename=")" + filename + R"("/></sensor>)";
}

std::vector<std::string> diags(const World& w, const std::string& code) {
  std::vector<std::string> out;
  for (const auto& d : w.robot("box").config.diagnostics)
    if (d.code == code) out.push_back(d.element + ": " + d.message);
  return out;
}

}  // namespace

// The sensor at (0.15, 0, 0.5), facing +x: the middle beam (angle 0) meets the wall's face at 1.9 - 0.15 = 1.75 m;
// the side beams (+-0.1 rad) at 1.75 / cos(0.1) = 1.758787 m (their y = 1.75 tan 0.1 = 0.1756 m is on the wall).
TEST_F(GazeboSensors, RaySensorPluginReadsTheRangesToAWall) {
  World w(wall_world());
  w.spawn(load_urdf_string(box(ray_sensor()), "box"), "box", translated(0, 0, 0.5));
  w.step(100);
  EXPECT_EQ(probe("front/ranges"), 3);
  EXPECT_NEAR(probe("front/range1"), 1.75, 1e-5);
  EXPECT_NEAR(probe("front/range0"), 1.75 / std::cos(0.1), 1e-5);
  EXPECT_NEAR(probe("front/range2"), 1.75 / std::cos(0.1), 1e-5);
}

// The plug-in's <plugin> element sits in its <sensor name>, as in Gazebo.
TEST_F(GazeboSensors, ASensorPluginsSdfParentIsItsSensor) {
  World w(wall_world());
  w.spawn(load_urdf_string(box(ray_sensor()), "box"), "box", translated(0, 0, 0.5));
  EXPECT_EQ(probe("front/sdf_parent_is_my_sensor"), 1);
}

// <gazebo/gazebo.hh> gives Gazebo's version macros, 11 (what a plug-in's `#if GAZEBO_MAJOR_VERSION >= 9` reads).
TEST_F(GazeboSensors, APluginSeesGazebosMajorVersion11) {
  World w(wall_world());
  w.spawn(load_urdf_string(box(ray_sensor()), "box"), "box", translated(0, 0, 0.5));
  EXPECT_EQ(probe("front/gazebo_major"), 11);
}

// The <ray> as written: 3 samples over [-0.1, 0.1]: a resolution of 0.2 / 2 = 0.1 rad; range max 10 m.
TEST_F(GazeboSensors, RaySensorGivesItsScanAsWritten) {
  World w(wall_world());
  w.spawn(load_urdf_string(box(ray_sensor()), "box"), "box", translated(0, 0, 0.5));
  w.step(100);
  EXPECT_EQ(probe("front/range_count"), 3);
  EXPECT_NEAR(probe("front/angle_min"), -0.1, 1e-12);
  EXPECT_NEAR(probe("front/angle_resolution"), 0.1, 1e-12);
  EXPECT_EQ(probe("front/range_max"), 10);
}

// <update_rate>10</update_rate> at dt 1 ms: a measurement every 100 steps, the first at 0.1 s: 10 in 1000 steps,
// the last at 1.0 s.
TEST_F(GazeboSensors, ASensorUpdatesOnItsUpdateRate) {
  World w(wall_world());
  w.spawn(load_urdf_string(box(ray_sensor()), "box"), "box", translated(0, 0, 0.5));
  w.step(1000);
  EXPECT_EQ(probe("front/updates"), 10);
  EXPECT_DOUBLE_EQ(probe("front/time"), 1.0);
}

// Not <always_on> and never SetActive(true): Gazebo's sensor does not measure, and neither does car's kind for it.
TEST_F(GazeboSensors, AnInactiveSensorDoesNotMeasure) {
  World w(wall_world());
  w.spawn(load_urdf_string(box(ray_sensor("front", "<inactive/>")), "box"), "box", translated(0, 0, 0.5));
  w.step(1000);
  EXPECT_EQ(probe("front/loaded"), 1);
  EXPECT_TRUE(std::isnan(probe("front/updates")));
}

// <always_on>true</always_on> makes the sensor active at load (Gazebo's Sensor::Load), without SetActive.
TEST_F(GazeboSensors, AlwaysOnMakesASensorActive) {
  World w(wall_world());
  const std::string s = ray_sensor("front", "<inactive/>");
  const std::string on = "<sensor type=\"ray\" name=\"front\"><always_on>true</always_on>" + s.substr(s.find('>') + 1);
  w.spawn(load_urdf_string(box(on), "box"), "box", translated(0, 0, 0.5));
  w.step(100);
  EXPECT_EQ(probe("front/updates"), 1);
}

// The same <ray><noise> and seed give the plug-in's sensor the very ranges car's own laser publishes for a
// <plugin> of the same name: one measurement, one noise.
TEST_F(GazeboSensors, RaySensorHasTheNoiseOfCarsLaser) {
  const std::string noise = "<noise><type>gaussian</type><mean>0</mean><stddev>0.05</stddev></noise>";
  WorldOptions o;
  o.seed = 7;
  World w(wall_world(), o);
  w.spawn(load_urdf_string(box(ray_sensor("front", "", noise)), "box"), "box", translated(0, 0, 0.5));
  w.step(100);
  World own(wall_world(), o);
  own.spawn(load_urdf_string(box(ray_sensor("front", "", noise, "libgazebo_ros_laser.so")), "box"), "box",
            translated(0, 0, 0.5));
  own.set_sensor_active("box", "probe", true);
  own.step(100);
  const OutputQueue outs = own.take_outputs();
  ASSERT_EQ(outs.size(), 1u);
  const LaserScanSample* scan = outs[0]->sample_of<LaserScanSample>();
  ASSERT_NE(scan, nullptr);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(probe("front/range" + std::to_string(i)), scan->ranges[i]) << i;
  EXPECT_NE(probe("front/range1"), 1.75f);  // the noise is there
}

// The 2 kg box resting on the ground plane (gravity 9.8 m/s^2): one contact, with the ground; every normal +z
// (from the ground into the box), every depth >= 0 (penetration) and small; the forces on the box sum to m g =
// 19.6 N up.
TEST_F(GazeboSensors, ContactSensorReportsABoxRestingOnTheGround) {
  World w(empty_world());
  const std::string bump = R"(<sensor type="contact" name="bump"><update_rate>100</update_rate>
      <contact><collision>base_collision</collision></contact>
      <plugin name="probe" filename="libsensor_probe.so"/></sensor>)";
  w.spawn(load_urdf_string(box(bump), "box"), "box", translated(0, 0, 0.1));
  w.step(1000);
  EXPECT_EQ(probe("bump/contacts"), 1);
  EXPECT_GE(probe("bump/points"), 1);
  EXPECT_NEAR(probe("bump/normal_z_min"), 1.0, 1e-6);
  EXPECT_GE(probe("bump/depth_min"), 0.0);
  EXPECT_LT(probe("bump/depth_max"), 0.005);
  EXPECT_NEAR(probe("bump/force_z"), 2 * 9.8, 0.02 * 2 * 9.8);
  EXPECT_EQ(probe("bump/collision1_is_mine"), 1);
}

// A contact sensor naming a named collision of a link lumped into "base" by a fixed joint (Gazebo's name
// "base_fixed_joint_lump__shell_collision", as Kobuki's bumper): it watches base's body, which rests on the ground.
TEST_F(GazeboSensors, ContactSensorFindsANamedLumpedCollision) {
  World w(empty_world());
  const std::string urdf = R"(<?xml version="1.0"?>
<robot name="box">
  <link name="base">
    <inertial><mass value="2"/><inertia ixx="0.02" iyy="0.02" izz="0.02" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  </link>
  <link name="shell_link">
    <inertial><mass value="0.1"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision name="shell"><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
  </link>
  <joint name="shell_joint" type="fixed"><parent link="base"/><child link="shell_link"/><origin xyz="0 0 0.15"/></joint>
  <gazebo reference="shell_link"><sensor type="contact" name="bump"><update_rate>100</update_rate>
      <contact><collision>base_fixed_joint_lump__shell_collision</collision></contact>
      <plugin name="probe" filename="libsensor_probe.so"/></sensor></gazebo>
</robot>)";
  w.spawn(load_urdf_string(urdf, "box"), "box", translated(0, 0, 0.1));
  w.step(1000);
  EXPECT_EQ(probe("bump/contacts"), 1);
}

// At rest on the ground, car's IMU without noise: the acceleration less gravity, (0, 0, +9.8) m/s^2 in the sensor
// frame; no turn (within the few urad/s that Bullet's resting contact leaves); the orientation the one at load
// (w = 1).
TEST_F(GazeboSensors, ImuSensorAtRestReadsPlusGOnZ) {
  World w(empty_world());
  const std::string imu = R"(<sensor type="imu" name="imu"><update_rate>100</update_rate>
      <plugin name="probe" filename="libsensor_probe.so"/></sensor>)";
  w.spawn(load_urdf_string(box(imu), "box"), "box", translated(0, 0, 0.1));
  w.step(1000);
  EXPECT_EQ(probe("imu/updates"), 100);
  EXPECT_NEAR(probe("imu/acc_z"), 9.8, 1e-3);
  EXPECT_NEAR(probe("imu/acc_x"), 0.0, 1e-3);
  EXPECT_NEAR(probe("imu/gyro_z"), 0.0, 1e-4);
  EXPECT_NEAR(probe("imu/orientation_w"), 1.0, 1e-9);
}

// A camera of 8 x 6 px looking up (pitch -pi/2) at nothing: every pixel is the scene's background (0, 0, 1):
// r g b = (0, 0, 255) (each channel times 255). The frame event gives the size and 3 bytes a pixel (R8G8B8).
TEST_F(GazeboSensors, CameraFrameHasItsSizeAndTheBackground) {
  World w(wall_world("0 0 1 1"));
  const std::string cam = down_camera("libsensor_probe.so");
  w.spawn(load_urdf_string(box(cam), "box"), "box", translated(0, 0, 0.5));
  w.step(100);
  EXPECT_EQ(probe("cam/width"), 8);
  EXPECT_EQ(probe("cam/height"), 6);
  EXPECT_EQ(probe("cam/centre_r"), 0);
  EXPECT_EQ(probe("cam/centre_g"), 0);
  EXPECT_EQ(probe("cam/centre_b"), 255);
  EXPECT_EQ(probe("cam/frames"), 1);
  EXPECT_EQ(probe("cam/frame_width"), 8);
  EXPECT_EQ(probe("cam/frame_depth"), 3);
}

// A depth camera facing the wall from (0, 0, 0.5): the centre pixel's depth along the optical axis is 1.9 m.
TEST_F(GazeboSensors, DepthCameraGivesTheDepthOfTheWall) {
  World w(wall_world());
  const std::string cam = depth_camera("libsensor_probe.so");
  w.spawn(load_urdf_string(box(cam), "box"), "box", translated(0, 0, 0.5));
  w.step(100);
  EXPECT_NEAR(probe("depth/centre_depth"), 1.9, 1e-5);
}

// A model plug-in finds the robot's sensors through SensorManager in its Load, by leaf name and by Gazebo's scoped
// name "world::model::link::sensor", including a sensor with no plug-in (as Kobuki's cliff sensors); a name that
// is not there gives none. It activates the ray sensor (0.15 m ahead of the box's centre) and reads 1.75 m to the
// wall.
TEST_F(GazeboSensors, ModelPluginFindsSensorsThroughSensorManager) {
  World w(wall_world());
  const std::string cliff = R"(<sensor type="ray" name="cliff"><update_rate>10</update_rate><pose>0.15 0 0 0 0 0</pose>
      <ray><scan><horizontal><samples>1</samples></horizontal></scan><range><min>0.05</min><max>10</max></range></ray>
      </sensor>)";
  const std::string finder = R"(<plugin name="finder" filename="libsensor_finder.so">
      <sensor_name>cliff</sensor_name><sensor_name>lab::box::base::cliff</sensor_name><sensor_name>nose</sensor_name>
      </plugin>)";
  w.spawn(load_urdf_string(box(cliff, finder), "box"), "box", translated(0, 0, 0.5));
  void* h = dlopen((kDir + "/libsensor_finder.so").c_str(), RTLD_LAZY | RTLD_NOLOAD);
  ASSERT_NE(h, nullptr);
  auto log = reinterpret_cast<const char* (*)()>(dlsym(h, "car_test_finder_log"));
  auto last = reinterpret_cast<double (*)()>(dlsym(h, "car_test_finder_last_range"));
  EXPECT_EQ(std::string(log()),
            "model=box cliff=lab::box::base::cliff,ray,box::base,off lab::box::base::cliff=lab::box::base::cliff,ray,box::base,on "
            "nose=none ");
  // the sensor measures at 0.1 s after WorldUpdateEnd of that step (car's sensors come after the step's events):
  // the plug-in reads the scan at the next step's end
  w.step(101);
  EXPECT_NEAR(last(), 1.75, 1e-5);
  dlclose(h);
}

// A sensor type the API does not offer: the plug-in is not loaded, with the message.
TEST_F(GazeboSensors, ASensorTypeNotOfferedLeavesItsPluginOut) {
  World w(wall_world());
  const std::string gps = R"(<sensor type="gps" name="fix"><plugin name="probe" filename="libsensor_probe.so"/></sensor>)";
  w.spawn(load_urdf_string(box(gps), "box"), "box", translated(0, 0, 0.5));
  EXPECT_EQ(diags(w, "plugin-not-loaded"),
            std::vector<std::string>{"sensor[fix]/plugin[probe]: sensor type 'gps' is not offered by car's Gazebo "
                                     "sensors API (ray, gpu_ray, contact, imu, camera, depth); the plug-in "
                                     "libsensor_probe.so is not loaded"});
  EXPECT_TRUE(std::isnan(probe("fix/loaded")));
}

// A model plug-in's library in a <sensor>: Gazebo's loader would not take it as a sensor plug-in; car says so and
// the model goes on.
TEST_F(GazeboSensors, AModelPluginInASensorIsAnError) {
  World w(wall_world());
  w.spawn(load_urdf_string(box(ray_sensor("front", "", "", "libmodel_push.so")), "box"), "box", translated(0, 0, 0.5));
  EXPECT_EQ(diags(w, "plugin-not-loaded"),
            std::vector<std::string>{"sensor[front]/plugin[probe]: plug-in 'probe' of model 'box' failed to load: "
                                     "Sensor[front] is attempting to load a plugin, but detected an incorrect plugin "
                                     "type. Plugin filename[libmodel_push.so] name[probe]: it is a model plug-in "
                                     "(GZ_REGISTER_MODEL_PLUGIN); a <plugin> in <sensor> takes a sensor plug-in "
                                     "(GZ_REGISTER_SENSOR_PLUGIN); the model goes on without it"});
  w.step(10);
}

// Deleting the model takes its sensors out of SensorManager.
TEST_F(GazeboSensors, ASensorGoesWithItsModel) {
  World w(wall_world());
  const std::string finder = R"(<plugin name="finder" filename="libsensor_finder.so"><sensor_name>front</sensor_name></plugin>)";
  w.spawn(load_urdf_string(box(ray_sensor(), finder), "box"), "box", translated(0, 0, 0.5));
  w.remove("box");
  World again(wall_world());
  again.spawn(load_urdf_string(box("", finder), "box"), "box", translated(0, 0, 0.5));
  void* h = dlopen((kDir + "/libsensor_finder.so").c_str(), RTLD_LAZY | RTLD_NOLOAD);
  ASSERT_NE(h, nullptr);
  EXPECT_EQ(std::string(reinterpret_cast<const char* (*)()>(dlsym(h, "car_test_finder_log"))()), "model=box front=none ");
  dlclose(h);
}

// ---- RayPlugin and the scan topic (test/gazebo/plugins/ray_plugin_probe.cc, written as gazebo_ros_laser is) ---------

namespace {

// What the RayPlugin probe logged since the last call, and its OnNewLaserScans calls.
std::string ray_plugin_log() {
  void* h = dlopen((kDir + "/libray_plugin_probe.so").c_str(), RTLD_LAZY | RTLD_NOLOAD);
  if (!h) return "<not loaded>";
  const std::string s = reinterpret_cast<const char* (*)()>(dlsym(h, "car_test_ray_plugin_probe_log"))();
  dlclose(h);
  return s;
}

int ray_plugin_scans() {
  void* h = dlopen((kDir + "/libray_plugin_probe.so").c_str(), RTLD_LAZY | RTLD_NOLOAD);
  if (!h) return -1;
  const int n = reinterpret_cast<int (*)()>(dlsym(h, "car_test_ray_plugin_probe_scans"))();
  dlclose(h);
  return n;
}

// The box with the 3-beam sensor "front" and the RayPlugin probe, at (0, 0, 0.5) before the wall.
std::unique_ptr<World> ray_plugin_box() {
  ray_plugin_log();
  ray_plugin_scans();
  auto w = std::make_unique<World>(wall_world());
  w->spawn(load_urdf_string(box(ray_sensor("front", "", "", "libray_plugin_probe.so")), "box"), "box",
           translated(0, 0, 0.5));
  return w;
}

}  // namespace

// Gazebo 11's RaySensor::Topic: "~/" + parent ("box::base") + "/" + name + "/scan", "::" as "/".
TEST_F(GazeboSensors, RaySensorTopicIsItsParentAndNameWithSlashes) {
  auto w = ray_plugin_box();
  EXPECT_EQ(ray_plugin_log(), "topic=~/box/base/front/scan ");
}

// The probe switches its sensor off, as gazebo_ros_laser does, and subscribes to its topic: the subscription keeps
// it measuring (Gazebo's RaySensor::IsActive), at its 10 Hz: 10 scans in 1 s, and OnNewLaserScans after each.
TEST_F(GazeboSensors, ARaySensorMeasuresWhileItsTopicHasASubscriber) {
  auto w = ray_plugin_box();
  ray_plugin_log();
  w->step(1000);
  const std::string log = ray_plugin_log();
  size_t n = 0;
  for (size_t at = log.find("scan@"); at != std::string::npos; at = log.find("scan@", at + 1)) ++n;
  EXPECT_EQ(n, 10u) << log;
  EXPECT_EQ(ray_plugin_scans(), 10);
}

// The first scan, at 0.1 s: the sensor's parent as frame, its 3 beams over [-0.1, 0.1] rad, range [0.05, 10] m, and
// the ranges to the wall (1.75 / cos(0.1) = 1.758787, 1.75, 1.758787 m; printed to 6 digits).
TEST_F(GazeboSensors, TheScanMessageHoldsTheSensorsScan) {
  auto w = ray_plugin_box();
  ray_plugin_log();
  w->step(100);
  EXPECT_EQ(ray_plugin_log(),
            "scan@0.100000000 frame=box::base count=3 min=-0.1 step=0.1 range=0.05..10 ranges=1.75879,1.75,1.75879 ");
}

// A RayPlugin in a sensor that is not a ray sensor: Gazebo's gzthrow, and the plug-in is left out.
TEST_F(GazeboSensors, ARayPluginOnAnotherSensorIsRefused) {
  World w(wall_world());
  testing::internal::CaptureStderr();
  w.spawn(load_urdf_string(box(R"(<sensor type="imu" name="imu"><update_rate>10</update_rate>
      <plugin name="probe" filename="libray_plugin_probe.so"/></sensor>)"), "box"), "box", translated(0, 0, 0.5));
  testing::internal::GetCapturedStderr();
  EXPECT_EQ(diags(w, "plugin-not-loaded"),
            std::vector<std::string>{"sensor[imu]/plugin[probe]: plug-in 'probe' of model 'box' failed to load: Load "
                                     "threw: RayPlugin requires a Ray Sensor as its parent; the model goes on without "
                                     "it"});
}

// ---- CameraPlugin and DepthCameraPlugin (test/gazebo/plugins/camera_plugin_probe.cc, depth_camera_plugin_probe.cc) ---

namespace {

// What the probe lib<name>.so logged since the last call (its car_test_<name>_log).
std::string probe_log(const std::string& name) {
  void* h = dlopen((kDir + "/lib" + name + ".so").c_str(), RTLD_LAZY | RTLD_NOLOAD);
  if (!h) return "<not loaded>";
  const std::string s = reinterpret_cast<const char* (*)()>(dlsym(h, ("car_test_" + name + "_log").c_str()))();
  dlclose(h);
  return s;
}

}  // namespace

// An 8 x 6 R8G8B8 camera looking down into the empty blue background: Load reads the camera's size, 3 bytes per
// pixel and format and activates the sensor; at 10 Hz the first frame comes at 0.1 s, blue at its centre.
TEST_F(GazeboSensors, CameraPluginGetsItsCameraAndItsFrames) {
  probe_log("camera_plugin_probe");
  World w(wall_world("0 0 1 1"));
  const std::string cam = down_camera("libcamera_plugin_probe.so");
  w.spawn(load_urdf_string(box(cam), "box"), "box", translated(0, 0, 0.5));
  w.step(100);
  EXPECT_EQ(probe_log("camera_plugin_probe"), "load 8x6 depth=3 format=R8G8B8 active=1 frame 8x6 centre=0,0,255 ");
}

// A 9 x 7 depth camera facing the wall's face 1.9 m ahead: the depth frame ("FLOAT32") reads 1.9 m at its centre,
// then the colour frame comes (Gazebo 11's DepthCamera::PostRender order); the base class's own OnNewDepthFrame prints upstream's line, whose "MidPoint" is
// upstream's index ((7 * 0.5) * 9 + 9 * 0.5 = 36: row 4, column 0), on the wall too.
TEST_F(GazeboSensors, DepthCameraPluginGetsTheDepthAndTheColourFrames) {
  probe_log("depth_camera_plugin_probe");
  World w(wall_world());
  const std::string cam = depth_camera("libdepth_camera_plugin_probe.so");
  w.spawn(load_urdf_string(box(cam), "box"), "box", translated(0, 0, 0.5));
  testing::internal::CaptureStdout();
  w.step(100);
  const std::string out = testing::internal::GetCapturedStdout();
  EXPECT_EQ(probe_log("depth_camera_plugin_probe"), "load 9x7 active=1 depth 9x7 format=FLOAT32 centre=1.9 image 9x7 ");
  EXPECT_NE(out.find("W[9] H[7] MidPoint[36] Dist[1.900000]"), std::string::npos) << out;
}

// A CameraPlugin in a ray sensor: upstream's two messages, and it does nothing (Gazebo 11 goes on to read the camera
// of no sensor and crashes).
TEST_F(GazeboSensors, ACameraPluginOnARaySensorSaysSoAndDoesNothing) {
  probe_log("camera_plugin_probe");
  World w(wall_world());
  testing::internal::CaptureStderr();
  w.spawn(load_urdf_string(box(ray_sensor("front", "", "", "libcamera_plugin_probe.so")), "box"), "box",
          translated(0, 0, 0.5));
  w.step(100);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("CameraPlugin requires a CameraSensor.\n"), std::string::npos) << err;
  EXPECT_NE(err.find("CameraPlugin not attached to a camera sensor\n"), std::string::npos) << err;
  EXPECT_EQ(probe_log("camera_plugin_probe"), "");
}
