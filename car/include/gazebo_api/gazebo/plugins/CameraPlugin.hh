// car's Gazebo 11 API (docs/PLUGINS.md "Sensor plug-in bases"): gazebo::CameraPlugin (gazebo/plugins/CameraPlugin.hh),
// the base of camera sensors' plug-ins: Load takes the parent CameraSensor and its camera (width, height, depth,
// format), activates the sensor and calls OnNewFrame with each frame. Link the library CameraPlugin, as with
// Gazebo 11.
#pragma once

#include <string>

#include "gazebo/common/Plugin.hh"
#include "gazebo/rendering/Camera.hh"
#include "gazebo/sensors/CameraSensor.hh"

namespace gazebo {

class GZ_PLUGIN_VISIBLE CameraPlugin : public SensorPlugin {
 public:
  CameraPlugin();
  virtual ~CameraPlugin();
  virtual void Load(sensors::SensorPtr _sensor, sdf::ElementPtr _sdf);
  // After each frame: the pixels, [pixels] width and height, [bytes] per pixel, the format; does nothing here.
  virtual void OnNewFrame(const unsigned char* _image, unsigned int _width, unsigned int _height, unsigned int _depth,
                          const std::string& _format);

 protected:
  unsigned int width, height, depth;
  std::string format;
  sensors::CameraSensorPtr parentSensor;
  rendering::CameraPtr camera;

 private:
  event::ConnectionPtr newFrameConnection;
};

}  // namespace gazebo
