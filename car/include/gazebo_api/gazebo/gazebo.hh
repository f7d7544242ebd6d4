// car's Gazebo 11 API (docs/PLUGINS.md): #include <gazebo/gazebo.hh> as in Gazebo 11 (common, msgs, transport); the
// subset car offers.
#pragma once

#include "gazebo/gazebo_config.h"
#include "gazebo/common/common.hh"
#include "gazebo/msgs/msgs.hh"
#include "gazebo/physics/PhysicsTypes.hh"
#include "gazebo/transport/transport.hh"
