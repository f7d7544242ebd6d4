// The plug-in registry: every kind car simulates, one line each. A new kind adds its folder under src/plugins/
// and one line here (and, for ROS, one line in src/ros/adapters/registry.cpp).
#include <map>

#include "car_sim/plugin.hpp"
#include "camera/camera.hpp"
#include "diff_drive/diff_drive.hpp"
#include "imu/imu.hpp"
#include "laser/laser.hpp"
#include "openni_kinect/openni_kinect.hpp"
#include "p3d/p3d.hpp"
#include "range/range.hpp"
#include "block_laser/block_laser.hpp"
#include "depth_camera/depth_camera.hpp"
#include "velodyne/velodyne.hpp"
#include "hector_sonar/hector_sonar.hpp"
#include "hector_magnetic/hector_magnetic.hpp"
#include "hector_gps/hector_gps.hpp"
#include "hector_imu/hector_imu.hpp"
#include "multicamera/multicamera.hpp"

namespace car_sim {

const std::vector<const PluginKind*>& plugin_kinds() {
  static const std::vector<const PluginKind*> kinds = {
      &diff_drive_kind(),
      &laser_kind(),
      &camera_kind(),
      &openni_kinect_kind(),
      &imu_kind(),
      &p3d_kind(),
      &range_kind(),
      &block_laser_kind(),
      &depth_camera_kind(),
      &velodyne_kind(),
      &hector_sonar_kind(),
      &hector_magnetic_kind(),
      &hector_gps_kind(),
      &hector_imu_kind(),
      &multicamera_kind(),
  };
  return kinds;
}

const PluginKind* find_plugin_kind(const std::string& name) {
  for (const PluginKind* k : plugin_kinds())
    if (k->name == name) return k;
  return nullptr;
}

const PluginKind* plugin_kind_for_file(const std::string& filename) {
  static const std::map<std::string, const PluginKind*> by_file = [] {
    std::map<std::string, const PluginKind*> m;
    for (const PluginKind* k : plugin_kinds())
      for (const auto& f : k->filenames) m[f] = k;
    return m;
  }();
  const auto it = by_file.find(filename);
  return it == by_file.end() ? nullptr : it->second;
}

}  // namespace car_sim
