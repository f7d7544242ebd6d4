// libgazebo_ros_f3d.so: the external force and torque applied to a link (ground truth of what plug-ins and
// services push with). WrenchOut is also the output of ft_sensor.
#pragma once

#include "car_sim/plugin.hpp"

namespace car_sim {

// wrench [N], [N m]: the frame is the kind's (f3d: world; ft_sensor: the child link)
struct WrenchOut : Output, WrenchSample {
  void visit(FieldVisitor& v) const override;
  void samples(SampleList& list) const override { list.add(static_cast<const WrenchSample*>(this)); }
};

const PluginKind& f3d_kind();

}  // namespace car_sim
