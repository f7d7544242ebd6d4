// car's Gazebo 11 API (docs/PLUGINS.md "Sensors"): gazebo::sensors::CameraSensor, the frames of car's ray-cast
// camera (libgazebo_ros_camera.so's kind) for a <sensor type="camera">.
#pragma once

#include <string>

#include "gazebo/rendering/RenderTypes.hh"
#include "gazebo/sensors/Sensor.hh"

namespace gazebo {
namespace sensors {

class CameraSensor : public Sensor {
 public:
  CameraSensor(const car_sim::SensorSpec& _spec, const std::string& _world, const std::string& _model,
               const std::vector<std::pair<std::string, std::string>>& _keys);
  // [px] <camera><image>
  unsigned int ImageWidth() const;
  unsigned int ImageHeight() const;
  // The last frame, rows top first, ImageWidth() x ImageDepth() bytes each; nullptr before the first.
  const unsigned char* ImageData() const;
  // Its camera: ConnectNewImageFrame, as Gazebo's rendering::Camera.
  rendering::CameraPtr Camera() const;

 protected:
  void CarMeasure(const car_sim::Output* _sample) override;
  rendering::CameraPtr camera;
};

}  // namespace sensors
}  // namespace gazebo
