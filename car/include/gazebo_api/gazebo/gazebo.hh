// car's Gazebo 11 API (docs/PLUGINS.md): #include <gazebo/gazebo.hh> as in Gazebo 11; the subset car offers.
#pragma once

#include "gazebo/gazebo_config.h"
#include "gazebo/common/common.hh"
#include "gazebo/physics/PhysicsTypes.hh"
