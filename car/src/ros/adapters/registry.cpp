// The ROS adapters, one line per plug-in kind (the kind's registry name and its adapter's factory).
#include <cstring>

#include "../adapter.hpp"

namespace car_ros {

std::unique_ptr<Adapter> make_ros_control_adapter();

namespace {

const AdapterKind kAdapters[] = {
    {"ros_control", make_ros_control_adapter},
};

}  // namespace

const AdapterKind* find_adapter(const std::string& kind) {
  for (const auto& a : kAdapters)
    if (kind == a.kind) return &a;
  return nullptr;
}

}  // namespace car_ros
