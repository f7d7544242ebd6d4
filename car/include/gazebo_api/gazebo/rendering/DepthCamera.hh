// car's Gazebo 11 API (docs/PLUGINS.md "Sensors"): gazebo::rendering::DepthCamera, a depth sensor's depth frames
// and their event, beside its colour frames (Camera).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "gazebo/common/CommonTypes.hh"
#include "gazebo/rendering/Camera.hh"

namespace gazebo {
namespace rendering {

class DepthCamera : public Camera {
 public:
  using Camera::Camera;
  // [m] per pixel along the optical axis, rows top first; nullptr before the first frame.
  const float* DepthData() const;
  // (depth, width, height, 1, "FLOAT32"), after each frame.
  event::ConnectionPtr ConnectNewDepthFrame(
      std::function<void(const float*, unsigned int, unsigned int, unsigned int, const std::string&)> _subscriber);

  // Gazebo's events of the depth camera's point cloud, reflectance and normals: car's depth camera renders none of
  // them, so these never fire (DepthCameraPlugin connects them; docs/PLUGINS.md "Sensor plug-in bases").
  event::ConnectionPtr ConnectNewRGBPointCloud(
      std::function<void(const float*, unsigned int, unsigned int, unsigned int, const std::string&)> _subscriber);
  event::ConnectionPtr ConnectNewReflectanceFrame(
      std::function<void(const float*, unsigned int, unsigned int, unsigned int, const std::string&)> _subscriber);
  event::ConnectionPtr ConnectNewNormalsPointCloud(
      std::function<void(const float*, unsigned int, unsigned int, unsigned int, const std::string&)> _subscriber);
  // car: a new depth frame: copied, the event raised.
  void CarDepthFrame(const float* _depth);

 private:
  std::vector<float> depthData;
};

}  // namespace rendering
}  // namespace gazebo
