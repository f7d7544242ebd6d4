// Internal: an sdformat DOM model to the core's RobotModel (sdf_model.cpp), shared by the SDF robot loader and the
// world loader (models inside a world that have plug-ins, sensors or joints). docs/COMPAT-sdf.md.
#pragma once

#include <sdf/Model.hh>

#include "car_sim/sdf_model.hpp"

namespace car_sim {
namespace detail {

// Converts one model; the returned root_pose is the root link in the frame the model's own pose is given in.
// Throws LoadError naming source, element and reason for what car cannot simulate.
SdfRobot convert_sdf_model(const sdf::Model& m, const std::string& source, const LoadOptions& options);

// True when a world model needs the robot path: a <plugin> (model or sensor), a <sensor>, or a joint.
bool sdf_model_is_robot(const sdf::Model& m);

}  // namespace detail
}  // namespace car_sim
