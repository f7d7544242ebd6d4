// libgazebo_ros_force.so: a wrench from a topic, applied to a link every step until the next one.
#pragma once

#include "car_sim/plugin.hpp"

namespace car_sim {

// A plug-in that takes a wrench command (through its input port).
class WrenchCommand {
 public:
  virtual ~WrenchCommand() = default;
  // force [N] at the link's centre of mass and torque [N m], world frame; holds until the next call
  virtual void set_wrench(const Wrench& w) = 0;
};

// The point a link's force acts at: its centre of mass (its <inertial> origin; the link origin without one).
Eigen::Vector3d link_com(const RobotHandle& robot, const std::string& link);

const PluginKind& force_kind();

}  // namespace car_sim
