// car's Gazebo 11 API (docs/PLUGINS.md "Sensor plug-in bases"): gazebo::DepthCameraPlugin
// (gazebo/plugins/DepthCameraPlugin.hh), the base of depth cameras' plug-ins: Load takes the parent DepthCameraSensor
// and its depth camera, activates the sensor, and calls OnNewDepthFrame with each depth frame ([m], "FLOAT32") and
// OnNewImageFrame with each colour frame; OnNewRGBPointCloud, OnNewReflectanceFrame and OnNewNormalsFrame never come
// in car (its depth camera renders no point cloud, reflectance or normals of Gazebo's). Link the library
// DepthCameraPlugin, as with Gazebo 11.
#pragma once

#include <string>

#include "gazebo/common/Plugin.hh"
#include "gazebo/rendering/DepthCamera.hh"
#include "gazebo/sensors/CameraSensor.hh"
#include "gazebo/sensors/DepthCameraSensor.hh"

namespace gazebo {

class GZ_PLUGIN_VISIBLE DepthCameraPlugin : public SensorPlugin {
 public:
  DepthCameraPlugin();
  virtual ~DepthCameraPlugin();
  void Load(sensors::SensorPtr _sensor, sdf::ElementPtr _sdf);
  // Here, as Gazebo 11's: prints the frame's size, middle point's depth, its least and greatest depth.
  virtual void OnNewDepthFrame(const float* _image, unsigned int _width, unsigned int _height, unsigned int _depth,
                               const std::string& _format);
  virtual void OnNewRGBPointCloud(const float* _pcd, unsigned int _width, unsigned int _height, unsigned int _depth,
                                  const std::string& _format);
  virtual void OnNewImageFrame(const unsigned char* _image, unsigned int _width, unsigned int _height,
                               unsigned int _depth, const std::string& _format);
  virtual void OnNewReflectanceFrame(const float* _reflectance, unsigned int _width, unsigned int _height,
                                     unsigned int _depth, const std::string& _format);
  virtual void OnNewNormalsFrame(const float* _normals, unsigned int _width, unsigned int _height,
                                 unsigned int _depth, const std::string& _format);

 protected:
  unsigned int width, height, depth;
  std::string format;
  sensors::DepthCameraSensorPtr parentSensor;
  rendering::DepthCameraPtr depthCamera;

 private:
  event::ConnectionPtr newDepthFrameConnection;
  event::ConnectionPtr newRGBPointCloudConnection;
  event::ConnectionPtr newImageFrameConnection;
  event::ConnectionPtr newReflectanceFrameConnection;
  event::ConnectionPtr newNormalsFrameConnection;
};

}  // namespace gazebo
