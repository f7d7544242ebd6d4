// Meshes: STL, COLLADA (DAE) and OBJ read through assimp, resolved by the URI rule (package://, model://, file://,
// plain paths), cached by file. Physics collides a dynamic body's mesh as its convex hull and a static one as its
// exact triangles; the ray scene (lidar, cameras) always sees the exact triangles. No ROS headers.
#pragma once

#include <memory>
#include <string>

#include "car_sim/description.hpp"
#include "car_sim/model.hpp"

namespace car_sim {

// The triangles of a mesh file (cached: the same path loads once). Throws LoadError(path, 0, "", reason) when the
// file cannot be read or holds no triangles.
std::shared_ptr<const TriMesh> load_mesh(const std::string& path);

// Where a URI was looked for, for an error message ("ROS_PACKAGE_PATH: /a:/b", "/abs/file", ...).
std::string mesh_search_description(const std::string& uri, const std::string& base_dir);

// Resolves and loads every mesh of a robot's collisions and visuals that is not loaded yet. Relative URIs start at
// base_dir (the URDF file's folder; "" for text: the current folder). A collision mesh that cannot be found or read
// throws LoadError naming the link, the URI and where it looked (or why); a visual's is a "visual-mesh-missing"
// warning appended to model->diagnostics, and that visual keeps no triangles (Gazebo simulates such a model).
void load_meshes(RobotModel* model, const std::string& base_dir);
// The same for a world's collisions and visuals (relative URIs from the world file's folder; warnings in
// world->diagnostics).
void load_meshes(WorldDescription* world, const std::string& base_dir);

}  // namespace car_sim
