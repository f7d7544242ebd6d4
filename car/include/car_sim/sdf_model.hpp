// SDF robots: an SDF <model> (SDF 1.4-1.9 through sdformat) read into the core's RobotModel, so it is spawned and
// simulated exactly as a URDF robot. Rules and their upstream sources: docs/COMPAT-sdf.md. No ROS headers.
#pragma once

#include <Eigen/Geometry>
#include <string>

#include "car_sim/model.hpp"

namespace car_sim {

// A loaded SDF model: the robot and where its root link sits in the document's frame.
struct SdfRobot {
  RobotModel model;
  // Root link frame in the frame the document places the model in: the model's <pose> (in the world for a
  // <world><include>) composed with the root link's pose in the model [m, rad]. The spawn pose goes on top.
  Eigen::Isometry3d root_pose = Eigen::Isometry3d::Identity();
  bool is_static = false;  // <static>true: anchored by a fixed joint from `world` (already in model.joints)
};

// Reads an SDF document holding one <model> (or a <world> with one, e.g. gazebo_ros's -database wrapper
// <world><include><uri>model://NAME</uri></include></world>). model:// resolves through GAZEBO_MODEL_PATH, then
// car's models/ (model.config's <sdf> picks the file). Relative URIs resolve against base_dir.
// Throws LoadError naming source, line, element and reason.
SdfRobot load_sdf_model_string(const std::string& xml, const std::string& source_name = "<string>",
                               const LoadOptions& options = LoadOptions(), const std::string& base_dir = "");

// True when the text's root element is <sdf> (gazebo_ros isSDF); false for <robot> and anything else.
bool is_sdf_document(const std::string& xml);

}  // namespace car_sim
