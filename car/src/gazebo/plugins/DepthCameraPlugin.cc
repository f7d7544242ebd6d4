// gazebo::DepthCameraPlugin for car (docs/PLUGINS.md "Sensor plug-in bases"), as Gazebo 11's
// plugins/DepthCameraPlugin.cc behaves; the library libDepthCameraPlugin.so is itself a sensor plug-in, as upstream's.
#include "gazebo/plugins/DepthCameraPlugin.hh"

#include <cstdio>
#include <functional>

#include "gazebo/common/Console.hh"

namespace gazebo {

GZ_REGISTER_SENSOR_PLUGIN(DepthCameraPlugin)

DepthCameraPlugin::DepthCameraPlugin() : SensorPlugin(), width(0), height(0), depth(0) {}

DepthCameraPlugin::~DepthCameraPlugin() {
  this->newDepthFrameConnection.reset();
  this->newRGBPointCloudConnection.reset();
  this->newImageFrameConnection.reset();
  this->newReflectanceFrameConnection.reset();
  this->newNormalsFrameConnection.reset();
  this->parentSensor.reset();
  this->depthCamera.reset();
}

void DepthCameraPlugin::Load(sensors::SensorPtr _sensor, sdf::ElementPtr /*_sdf*/) {
  using std::placeholders::_1;
  using std::placeholders::_2;
  using std::placeholders::_3;
  using std::placeholders::_4;
  using std::placeholders::_5;
  this->parentSensor = std::dynamic_pointer_cast<sensors::DepthCameraSensor>(_sensor);
  // upstream's message; where Gazebo 11 first reads the depth camera of no sensor (a crash), car returns
  if (!this->parentSensor) {
    gzerr << "DepthCameraPlugin not attached to a depthCamera sensor\n";
    return;
  }
  this->depthCamera = this->parentSensor->DepthCamera();
  this->width = this->depthCamera->ImageWidth();
  this->height = this->depthCamera->ImageHeight();
  this->depth = this->depthCamera->ImageDepth();
  this->format = this->depthCamera->ImageFormat();
  this->newDepthFrameConnection =
      this->depthCamera->ConnectNewDepthFrame(std::bind(&DepthCameraPlugin::OnNewDepthFrame, this, _1, _2, _3, _4, _5));
  this->newRGBPointCloudConnection = this->depthCamera->ConnectNewRGBPointCloud(
      std::bind(&DepthCameraPlugin::OnNewRGBPointCloud, this, _1, _2, _3, _4, _5));
  this->newImageFrameConnection =
      this->depthCamera->ConnectNewImageFrame(std::bind(&DepthCameraPlugin::OnNewImageFrame, this, _1, _2, _3, _4, _5));
  this->newReflectanceFrameConnection = this->depthCamera->ConnectNewReflectanceFrame(
      std::bind(&DepthCameraPlugin::OnNewReflectanceFrame, this, _1, _2, _3, _4, _5));
  this->newNormalsFrameConnection = this->depthCamera->ConnectNewNormalsPointCloud(
      std::bind(&DepthCameraPlugin::OnNewNormalsFrame, this, _1, _2, _3, _4, _5));
  this->parentSensor->SetActive(true);
}

// As upstream's: the frame's size, its middle point's depth, its least and greatest depth [m]
void DepthCameraPlugin::OnNewDepthFrame(const float* _image, unsigned int _width, unsigned int _height,
                                        unsigned int /*_depth*/, const std::string& /*_format*/) {
  float min = 1000, max = 0;
  for (unsigned int i = 0; i < _width * _height; i++) {
    if (_image[i] > max) max = _image[i];
    if (_image[i] < min) min = _image[i];
  }
  const int index = ((_height * 0.5) * _width) + _width * 0.5;
  printf("W[%u] H[%u] MidPoint[%d] Dist[%f] Min[%f] Max[%f]\n", width, height, index, _image[index], min, max);
}

void DepthCameraPlugin::OnNewRGBPointCloud(const float*, unsigned int, unsigned int, unsigned int,
                                           const std::string&) {}

void DepthCameraPlugin::OnNewImageFrame(const unsigned char*, unsigned int, unsigned int, unsigned int,
                                        const std::string&) {}

void DepthCameraPlugin::OnNewReflectanceFrame(const float*, unsigned int, unsigned int, unsigned int,
                                              const std::string&) {}

void DepthCameraPlugin::OnNewNormalsFrame(const float*, unsigned int, unsigned int, unsigned int, const std::string&) {}

}  // namespace gazebo
