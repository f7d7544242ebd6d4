// The ROS adapters, one line per plug-in kind (the kind's registry name and its adapter's factory).
#include <cstring>

#include "../adapter.hpp"

namespace car_ros {

std::unique_ptr<Adapter> make_camera_adapter();
std::unique_ptr<Adapter> make_openni_kinect_adapter();
std::unique_ptr<Adapter> make_multicamera_adapter();
std::unique_ptr<Adapter> make_triggered_camera_adapter();
std::unique_ptr<Adapter> make_ros_control_adapter();

namespace {

const AdapterKind kAdapters[] = {
    {"camera", make_camera_adapter},
    {"openni_kinect", make_openni_kinect_adapter},
    {"depth_camera", make_openni_kinect_adapter},  // same topics and messages as the Kinect
    {"multicamera", make_multicamera_adapter},
    {"triggered_camera", make_triggered_camera_adapter},
    {"ros_control", make_ros_control_adapter},
};

}  // namespace

const AdapterKind* find_adapter(const std::string& kind) {
  for (const auto& a : kAdapters)
    if (kind == a.kind) return &a;
  return nullptr;
}

}  // namespace car_ros
