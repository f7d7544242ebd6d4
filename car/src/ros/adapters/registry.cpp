// The ROS adapters, one line per plug-in kind (the kind's registry name and its adapter's factory).
#include <cstring>

#include "../adapter.hpp"

namespace car_ros {

std::unique_ptr<Adapter> make_laser_adapter();
std::unique_ptr<Adapter> make_imu_adapter();
std::unique_ptr<Adapter> make_f3d_adapter();
std::unique_ptr<Adapter> make_bumper_adapter();
std::unique_ptr<Adapter> make_ft_sensor_adapter();
std::unique_ptr<Adapter> make_hand_of_god_adapter();
std::unique_ptr<Adapter> make_range_adapter();
std::unique_ptr<Adapter> make_block_laser_adapter();
std::unique_ptr<Adapter> make_velodyne_adapter();
std::unique_ptr<Adapter> make_hector_sonar_adapter();
std::unique_ptr<Adapter> make_hector_magnetic_adapter();
std::unique_ptr<Adapter> make_hector_gps_adapter();
std::unique_ptr<Adapter> make_hector_imu_adapter();
std::unique_ptr<Adapter> make_ros_control_adapter();

namespace {

const AdapterKind kAdapters[] = {
    {"laser", make_laser_adapter},
    {"imu", make_imu_adapter},
    {"f3d", make_f3d_adapter},
    {"bumper", make_bumper_adapter},
    {"ft_sensor", make_ft_sensor_adapter},
    {"hand_of_god", make_hand_of_god_adapter},
    {"range", make_range_adapter},
    {"block_laser", make_block_laser_adapter},
    {"velodyne", make_velodyne_adapter},
    {"hector_sonar", make_hector_sonar_adapter},
    {"hector_magnetic", make_hector_magnetic_adapter},
    {"hector_gps", make_hector_gps_adapter},
    {"hector_imu", make_hector_imu_adapter},
    {"ros_control", make_ros_control_adapter},
};

}  // namespace

const AdapterKind* find_adapter(const std::string& kind) {
  for (const auto& a : kAdapters)
    if (kind == a.kind) return &a;
  return nullptr;
}

}  // namespace car_ros
