// libgazebo_ros_hand_of_god.so: a link pulled to a desired pose (from TF) by a critically damped spring, its
// gravity switched off.
#pragma once

#include "car_sim/plugin.hpp"

namespace car_sim {

// A plug-in that follows a pose target (its input port, which a ROS skin reads from TF).
class PoseTarget {
 public:
  virtual ~PoseTarget() = default;
  virtual void set_target(const Eigen::Isometry3d& world_pose) = 0;
};

struct PoseOut : Output {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // the link's frame, world frame
  void visit(FieldVisitor& v) const override;
  void samples(SampleList& list) const override { list.add(TransformSample{pose}); }
};

// The hand of god's wrench for a link at `pose` moving at v (world) and w_link (link frame) toward `target`:
// force kl (p_target - p) - cl v, world frame; torque ka log(R^-1 R_target) - ca w_link, link frame, where log of
// a unit quaternion is half the rotation vector (ignition's Quaternion::Log, as upstream).
Wrench hand_of_god_wrench(const Eigen::Isometry3d& pose, const Eigen::Vector3d& v, const Eigen::Vector3d& w_link,
                          const Eigen::Isometry3d& target, double kl, double ka, double cl, double ca);

const PluginKind& hand_of_god_kind();

}  // namespace car_sim
