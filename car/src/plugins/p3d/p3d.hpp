// libgazebo_ros_p3d.so: a link's pose and twist (ground truth), in the world or relative to another link of the
// model, with constant offsets and Gaussian noise on the twist. The ROS node attaches one to every robot for
// /gazebo/ground_truth/<model>.
#pragma once

#include <string>

#include "car_sim/plugin.hpp"

namespace car_sim {

struct P3dOut : Output {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // the body's frame in frameName's frame
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();        // [m/s] of the body's origin, frameName's axes
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();       // [rad/s], frameName's axes
  void visit(FieldVisitor& v) const override;
  void samples(SampleList& list) const override { list.add(OdometrySample{pose, linear, angular, std::nullopt}); }
};

const PluginKind& p3d_kind();

}  // namespace car_sim
