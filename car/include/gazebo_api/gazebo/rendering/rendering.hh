// car's Gazebo 11 API (docs/PLUGINS.md "Sensors"): #include <gazebo/rendering/rendering.hh>, the cameras car offers.
#pragma once

#include "gazebo/rendering/Camera.hh"
#include "gazebo/rendering/DepthCamera.hh"
#include "gazebo/rendering/RenderTypes.hh"
