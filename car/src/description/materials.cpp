#include "materials.hpp"

#include <fstream>
#include <sstream>

#include "package_path.hpp"

namespace car_sim {

const std::map<std::string, Eigen::Vector4d>& gazebo_colours() {
  static const std::map<std::string, Eigen::Vector4d> table = [] {
    std::map<std::string, Eigen::Vector4d> t;
    std::ifstream in(detail::car_package_dir() + "/config/gazebo_materials.txt");
    std::string line;
    while (std::getline(in, line)) {
      line = line.substr(0, line.find('#'));
      std::istringstream ls(line);
      std::string name;
      Eigen::Vector4d c;
      if (ls >> name >> c[0] >> c[1] >> c[2] >> c[3]) t[name] = c;
    }
    return t;
  }();
  return table;
}

std::optional<Eigen::Vector4d> gazebo_colour(const std::string& name) {
  const auto it = gazebo_colours().find(name);
  if (it == gazebo_colours().end()) return std::nullopt;
  return it->second;
}

Eigen::Vector4d visual_colour(const std::string& script, const std::optional<Eigen::Vector4d>& diffuse,
                              const std::optional<Eigen::Vector4d>& ambient) {
  if (auto c = gazebo_colour(script)) return *c;
  if (diffuse) return *diffuse;
  if (ambient) return *ambient;
  return kDefaultColour;
}

Eigen::Vector4d visual_colour(const WorldVisual& v) {
  return visual_colour(v.script_name, v.material.has_rgba ? std::optional<Eigen::Vector4d>(v.material.rgba) : std::nullopt,
                       v.has_ambient ? std::optional<Eigen::Vector4d>(v.ambient) : std::nullopt);
}

Eigen::Vector4d link_colour(const Link& l) {
  if (auto c = gazebo_colour(l.gazebo.material)) return *c;
  for (const auto& v : l.visuals)
    if (v.material.has_rgba) return v.material.rgba;
  // where the URDF gives no colour, a visual mesh's own material
  for (const auto& v : l.visuals)
    if (v.shape.mesh && v.shape.mesh->colour) return *v.shape.mesh->colour;
  return kDefaultColour;
}

}  // namespace car_sim
