// One rule for sensor limits (validate.hpp check_sensor_limits): a 100 000 px camera side or 10^9 ray samples is
// refused with the same message whether the sensor comes in a URDF, an SDF robot, a world model, a nested model or
// a model:// include. The limits: docs/COMPAT-validation.md.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "car_sim/description.hpp"
#include "car_sim/model.hpp"
#include "car_sim/sdf_model.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

const char* kCameraReason = "sensor[cam]/camera/image/width: camera/image/width 100000 is above the limit 8192 px";
const char* kRayReason = "sensor[scan]/ray/scan/horizontal/samples: ray/scan/horizontal/samples 1000000000 is above "
                         "the limit 100000";

// A camera of 100 000 x 100 000 px, and a lidar of 10^9 samples: the same text in URDF and SDF.
const std::string kCamera =
    "<sensor type='camera' name='cam'><update_rate>10</update_rate><camera><horizontal_fov>1</horizontal_fov>"
    "<image><width>100000</width><height>100000</height></image><clip><near>0.1</near><far>50</far></clip></camera>"
    "<plugin name='p' filename='libgazebo_ros_camera.so'><cameraName>cam</cameraName></plugin></sensor>";
const std::string kRay =
    "<sensor type='ray' name='scan'><update_rate>10</update_rate><ray><scan><horizontal><samples>1000000000</samples>"
    "<min_angle>-1</min_angle><max_angle>1</max_angle></horizontal></scan><range><min>0.1</min><max>10</max></range>"
    "</ray></sensor>";

const std::string kSdfLink =
    "<link name='body'><inertial><mass>1</mass><inertia><ixx>0.1</ixx><iyy>0.1</iyy><izz>0.1</izz></inertia>"
    "</inertial>";

std::string urdf_with(const std::string& sensor) {
  return "<robot name='r'><link name='body'><inertial><mass value='1'/><inertia ixx='0.1' ixy='0' ixz='0' "
         "iyy='0.1' iyz='0' izz='0.1'/></inertial></link><gazebo reference='body'>" + sensor + "</gazebo></robot>";
}

std::string sdf_model_with(const std::string& sensor) {
  return "<sdf version='1.6'><model name='m'>" + kSdfLink + sensor + "</link></model></sdf>";
}

template <class F>
std::string error_of(F load) {
  try {
    load();
  } catch (const LoadError& e) {
    return e.what();
  }
  return "(loaded)";
}

}  // namespace

TEST(SensorLimits, AUrdfCameraIsRefused) {
  EXPECT_EQ(error_of([] { load_urdf_string(urdf_with(kCamera), "r.urdf"); }), std::string("r.urdf:1: ") + kCameraReason);
}

TEST(SensorLimits, AnSdfRobotsCameraIsRefused) {
  EXPECT_EQ(error_of([] { load_sdf_model_string(sdf_model_with(kCamera), "m.sdf"); }),
            std::string("m.sdf:1: ") + kCameraReason);
}

TEST(SensorLimits, AWorldModelsCameraWithoutAPluginIsRefused) {
  // no plug-in: nothing would publish it, but Gazebo 11 renders every camera (and would allocate its target)
  const std::string camera_alone = kCamera.substr(0, kCamera.find("<plugin")) + "</sensor>";
  const std::string world =
      "<sdf version='1.6'><world name='w'><model name='m'>" + kSdfLink + camera_alone + "</link></model></world></sdf>";
  EXPECT_EQ(error_of([&] { load_world_string(world, "w.world"); }), std::string("w.world:1: ") + kCameraReason);
}

TEST(SensorLimits, ANestedModelsCameraIsRefused) {
  const std::string world = "<sdf version='1.6'><world name='w'><model name='outer'>" + kSdfLink +
                            "</link><model name='inner'>" + kSdfLink + kCamera + "</link></model></model></world></sdf>";
  EXPECT_EQ(error_of([&] { load_world_string(world, "w.world"); }), std::string("w.world:1: ") + kCameraReason);
}

TEST(SensorLimits, AnIncludedModelsCameraIsRefusedNamingItsFile) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "car_sensor_limits" / "bigcam";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "model.config") << "<model><name>bigcam</name><sdf version='1.6'>model.sdf</sdf></model>";
  std::ofstream(dir / "model.sdf") << sdf_model_with(kCamera);
  ScopedEnv env{{"GAZEBO_MODEL_PATH", dir.parent_path().string()}};
  const std::string world = "<sdf version='1.6'><world name='w'><include><uri>model://bigcam</uri></include></world></sdf>";
  const std::string e = error_of([&] { load_world_string(world, "w.world"); });
  EXPECT_EQ(e, (dir / "model.sdf").string() + ":1: " + kCameraReason);
}

TEST(SensorLimits, AUrdfLidarIsRefused) {
  EXPECT_EQ(error_of([] { load_urdf_string(urdf_with(kRay), "r.urdf"); }), std::string("r.urdf:1: ") + kRayReason);
}

TEST(SensorLimits, AWorldModelsLidarIsRefused) {
  const std::string world =
      "<sdf version='1.6'><world name='w'><model name='m'>" + kSdfLink + kRay + "</link></model></world></sdf>";
  EXPECT_EQ(error_of([&] { load_world_string(world, "w.world"); }), std::string("w.world:1: ") + kRayReason);
}

TEST(SensorLimits, EachCameraOfAMulticameraIsChecked) {
  // the second camera is the large one
  const std::string multi =
      "<sensor type='multicamera' name='cam'><update_rate>10</update_rate>"
      "<camera name='left'><image><width>640</width><height>480</height></image></camera>"
      "<camera name='right'><image><width>100000</width><height>480</height></image></camera></sensor>";
  EXPECT_EQ(error_of([&] { load_sdf_model_string(sdf_model_with(multi), "m.sdf"); }),
            std::string("m.sdf:1: ") + kCameraReason);
}

TEST(SensorLimits, PixelsPerSecondAreCountedFromTheSensorsRate) {
  // 2048 x 2048 px at 1000 Hz: 4.19e9 px/s
  const std::string fast =
      "<sensor type='camera' name='cam'><update_rate>1000</update_rate><camera><image><width>2048</width>"
      "<height>2048</height></image></camera></sensor>";
  EXPECT_EQ(error_of([&] { load_urdf_string(urdf_with(fast), "r.urdf"); }),
            "r.urdf:1: sensor[cam]/update_rate: width x height x update_rate = 4194304000 px/s is above the limit "
            "1e9 px/s");
}

TEST(SensorLimits, AHugeRateIsRefusedWithItsProductInScientificNotation) {
  // 640 x 480 px at 1e21 Hz: 307 200 px x 1e21 /s = 3.072e26 px/s, beyond a long long (9.2e18): written with 10
  // significant digits (found by fuzz_urdf: the conversion to long long was undefined behaviour)
  const std::string fast =
      "<sensor type='camera' name='cam'><update_rate>1e21</update_rate><camera><image><width>640</width>"
      "<height>480</height></image></camera></sensor>";
  EXPECT_EQ(error_of([&] { load_urdf_string(urdf_with(fast), "r.urdf"); }),
            "r.urdf:1: sensor[cam]/update_rate: width x height x update_rate = 3.072e+26 px/s is above the limit "
            "1e9 px/s");
}

TEST(SensorLimits, ACameraWithinTheLimitsLoads) {
  const std::string ok =
      "<sensor type='camera' name='cam'><update_rate>30</update_rate><camera><image><width>2048</width>"
      "<height>2048</height></image></camera></sensor>";
  EXPECT_EQ(error_of([&] { load_urdf_string(urdf_with(ok), "r.urdf"); }), "(loaded)");
}
