// car's Gazebo 11 API (docs/PLUGINS.md): the transport car offers (a Node and a Publisher for ~/factory).
#pragma once

#include "gazebo/transport/Node.hh"
#include "gazebo/transport/Publisher.hh"
#include "gazebo/transport/Subscriber.hh"
#include "gazebo/transport/TransportTypes.hh"
