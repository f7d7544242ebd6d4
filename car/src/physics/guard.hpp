// The physics guards itself (private to the core): after a step, the first body whose state is not finite.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

class btMultiBodyDynamicsWorld;

namespace car_sim {
namespace physics {

// Thrown by Physics::step when a body's state turned non-finite; what() names the body and the quantity.
struct NonFiniteState : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// "model/link: position (nan nan nan)" for the first body (rigid body, static object or multibody link) whose
// pose, velocity or joint coordinates are not finite; "" when every one is. names: collision object user index
// -> "model/link".
std::string first_non_finite(const btMultiBodyDynamicsWorld& world, const std::vector<std::string>& names);

}  // namespace physics
}  // namespace car_sim
