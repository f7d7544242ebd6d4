// Internal: an sdformat DOM model to the core's RobotModel (sdf_model.cpp), shared by the SDF robot loader and the
// world loader (models inside a world that have plug-ins, sensors or joints), with the DOM readers both use: poses,
// shapes, sdformat's errors. docs/COMPAT-sdf.md.
#pragma once

#include <sdf/Error.hh>
#include <sdf/Geometry.hh>
#include <sdf/Model.hh>
#include <sdf/Visual.hh>

#include <optional>
#include <string>
#include <vector>

#include "car_sim/description.hpp"
#include "car_sim/sdf_model.hpp"

namespace car_sim {
namespace detail {

Eigen::Isometry3d to_iso(const ignition::math::Pose3d& p);

// An element's line in its file; 0 when sdformat does not know it.
int line_of(const sdf::ElementPtr& e);

// sdformat's first error as a LoadError (with how many more there were); returns when there is none. An error
// inside an included file names that file; one in the text itself names source (sdformat calls such text
// "data-string"). Not errors, as Gazebo 11 loads the model or world: LINK_INERTIA_INVALID (car warns itself) and,
// with warnings given, an <include> that resolves nowhere (a warning "include-missing"; the rest loads).
void refuse_errors(const std::string& source, const sdf::Errors& errors, std::vector<Diagnostic>* warnings);

// Rule 9: box, cylinder, sphere, mesh, plane as a Shape (origin identity); anything else is nullopt with a warning
// at `where` (line: its line, 0 = unknown) appended to *diagnostics.
std::optional<Shape> to_shape(const sdf::Geometry& g, const std::string& where, int line,
                              std::vector<Diagnostic>* diagnostics);

// A <visual> of link `where` ("model[M]/link[L]"): its shape in the link frame, its material (script name, rgba from
// <diffuse>, <ambient>); nullopt for a geometry car does not draw (to_shape's warning appended). The one reader of
// visuals, for robots and world models alike.
std::optional<WorldVisual> read_visual(const sdf::Visual& v, const std::string& where,
                                       std::vector<Diagnostic>* diagnostics);

// A link's <inertial> as the DOM gives it: SDF's default (1 kg, unit inertia at the link origin) when absent (Rule 3).
// The one reader of inertials, for robots and world models alike.
Inertial read_inertial(const sdf::Link& l);

// Converts one model; the returned root_pose is the root link in the frame the model's own pose is given in.
// Throws LoadError naming source, element and reason for what car cannot simulate.
SdfRobot convert_sdf_model(const sdf::Model& m, const std::string& source, const LoadOptions& options);

// True when a world model needs the robot path: a <plugin> (model or sensor), a <sensor>, or a joint.
bool sdf_model_is_robot(const sdf::Model& m);

}  // namespace detail
}  // namespace car_sim
