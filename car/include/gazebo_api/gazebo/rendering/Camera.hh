// car's Gazebo 11 API (docs/PLUGINS.md "Sensors"): gazebo::rendering::Camera, a camera sensor's frames and its
// new-frame event. car's camera is its ray-cast one (docs/COMPAT-sensors.md); the frame event fires after each
// measurement of its sensor, on the physics thread.
#pragma once

#include <functional>
#include <ignition/math/Angle.hh>
#include <string>
#include <vector>

#include "gazebo/common/Event.hh"
#include "gazebo/common/PID.hh"
#include "gazebo/common/Time.hh"
#include "gazebo/msgs/MessageTypes.hh"
#include "gazebo/msgs/msgs.hh"
#include "gazebo/rendering/RenderTypes.hh"
#include "gazebo/transport/Node.hh"
#include "gazebo/transport/Subscriber.hh"

namespace gazebo {
namespace rendering {

class CameraEvents;

class Camera {
 public:
  // car: made by car_gazebo for a camera sensor; `_format` is <image><format> ("R8G8B8", "L8", ...).
  Camera(const std::string& _name, unsigned int _width, unsigned int _height, const std::string& _format,
         double _hfov);
  virtual ~Camera();

  std::string Name() const;
  unsigned int ImageWidth() const;
  unsigned int ImageHeight() const;
  // [bytes] per pixel
  unsigned int ImageDepth() const;
  std::string ImageFormat() const;
  // [rad] <horizontal_fov>
  ignition::math::Angle HFOV() const;
  // The last frame (nullptr before the first); car's cameras have one frame (_i 0).
  const unsigned char* ImageData(const unsigned int _i = 0) const;
  // (image, width, height, depth [bytes per pixel], format), after each frame.
  event::ConnectionPtr ConnectNewImageFrame(
      std::function<void(const unsigned char*, unsigned int, unsigned int, unsigned int, const std::string&)>
          _subscriber);

  // car: a new frame: its bytes copied, the event raised.
  void CarFrame(const unsigned char* _data, size_t _bytes);

 protected:
  std::string name, format;
  unsigned int width, height, depth;
  double hfov;
  std::vector<unsigned char> image;
  std::shared_ptr<CameraEvents> events;
};

}  // namespace rendering
}  // namespace gazebo
