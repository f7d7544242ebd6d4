// The colour rule, in one place (the ray scene's surfaces, the Python tools and rviz markers all use it):
// a URDF link looks like its <gazebo><material> Gazebo/Name when known, else its URDF colour, else grey; an SDF
// visual like its material script Gazebo/Name when known, else <diffuse>, else <ambient>, else grey.
// Gazebo/Name colours come from config/gazebo_materials.txt. No ROS headers.
#pragma once

#include <Eigen/Core>
#include <map>
#include <optional>
#include <string>

#include "car_sim/description.hpp"
#include "car_sim/model.hpp"

namespace car_sim {

// Gazebo's grey, for surfaces that set no colour.
inline const Eigen::Vector4d kDefaultColour(0.7, 0.7, 0.7, 1.0);

// Gazebo's standard materials as colours (textured ones as their texture's mean colour).
const std::map<std::string, Eigen::Vector4d>& gazebo_colours();
std::optional<Eigen::Vector4d> gazebo_colour(const std::string& name);

// RGBA of an SDF visual: script, else diffuse, else ambient, else grey.
Eigen::Vector4d visual_colour(const std::string& script, const std::optional<Eigen::Vector4d>& diffuse,
                              const std::optional<Eigen::Vector4d>& ambient);
Eigen::Vector4d visual_colour(const WorldVisual& v);
// RGBA of a URDF link: its <gazebo><material>, else its first visual's colour, else a visual mesh's own material,
// else grey.
Eigen::Vector4d link_colour(const Link& l);

}  // namespace car_sim
