// A world of walls and a one-link robot carrying one sensor, for the ray-sensor kinds' tests (range, block laser,
// velodyne). The robot: a 0.2 m cube of 1 kg on the ground (its link frame at the cube's centre, z = 0.1 m).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "car_sim/world.hpp"
#include "test_util.hpp"

namespace car_sim {
namespace test_support {

// An SDF world: the ground plane plus the given static models (SDF <model> elements).
inline WorldDescription ray_world(const std::string& models) {
  return load_world_string(
      "<sdf version='1.6'><world name='w'>"
      "<model name='ground'><static>true</static><link name='l'><collision name='c'><geometry><plane>"
      "<normal>0 0 1</normal><size>100 100</size></plane></geometry></collision></link></model>" +
      models + "</world></sdf>");
}

// A static box model: centre (x, y, z) [m], size (sx, sy, sz) [m].
inline std::string box_model(const std::string& name, double x, double y, double z, double sx, double sy, double sz) {
  auto s = [](double v) { return std::to_string(v); };
  return "<model name='" + name + "'><static>true</static><pose>" + s(x) + " " + s(y) + " " + s(z) +
         " 0 0 0</pose><link name='l'><collision name='c'><geometry><box><size>" + s(sx) + " " + s(sy) + " " +
         s(sz) + "</size></box></geometry></collision></link></model>";
}

// The cube robot with one <gazebo reference="base"> block (a <sensor> element).
inline std::string cube_robot(const std::string& sensor) {
  return "<robot name='cube'><link name='base'><inertial><mass value='1'/><inertia ixx='0.0067' iyy='0.0067' "
         "izz='0.0067' ixy='0' ixz='0' iyz='0'/></inertial><collision><geometry><box size='0.2 0.2 0.2'/>"
         "</geometry></collision></link><gazebo reference='base'>" +
         sensor + "</gazebo></robot>";
}

// Spawns the cube at (x, y) with yaw [rad], resting on the ground.
inline std::unique_ptr<World> world_with_cube(const WorldDescription& d, const std::string& sensor, double x = 0,
                                              double y = 0, double yaw = 0, uint64_t seed = 0) {
  WorldOptions o;
  o.seed = seed;
  auto w = std::make_unique<World>(d, o);
  Eigen::Isometry3d p = at(x, y, yaw);
  p.translation().z() = 0.1;
  w->spawn(load_urdf_string(cube_robot(sensor), "cube"), "cube", p);
  return w;
}

// A <sensor type=TYPE> with a ray grid and one plug-in.
inline std::string ray_sensor(const std::string& type, const std::string& name, const std::string& pose,
                              const std::string& horizontal, const std::string& vertical, double rmin, double rmax,
                              const std::string& plugin) {
  return "<sensor type='" + type + "' name='" + name + "'><pose>" + pose +
         "</pose><update_rate>10</update_rate><ray><scan><horizontal>" + horizontal + "</horizontal><vertical>" +
         vertical + "</vertical></scan><range><min>" + std::to_string(rmin) + "</min><max>" + std::to_string(rmax) +
         "</max></range></ray>" + plugin + "</sensor>";
}

inline std::string scan_axis(int samples, double min_angle, double max_angle) {
  return "<samples>" + std::to_string(samples) + "</samples><resolution>1</resolution><min_angle>" +
         std::to_string(min_angle) + "</min_angle><max_angle>" + std::to_string(max_angle) + "</max_angle>";
}

// The plug-ins resolved (and their diagnostics) when the cube carries `plugin` (a <plugin> element) on a 3 x 3
// sensor of `type`.
inline ModelConfig resolved_on(const std::string& type, const std::string& plugin) {
  return resolve_plugins(load_urdf_string(
      cube_robot(ray_sensor(type, "s", "0 0 0.2 0 0 0", scan_axis(3, -0.1, 0.1), scan_axis(3, -0.1, 0.1), 0.05, 3.0,
                            plugin)),
      "cube"));
}

// The kinds of the plug-ins resolved_on(type, plugin) loads: empty when the plug-in is not loaded.
inline std::vector<std::string> loaded_kinds_on(const std::string& type, const std::string& plugin) {
  std::vector<std::string> kinds;
  for (const auto& p : resolved_on(type, plugin).plugins) kinds.push_back(p.kind);
  return kinds;
}

// The message of the plugin-not-loaded diagnostic when the cube carries `plugin` (a <plugin> element) on a 3 x 3
// sensor of `type`; "" when it loads.
inline std::string not_loaded_on(const std::string& type, const std::string& plugin) {
  const ModelConfig c = resolved_on(type, plugin);
  for (const auto& d : c.diagnostics)
    if (d.code == "plugin-not-loaded") return d.message;
  return "";
}

}  // namespace test_support
}  // namespace car_sim
