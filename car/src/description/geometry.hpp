// Internal: the SDF geometry car simulates (world_tool check's rule in validate.cpp; car._core.simulated_geometry).
#pragma once

#include <string>
#include <vector>

namespace car_sim {

// The SDF geometry elements detail::to_shape converts (box, cylinder, sphere, plane, mesh); the others are loaded
// and ignored with a warning (docs/COMPAT-sdf.md rule 9).
const std::vector<std::string>& simulated_geometry();

}  // namespace car_sim
