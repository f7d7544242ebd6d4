// car's Gazebo 11 API (docs/PLUGINS.md "Sensors"): gazebo::sensors::DepthCameraSensor, the colour and depth
// frames of car's depth camera (libgazebo_ros_depth_camera.so's kind) for a <sensor type="depth">.
#pragma once

#include "gazebo/rendering/RenderTypes.hh"
#include "gazebo/sensors/CameraSensor.hh"

namespace gazebo {
namespace sensors {

class DepthCameraSensor : public CameraSensor {
 public:
  DepthCameraSensor(const car_sim::SensorSpec& _spec, const std::string& _world, const std::string& _model,
                    const std::vector<std::pair<std::string, std::string>>& _keys);
  // [m] per pixel along the optical axis, rows top first; nullptr before the first frame.
  const float* DepthData() const;
  // Its depth camera: ConnectNewDepthFrame, as Gazebo's rendering::DepthCamera.
  rendering::DepthCameraPtr DepthCamera() const;

 protected:
  void CarMeasure(const car_sim::Output* _sample) override;
  rendering::DepthCameraPtr depthCamera;
};

}  // namespace sensors
}  // namespace gazebo
