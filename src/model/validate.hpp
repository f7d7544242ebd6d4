// Limits and validation before allocation (private to the core): every number a URDF or SDF world writes is
// checked before urdfdom, sdformat, the physics or a plug-in allocates anything from it. Errors are LoadErrors
// naming file, line, element and reason with the value as written; out-of-range values the physics can still
// use are warnings.
#pragma once

#include <tinyxml2.h>

#include <string>
#include <vector>

#include "car_sim/description.hpp"
#include "car_sim/model.hpp"

namespace car_sim {
namespace limits {

// [kg] a link mass outside this range is a warning (a unit mistake, or a body the solver handles badly)
constexpr double kMassMin = 1e-6, kMassMax = 1e6;
// [kg m^2] a diagonal inertia entry outside this range is a warning
constexpr double kInertiaMin = 1e-12, kInertiaMax = 1e6;
// [m] shape sizes and positions above this are errors: the ray scene works in single precision (a float's step
// at 1e6 m is 6 cm)
constexpr double kLengthMax = 1e6;
// includes nested deeper than this are refused (the world tools' flattener has the same limit)
constexpr int kIncludeDepthMax = 32;
// models (and <include>s) in one world: libsdformat 12 holds about 2.5 MB and takes about 15 ms per model while it
// parses (measured: 1000 static boxes, 2.5 GB, 15 s), so a larger world is refused before sdformat sees it
constexpr int kWorldModelsMax = 1000;

}  // namespace limits

namespace detail {

// A URDF document before urdfdom reads it: DTD entity declarations are refused; every number of every link and
// joint (origins, mass, inertia, geometry, axis, limits, dynamics, calibration, mimic, safety controller) must be
// finite; sizes > 0; lengths and positions within limits::kLengthMax; damping and friction >= 0. Throws LoadError
// for the first error in document order; returns the warnings (mass and inertia out of range, negative effort or
// velocity limits).
std::vector<Diagnostic> validate_urdf(const tinyxml2::XMLDocument& doc, const std::string& source);

// SDF text before sdformat reads it: DTD entities refused, every numeric element finite, and every <include>
// found, acyclic and at most limits::kIncludeDepthMax deep (each included file checked the same way). base_dir:
// where relative URIs resolve ("" for text). Throws LoadError naming file, line, element and reason.
void prevalidate_sdf(const std::string& xml, const std::string& source, const std::string& base_dir);

// A converted world: step size > 0 and finite, gravity finite, real-time factor finite and >= 0; every model's
// poses, masses, inertias and shape sizes by the URDF's rules. Throws LoadError for errors; appends warnings to
// d->diagnostics.
void validate_world(WorldDescription* d);

}  // namespace detail
}  // namespace car_sim
