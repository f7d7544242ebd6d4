// Car's collision configuration (private to physics/): Bullet's, with car's algorithms for a shape against a
// plane (plane_collision.cpp; docs/COMPAT-physics.md "Contact points").
#pragma once

#include <btBulletDynamicsCommon.h>

#include <memory>

namespace car_sim {
namespace physics {

// Bullet's default collision configuration, except a box, a sphere, another convex shape or a compound against a
// plane, which car's algorithms collide.
std::unique_ptr<btCollisionConfiguration> make_collision_config();

}  // namespace physics
}  // namespace car_sim
