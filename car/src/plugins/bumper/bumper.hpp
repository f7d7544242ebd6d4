// libgazebo_ros_bumper.so in <sensor type="contact">: the contacts of the sensor's collision (its link's rigid
// body), one state per other body, as gazebo_msgs/ContactsState.
#pragma once

#include <string>
#include <vector>

#include "car_sim/plugin.hpp"

namespace car_sim {

// ContactPair (one pair of bodies in contact) is a sample type of the ports (car_sim/ports.hpp).
struct ContactsOut : Output {
  std::vector<ContactPair> states;
  void visit(FieldVisitor& v) const override;
  const std::vector<ContactPair>* contacts_sample() const override { return &states; }
};

// The link a contact sensor's <contact><collision> names: "LINK_collision", "LINK_collision_N", or a lumped
// "TOP_fixed_joint_lump__LINK_collision" (Gazebo's URDF names); "" when no link of the model matches.
std::string link_of_collision(const RobotModel& model, const std::string& collision);

const PluginKind& bumper_kind();

}  // namespace car_sim
