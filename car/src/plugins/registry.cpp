// The plug-in registry: every kind car simulates, one line each, and last the entry for plug-ins from shared
// libraries (users' own Gazebo plug-ins). A new kind adds its folder under src/plugins/
// and one line here.
#include <map>

#include "car_sim/plugin.hpp"
#include "camera/camera.hpp"
#include "diff_drive/diff_drive.hpp"
#include "imu/imu.hpp"
#include "imu_sensor/imu_sensor.hpp"
#include "laser/laser.hpp"
#include "openni_kinect/openni_kinect.hpp"
#include "p3d/p3d.hpp"
#include "planar_move/planar_move.hpp"
#include "skid_steer_drive/skid_steer_drive.hpp"
#include "joint_state_publisher/joint_state_publisher.hpp"
#include "force/force.hpp"
#include "f3d/f3d.hpp"
#include "bumper/bumper.hpp"
#include "ft_sensor/ft_sensor.hpp"
#include "hand_of_god/hand_of_god.hpp"
#include "joint_pose_trajectory/joint_pose_trajectory.hpp"
#include "tricycle_drive/tricycle_drive.hpp"
#include "range/range.hpp"
#include "block_laser/block_laser.hpp"
#include "depth_camera/depth_camera.hpp"
#include "velodyne/velodyne.hpp"
#include "hector_sonar/hector_sonar.hpp"
#include "hector_magnetic/hector_magnetic.hpp"
#include "hector_gps/hector_gps.hpp"
#include "hector_imu/hector_imu.hpp"
#include "multicamera/multicamera.hpp"
#include "ros_control/ros_control.hpp"
#include "triggered_camera/triggered_camera.hpp"
#include "shared_library/shared_library.hpp"
#include "car_sim/shared_plugin.hpp"

namespace car_sim {

const std::vector<const PluginKind*>& plugin_kinds() {
  static const std::vector<const PluginKind*> kinds = {
      &diff_drive_kind(),
      &laser_kind(),
      &camera_kind(),
      &openni_kinect_kind(),
      &imu_kind(),
      &imu_sensor_kind(),
      &p3d_kind(),
      &planar_move_kind(),
      &skid_steer_drive_kind(),
      &joint_state_publisher_kind(),
      &force_kind(),
      &f3d_kind(),
      &bumper_kind(),
      &ft_sensor_kind(),
      &hand_of_god_kind(),
      &joint_pose_trajectory_kind(),
      &tricycle_drive_kind(),
      &range_kind(),
      &block_laser_kind(),
      &depth_camera_kind(),
      &velodyne_kind(),
      &hector_sonar_kind(),
      &hector_magnetic_kind(),
      &hector_gps_kind(),
      &hector_imu_kind(),
      &multicamera_kind(),
      &ros_control_kind(),
      &triggered_camera_kind(),
      // any other robot-level file found on the search path: a plug-in from a shared library (a user's own)
      &shared_library_kind(),
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
  if (it != by_file.end() && !upstream_plugin_wanted(filename)) return it->second;
  return find_shared_plugin(filename, shared_plugin_search_path()).empty() ? (it == by_file.end() ? nullptr : it->second)
                                                                          : &shared_library_kind();
}

}  // namespace car_sim
