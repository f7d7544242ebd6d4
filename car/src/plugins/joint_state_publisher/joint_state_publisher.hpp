// libgazebo_ros_joint_state_publisher.so: the listed joints' positions and velocities at updateRate.
#pragma once

#include <string>
#include <vector>

#include "car_sim/plugin.hpp"

namespace car_sim {

struct JointStatesOut : Output {
  std::vector<JointState> joints;  // in the order of jointName
  void visit(FieldVisitor& v) const override;
  void samples(SampleList& list) const override { list.add(JointStatesSample{&joints, nullptr}); }
};

// jointName as upstream reads it: spaces removed, split at ',' (an empty piece stays a name, as boost::split).
std::vector<std::string> split_joint_names(const std::string& text);

const PluginKind& joint_state_publisher_kind();

}  // namespace car_sim
