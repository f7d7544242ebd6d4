// libgazebo_ros_bumper.so in <sensor type="contact">: the contacts of the sensor's collision (its link's rigid
// body), one state per other body, as gazebo_msgs/ContactsState.
#pragma once

#include <string>
#include <vector>

#include "car_sim/plugin.hpp"

namespace car_sim {

// One pair of bodies in contact: gazebo_msgs/ContactState's fields.
struct ContactPair {
  std::string collision1, collision2;   // "model::link::collision" (this sensor's), "model::link" (the other)
  std::vector<Wrench> wrenches;         // [N], world frame: force on collision1 at each point (torque 0)
  Wrench total;                         // sum of wrenches
  std::vector<Eigen::Vector3d> positions;  // [m], world frame
  std::vector<Eigen::Vector3d> normals;    // unit, world frame, from collision2 into collision1
  std::vector<double> depths;              // [m]
};

struct ContactsOut : Output {
  std::vector<ContactPair> states;
  void visit(FieldVisitor& v) const override;
};

// The link a contact sensor's <contact><collision> names: "LINK_collision", "LINK_collision_N", or a lumped
// "TOP_fixed_joint_lump__LINK_collision" (Gazebo's URDF names); "" when no link of the model matches.
std::string link_of_collision(const RobotModel& model, const std::string& collision);

const PluginKind& bumper_kind();

}  // namespace car_sim
