// The ROS adapters, one line per plug-in kind (the kind's registry name and its adapter's factory).
#include <cstring>

#include "../adapter.hpp"

namespace car_ros {

std::unique_ptr<Adapter> make_diff_drive_adapter();
std::unique_ptr<Adapter> make_laser_adapter();
std::unique_ptr<Adapter> make_camera_adapter();
std::unique_ptr<Adapter> make_openni_kinect_adapter();
std::unique_ptr<Adapter> make_imu_adapter();
std::unique_ptr<Adapter> make_p3d_adapter();
std::unique_ptr<Adapter> make_range_adapter();
std::unique_ptr<Adapter> make_block_laser_adapter();
std::unique_ptr<Adapter> make_velodyne_adapter();
std::unique_ptr<Adapter> make_hector_sonar_adapter();
std::unique_ptr<Adapter> make_hector_magnetic_adapter();
std::unique_ptr<Adapter> make_hector_gps_adapter();
std::unique_ptr<Adapter> make_hector_imu_adapter();
std::unique_ptr<Adapter> make_multicamera_adapter();

namespace {

const AdapterKind kAdapters[] = {
    {"diff_drive", make_diff_drive_adapter},
    {"laser", make_laser_adapter},
    {"camera", make_camera_adapter},
    {"openni_kinect", make_openni_kinect_adapter},
    {"imu", make_imu_adapter},
    {"p3d", make_p3d_adapter},
    {"range", make_range_adapter},
    {"block_laser", make_block_laser_adapter},
    {"depth_camera", make_openni_kinect_adapter},  // same topics and messages as the Kinect
    {"velodyne", make_velodyne_adapter},
    {"hector_sonar", make_hector_sonar_adapter},
    {"hector_magnetic", make_hector_magnetic_adapter},
    {"hector_gps", make_hector_gps_adapter},
    {"hector_imu", make_hector_imu_adapter},
    {"multicamera", make_multicamera_adapter},
};

}  // namespace

const AdapterKind* find_adapter(const std::string& kind) {
  for (const auto& a : kAdapters)
    if (kind == a.kind) return &a;
  return nullptr;
}

}  // namespace car_ros
