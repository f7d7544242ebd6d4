// car's Gazebo 11 API (docs/PLUGINS.md): what a world update event carries.
#pragma once

#include <string>

#include "gazebo/common/Time.hh"

namespace gazebo {
namespace common {

class UpdateInfo {
 public:
  std::string worldName;
  common::Time simTime;   // the sim time of the step being made (WorldUpdateBegin: it counts the coming step)
  common::Time realTime;  // car: equal to simTime (the core reads no clock; docs/PLUGINS.md)
};

}  // namespace common
}  // namespace gazebo
