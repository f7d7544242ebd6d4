// The camera kinds' output ports, resolved in the core (PluginInfo::outputs), and the frames they read
// (Output::image_sample). Values from the kinds' schemas as gazebo_ros_camera_utils reads them: image and
// camera_info under <namespace>/<cameraName>/ with queue 2, header frame frameName, camera_info once per
// 1/updateRate s, D = (k1 k2 t1 t2 k3), P[3] = -f hackBaseline.
#include <gtest/gtest.h>

#include "../range/ray_world.hpp"
#include "camera/camera.hpp"
#include "multicamera/multicamera.hpp"
#include "seed_car.hpp"

using namespace car_sim;
using namespace car_sim::test_support;

namespace {

std::vector<OutputPort> ports_of(const World& w, const std::string& plugin) {
  for (const auto& p : w.plugins())
    if (p.config.name == plugin) return p.outputs;
  ADD_FAILURE() << "no plug-in " << plugin;
  return {};
}

// A 32 x 24 stereo pair, cameraName stereo, frameName stereo_optical, hackBaseline 0.14, updateRate 4.
std::string stereo() {
  auto cam = [](const char* name, const char* y) {
    return std::string("<camera name='") + name + "'><pose>0 " + y + " 0 0 0 0</pose><horizontal_fov>1.0" +
           "</horizontal_fov><image><width>32</width><height>24</height><format>R8G8B8</format></image><clip>" +
           "<near>0.05</near><far>20</far></clip></camera>";
  };
  return "<sensor type='multicamera' name='stereo'><update_rate>10</update_rate>" + cam("left", "0.07") +
         cam("right", "-0.07") +
         "<plugin name='stereo_plugin' filename='libgazebo_ros_multicamera.so'><cameraName>stereo</cameraName>"
         "<frameName>stereo_optical</frameName><hackBaseline>0.14</hackBaseline><updateRate>4</updateRate>"
         "</plugin></sensor>";
}

// An 8 x 6 sensor of `type` at 10 Hz with `plugin` (a <plugin> element).
std::string small_sensor(const std::string& type, const std::string& plugin) {
  return "<sensor type='" + type + "' name='cam'><update_rate>10</update_rate><camera><horizontal_fov>1.0" +
         "</horizontal_fov><image><width>8</width><height>6</height></image><clip><near>0.05</near><far>10</far>" +
         "</clip></camera>" + plugin + "</sensor>";
}

}  // namespace

// The seed car's Kinect (car_camera_lidar kinect.xacro: cameraName camera, rgb/ and depth/ topics, frameName
// support_depth, updateRate 10, no robotNamespace: global): the colour image, the depth camera_info (sent just
// before the colour one), the colour camera_info, the depth image in metres, the cloud.
TEST(CameraPorts, KinectTopicsInOrder) {
  auto w = world_with_car(false);
  const auto ports = ports_of(*w, "kinect_camera_controller");
  ASSERT_EQ(ports.size(), 5u);
  const std::vector<std::pair<SampleType, std::string>> want = {
      {sample_type<ImageSample>(), "/camera/rgb/image_raw"},
      {sample_type<CameraInfoSample>(), "/camera/depth/camera_info"},
      {sample_type<CameraInfoSample>(), "/camera/rgb/camera_info"},
      {sample_type<DepthImageSample>(), "/camera/depth/image_raw"},
      {sample_type<DepthCloudSample>(), "/camera/depth/points"}};
  for (size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(ports[i].type, want[i].first) << i;
    EXPECT_EQ(ports[i].topic, want[i].second) << i;
    EXPECT_EQ(ports[i].queue, 2u) << i;
    EXPECT_EQ(ports[i].frame, "support_depth") << i;
    // camera_utils resolves the frame with tf_prefix searched upwards (the ROS skin looks it up)
    EXPECT_EQ(ports[i].frame_rule, FrameRule::PrefixSearched) << i;
    EXPECT_EQ(ports[i].image.frame, 0u) << i;
  }
  EXPECT_FALSE(ports[3].image.millimetres);
  // updateRate 10 Hz: one camera_info per 0.1 s; <baseline> is not hackBaseline: P[3] 0
  EXPECT_DOUBLE_EQ(ports[2].image.period, 0.1);
  EXPECT_EQ(ports[2].image.baseline, 0.0);
}

// Which parts of the frame each port takes: the image the colour, the depth image depth, the cloud all three
// (kCameraCloud); camera_info none of its own, but depth (the cheapest) while nothing else is taken.
TEST(CameraPorts, KinectPortsNameTheirParts) {
  auto w = world_with_car(false);
  const auto ports = ports_of(*w, "kinect_camera_controller");
  ASSERT_EQ(ports.size(), 5u);
  const uint32_t parts[5] = {kCameraImage, 0, 0, kCameraDepth, kCameraCloud};
  const uint32_t idle[5] = {0, kCameraDepth, kCameraDepth, 0, 0};
  for (size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(ports[i].parts, parts[i]) << i;
    EXPECT_EQ(ports[i].idle_parts, idle[i]) << i;
  }
}

// Per side, its frame of the output, its topics under stereo/<side>, the right one's P[3] from hackBaseline
// (the left camera's baseline is 0, as upstream's multicamera sets it).
TEST(CameraPorts, MulticameraSidesFramesAndBaselines) {
  auto w = world_with_cube(ray_world(""), stereo());
  const auto ports = ports_of(*w, "stereo_plugin");
  ASSERT_EQ(ports.size(), 4u);
  EXPECT_EQ(ports[0].topic, "/stereo/left/image_raw");
  EXPECT_EQ(ports[1].topic, "/stereo/left/camera_info");
  EXPECT_EQ(ports[2].topic, "/stereo/right/image_raw");
  EXPECT_EQ(ports[3].topic, "/stereo/right/camera_info");
  EXPECT_EQ(ports[0].image.frame, 0u);
  EXPECT_EQ(ports[1].image.frame, 0u);
  EXPECT_EQ(ports[2].image.frame, 1u);
  EXPECT_EQ(ports[3].image.frame, 1u);
  EXPECT_EQ(ports[1].image.baseline, 0.0);
  EXPECT_EQ(ports[3].image.baseline, 0.14);
  EXPECT_DOUBLE_EQ(ports[3].image.period, 0.25);
  EXPECT_EQ(ports[3].frame, "stereo_optical");
}

// A multicamera output's frame i is its i-th side's; there is no third.
TEST(CameraPorts, MulticameraSamplesAreItsFrames) {
  auto w = world_with_cube(ray_world(""), stereo());
  w->set_sensor_active("cube", "stereo_plugin", true);
  w->step(100);
  const auto outs = w->take_outputs<MultiCameraOut>();
  ASSERT_EQ(outs.size(), 1u);
  const std::optional<ImageSample> s = outs[0].sample_of<ImageSample>({}, 1);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->image, outs[0].frames[1].image.data());
  EXPECT_EQ(s->image_bytes, 32u * 24u * 3u);
  EXPECT_EQ(s->step, 96u);
  EXPECT_EQ(s->encoding, "rgb8");
  EXPECT_EQ(s->depth, nullptr);
  EXPECT_FALSE(outs[0].sample_of<ImageSample>({}, 2));
}

// The triggered camera sends camera_info only while its image has subscribers (upstream's triggered camera);
// the plain camera always.
TEST(CameraPorts, TriggeredCameraInfoIsACameraInfoPort) {
  auto sensor = [](const char* file) {
    return std::string("<sensor type='camera' name='eye'><camera><image><width>8</width><height>6</height>") +
           "</image></camera><plugin name='eye_camera' filename='" + file +
           "'><cameraName>eye</cameraName><distortionK1>0.1</distortionK1><distortionT2>0.2</distortionT2>" +
           "</plugin></sensor>";
  };
  auto triggered = world_with_cube(ray_world(""), sensor("libgazebo_ros_triggered_camera.so"));
  auto plain = world_with_cube(ray_world(""), sensor("libgazebo_ros_camera.so"));
  const auto t = ports_of(*triggered, "eye_camera"), p = ports_of(*plain, "eye_camera");
  ASSERT_EQ(t.size(), 2u);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(t[1].topic, "/eye/camera_info");
  // D in plumb_bob's order k1 k2 t1 t2 k3
  const std::array<double, 5> d = {0.1, 0, 0, 0.2, 0};
  EXPECT_EQ(p[1].image.distortion, d);
  // updateRate 0: with every frame
  EXPECT_EQ(p[1].image.period, 0.0);
}

// gazebo_ros_camera's and gazebo_ros_multicamera's OnNewFrame send the image, too, at most once per 1/updateRate
// (PeriodGate in the node); the depth cameras send every frame.
TEST(CameraPorts, CameraImagesAreThrottledByUpdateRate) {
  auto w = world_with_cube(ray_world(""), stereo());
  const auto ports = ports_of(*w, "stereo_plugin");
  ASSERT_EQ(ports.size(), 4u);
  EXPECT_DOUBLE_EQ(ports[0].min_period, 0.25);
  EXPECT_DOUBLE_EQ(ports[2].min_period, 0.25);
  auto car = world_with_car(false);
  EXPECT_EQ(ports_of(*car, "kinect_camera_controller")[0].min_period, 0.0);
}

// Without <frameName> camera_utils only logs "defaults to /world": its frame_name_ stays "", and so does the
// header's frame_id.
TEST(CameraPorts, WithoutFrameNameTheFrameIsEmpty) {
  auto w = world_with_cube(ray_world(""), small_sensor("camera", "<plugin name='cam_plugin' filename='libgazebo_ros_"
                                                                "camera.so'><cameraName>cam</cameraName></plugin>"));
  const auto ports = ports_of(*w, "cam_plugin");
  ASSERT_EQ(ports.size(), 2u);
  EXPECT_EQ(ports[0].frame, "");
  EXPECT_EQ(ports[1].frame, "");
}

// upstream's CameraPlugin takes any CameraSensor, and a depth sensor is one: libgazebo_ros_camera.so on a depth
// sensor publishes its colour image.
TEST(CameraPorts, TheCameraPluginWorksOnADepthSensor) {
  auto w = world_with_cube(ray_world(""), small_sensor("depth", "<plugin name='cam_plugin' filename='libgazebo_ros_"
                                                               "camera.so'><cameraName>cam</cameraName></plugin>"));
  const auto ports = ports_of(*w, "cam_plugin");
  ASSERT_EQ(ports.size(), 2u);
  EXPECT_EQ(ports[0].topic, "/cam/image_raw");
  w->set_sensor_active("cube", "cam_plugin", true);
  w->step(100);
  const OutputQueue q = w->take_outputs();
  ASSERT_FALSE(q.empty());
  const std::optional<ImageSample> s = q.back()->sample_of<ImageSample>();
  ASSERT_TRUE(s);
  EXPECT_EQ(s->width, 8u);
  EXPECT_NE(s->image, nullptr);
}

// pointCloudCutoff >= pointCloudCutoffMax: upstream keeps no depth (every pixel NaN); car the same, with a warning.
TEST(CameraPorts, AKinectWithAnEmptyDepthBandLoads) {
  auto w = world_with_cube(ray_world(""),
                           small_sensor("depth", "<plugin name='kin_plugin' filename='libgazebo_ros_openni_kinect.so'>"
                                                 "<cameraName>kin</cameraName><pointCloudCutoff>5</pointCloudCutoff>"
                                                 "<pointCloudCutoffMax>2</pointCloudCutoffMax></plugin>"));
  bool warned = false;
  for (const Diagnostic& d : w->robot("cube").config.diagnostics) warned = warned || d.code == "kinect-band";
  EXPECT_TRUE(warned);
  w->set_sensor_active("cube", "kin_plugin", true);
  w->step(100);
  const OutputQueue q = w->take_outputs();
  ASSERT_FALSE(q.empty());
  const std::optional<ImageSample> s = q.back()->sample_of<ImageSample>();
  ASSERT_TRUE(s);
  ASSERT_NE(s->depth, nullptr);
  for (int i = 0; i < s->width * s->height; ++i) EXPECT_TRUE(std::isnan(s->depth[i])) << i;
}

namespace {

// A one-link robot with small_sensor("camera", a libgazebo_ros_camera.so plug-in with `keys`) on its link.
ModelConfig camera_robot(const std::string& keys) {
  return resolve_plugins(load_urdf_string(
      "<robot name='bot'><link name='body'><inertial><mass value='1'/><inertia ixx='0.1' iyy='0.1' izz='0.1' "
      "ixy='0' ixz='0' iyz='0'/></inertial></link><gazebo reference='body'>" +
          small_sensor("camera", "<plugin name='cam_plugin' filename='libgazebo_ros_camera.so'><cameraName>cam"
                                 "</cameraName>" + keys + "</plugin>") +
          "</gazebo></robot>",
      "bot.urdf"));
}

bool has_code(const ModelConfig& c, const std::string& code) {
  for (const auto& d : c.diagnostics)
    if (d.code == code) return true;
  return false;
}

}  // namespace

// camera_utils' non-zero <Cx>, <Cy>, <focalLength> [px] go to camera_info (the info port), as written; the image
// port does not take them (the image is rendered from horizontal_fov).
TEST(CameraPorts, NonZeroIntrinsicsGoToTheInfoPort) {
  auto w = world_with_cube(ray_world(""), small_sensor("camera", "<plugin name='cam_plugin' filename='libgazebo_ros_"
                                                                "camera.so'><cameraName>cam</cameraName><Cx>3.5</Cx>"
                                                                "<Cy>2.25</Cy><focalLength>7.32195088685</focalLength>"
                                                                "</plugin>"));
  const auto ports = ports_of(*w, "cam_plugin");
  ASSERT_EQ(ports.size(), 2u);
  ASSERT_EQ(ports[1].type, sample_type<CameraInfoSample>());
  EXPECT_EQ(ports[1].image.cx, 3.5);
  EXPECT_EQ(ports[1].image.cy, 2.25);
  EXPECT_EQ(ports[1].image.focal_length, 7.32195088685);
}

// Absent, they are 0: camera_info takes the values the image is rendered with.
TEST(CameraPorts, AbsentIntrinsicsAreZero) {
  auto w = world_with_cube(ray_world(""), small_sensor("camera", "<plugin name='cam_plugin' filename='libgazebo_ros_"
                                                                "camera.so'><cameraName>cam</cameraName></plugin>"));
  const auto ports = ports_of(*w, "cam_plugin");
  ASSERT_EQ(ports.size(), 2u);
  EXPECT_EQ(ports[1].image.cx, 0.0);
  EXPECT_EQ(ports[1].image.cy, 0.0);
  EXPECT_EQ(ports[1].image.focal_length, 0.0);
}

// A focal length other than width / (2 tan(hfov / 2)) = 8 / (2 tan 0.5) = 7.3219509 px loads with camera_utils'
// warning, in its words (typos included).
TEST(CameraPorts, InconsistentFocalLengthWarns) {
  const ModelConfig c = camera_robot("<focalLength>7</focalLength>");
  ASSERT_EQ(c.plugins.size(), 1u);
  bool found = false;
  for (const auto& d : c.diagnostics)
    if (d.code == "focal-length") {
      found = true;
      EXPECT_EQ(d.message,
                "The <focal_length>[7.000000] you have provided for camera_ [cam] is inconsistent with specified "
                "image_width [8] and HFOV [1.000000].   Please double check to see that focal_length = width_ / "
                "(2.0 * tan(HFOV/2.0)), the explected focal_lengtth value is [7.321951], please update your "
                "camera_ model description accordingly.");
    }
  EXPECT_TRUE(found);
}

// Within ignition::math::equal's 1e-6 of the computed value it loads quietly.
TEST(CameraPorts, ConsistentFocalLengthLoadsQuietly) {
  EXPECT_FALSE(has_code(camera_robot("<focalLength>7.3219513</focalLength>"), "focal-length"));
}
