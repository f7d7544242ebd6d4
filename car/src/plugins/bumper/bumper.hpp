// libgazebo_ros_bumper.so in <sensor type="contact">: the contacts of the sensor's collision (its link's rigid
// body), one state per other body, as gazebo_msgs/ContactsState.
#pragma once

#include <string>
#include <vector>

#include "car_sim/plugin.hpp"

namespace car_sim {

// states: one ContactPair per pair of bodies in contact (ContactsSample, car_sim/ports.hpp)
struct ContactsOut : Output, ContactsSample {
  void visit(FieldVisitor& v) const override;
  void samples(SampleList& list) const override { list.add(static_cast<const ContactsSample*>(this)); }
};

// The link a contact sensor's <contact><collision> names: "LINK_collision", "LINK_collision_N", or a lumped
// "TOP_fixed_joint_lump__LINK_collision" (Gazebo's URDF names); "" when no link of the model matches.
std::string link_of_collision(const RobotModel& model, const std::string& collision);

const PluginKind& bumper_kind();

}  // namespace car_sim
