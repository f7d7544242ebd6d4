// Test plug-in for Gazebo's DepthCameraPlugin base (docs/PLUGINS.md "Sensor plug-in bases"): a DepthCameraPlugin that
// logs, read through car_test_depth_camera_plugin_probe_log(), what Load set ("load WxH active=A"), each depth frame
// ("depth WxH format=F centre=C", then the base class's own printout on stdout) and each colour frame ("image WxH").
#include <gazebo/plugins/DepthCameraPlugin.hh>

#include <sstream>
#include <string>

#include "event_log.hh"

CAR_TEST_PLUGIN_LOG(depth_camera_plugin_probe)

namespace gazebo {
class DepthCameraPluginProbe : public DepthCameraPlugin {
 public:
  void Load(sensors::SensorPtr _sensor, sdf::ElementPtr _sdf) override {
    DepthCameraPlugin::Load(_sensor, _sdf);
    if (!parentSensor) return;
    g_log << "load " << width << "x" << height << " active=" << parentSensor->IsActive() << " ";
  }
  void OnNewDepthFrame(const float* _image, unsigned int _width, unsigned int _height, unsigned int _depth,
                       const std::string& _format) override {
    g_log << "depth " << _width << "x" << _height << " format=" << _format
          << " centre=" << _image[(_height / 2) * _width + _width / 2] << " ";
    DepthCameraPlugin::OnNewDepthFrame(_image, _width, _height, _depth, _format);
  }
  void OnNewImageFrame(const unsigned char*, unsigned int _width, unsigned int _height, unsigned int,
                       const std::string&) override {
    g_log << "image " << _width << "x" << _height << " ";
  }
};
GZ_REGISTER_SENSOR_PLUGIN(DepthCameraPluginProbe)
}  // namespace gazebo
