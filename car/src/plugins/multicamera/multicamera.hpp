// libgazebo_ros_multicamera.so on a <sensor type="multicamera">: the cameras whose names contain "left" and
// "right" (a stereo pair), rendered at the same tick by the shared ray-cast camera.
#pragma once

#include <string>
#include <vector>

#include "../common/camera_render.hpp"
#include "car_sim/plugin.hpp"

namespace car_sim {

struct MultiCameraOut : Output {
  std::vector<std::string> sides;  // "left", "right" (those the sensor has)
  std::vector<CameraOut> frames;   // one per side, same tick
  void visit(FieldVisitor& v) const override;
  void samples(SampleList& list) const override;  // frame i: frames[i]
};

const PluginKind& multicamera_kind();

}  // namespace car_sim
