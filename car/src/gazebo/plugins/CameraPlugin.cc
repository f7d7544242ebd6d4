// gazebo::CameraPlugin for car (docs/PLUGINS.md "Sensor plug-in bases"), as Gazebo 11's plugins/CameraPlugin.cc
// behaves; the library libCameraPlugin.so is itself a sensor plug-in, as upstream's.
#include "gazebo/plugins/CameraPlugin.hh"

#include <functional>

#include "gazebo/common/Console.hh"

namespace gazebo {

GZ_REGISTER_SENSOR_PLUGIN(CameraPlugin)

CameraPlugin::CameraPlugin() : SensorPlugin(), width(0), height(0), depth(0) {}

CameraPlugin::~CameraPlugin() {
  this->newFrameConnection.reset();
  this->parentSensor.reset();
  this->camera.reset();
}

void CameraPlugin::Load(sensors::SensorPtr _sensor, sdf::ElementPtr /*_sdf*/) {
  if (!_sensor) gzerr << "Invalid sensor pointer.\n";
  this->parentSensor = std::dynamic_pointer_cast<sensors::CameraSensor>(_sensor);
  // upstream's two messages; where Gazebo 11 then reads the camera of no sensor (a crash), car returns
  if (!this->parentSensor) {
    gzerr << "CameraPlugin requires a CameraSensor.\n";
    gzerr << "CameraPlugin not attached to a camera sensor\n";
    return;
  }
  this->camera = this->parentSensor->Camera();
  this->width = this->camera->ImageWidth();
  this->height = this->camera->ImageHeight();
  this->depth = this->camera->ImageDepth();
  this->format = this->camera->ImageFormat();
  this->newFrameConnection = this->camera->ConnectNewImageFrame(
      std::bind(&CameraPlugin::OnNewFrame, this, std::placeholders::_1, std::placeholders::_2, std::placeholders::_3,
                std::placeholders::_4, std::placeholders::_5));
  this->parentSensor->SetActive(true);
}

void CameraPlugin::OnNewFrame(const unsigned char* /*_image*/, unsigned int /*_width*/, unsigned int /*_height*/,
                              unsigned int /*_depth*/, const std::string& /*_format*/) {}

}  // namespace gazebo
