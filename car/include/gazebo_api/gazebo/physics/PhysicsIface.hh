// car's Gazebo 11 API (docs/PLUGINS.md): the free functions of gazebo/physics/PhysicsIface.hh that plug-ins call.
// car's worlds are its simulator's; the others (create_world, load_world, run_world, ...) belong to gzserver's own
// start-up and are not offered.
#pragma once

#include <string>

#include "gazebo/physics/PhysicsTypes.hh"

namespace gazebo {
namespace physics {

// The world named _name, or, for "", the world of the plug-in running now (gzserver's first and only world). None:
// gzerr "Unable to find world by name in physics::get_world[NAME]" and gzthrow, as Gazebo 11's.
WorldPtr get_world(const std::string& _name = "");
// Whether get_world(_name) finds one.
bool has_world(const std::string& _name = "");

}  // namespace physics
}  // namespace gazebo
