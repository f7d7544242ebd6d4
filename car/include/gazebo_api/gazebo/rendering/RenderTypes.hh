// car's Gazebo 11 API (docs/PLUGINS.md "Sensors"): the cameras' pointer types, std::shared_ptr as in Gazebo 11's
// gazebo/rendering/RenderTypes.hh. car renders by ray casting (docs/COMPAT-sensors.md): no OGRE, no scene.
#pragma once

#include <memory>

namespace gazebo {
namespace rendering {

class Camera;
class DepthCamera;

typedef std::shared_ptr<Camera> CameraPtr;
typedef std::shared_ptr<DepthCamera> DepthCameraPtr;

}  // namespace rendering
}  // namespace gazebo
