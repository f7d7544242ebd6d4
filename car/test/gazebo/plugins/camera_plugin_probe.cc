// Test plug-in for Gazebo's CameraPlugin base (docs/PLUGINS.md "Sensor plug-in bases"): a CameraPlugin that logs, read
// through car_test_camera_plugin_probe_log(), what Load set ("load WxH depth=D format=F active=A") and each frame
// ("frame WxH centre=R,G,B").
#include <gazebo/plugins/CameraPlugin.hh>

#include <sstream>
#include <string>

#include "event_log.hh"

CAR_TEST_PLUGIN_LOG(camera_plugin_probe)

namespace gazebo {
class CameraPluginProbe : public CameraPlugin {
 public:
  void Load(sensors::SensorPtr _sensor, sdf::ElementPtr _sdf) override {
    CameraPlugin::Load(_sensor, _sdf);
    if (!parentSensor) return;
    g_log << "load " << width << "x" << height << " depth=" << depth << " format=" << format
          << " active=" << parentSensor->IsActive() << " ";
  }
  void OnNewFrame(const unsigned char* _image, unsigned int _width, unsigned int _height, unsigned int _depth,
                  const std::string&) override {
    const unsigned int at = ((_height / 2) * _width + _width / 2) * _depth;
    g_log << "frame " << _width << "x" << _height << " centre=" << int(_image[at]) << "," << int(_image[at + 1]) << ","
          << int(_image[at + 2]) << " ";
  }
};
GZ_REGISTER_SENSOR_PLUGIN(CameraPluginProbe)
}  // namespace gazebo
