// car's Gazebo 11 API (docs/PLUGINS.md): gazebo::msgs::Contact, hand-written (vector3d.pb.h): one pair of
// collisions in contact, its points in the world frame.
#pragma once

#include <string>
#include <vector>

#include "gazebo/msgs/joint_wrench.pb.h"
#include "gazebo/msgs/time.pb.h"
#include "gazebo/msgs/vector3d.pb.h"

namespace gazebo {
namespace msgs {

class Contact {
 public:
  // "model::link::collision"
  const std::string& collision1() const { return collision1_; }
  const std::string& collision2() const { return collision2_; }
  void set_collision1(const std::string& _v) { collision1_ = _v; }
  void set_collision2(const std::string& _v) { collision2_ = _v; }
  // [m], world frame
  int position_size() const { return static_cast<int>(position_.size()); }
  const Vector3d& position(int _i) const { return position_.at(_i); }
  Vector3d* add_position() { position_.emplace_back(); return &position_.back(); }
  // unit, world frame
  int normal_size() const { return static_cast<int>(normal_.size()); }
  const Vector3d& normal(int _i) const { return normal_.at(_i); }
  Vector3d* add_normal() { normal_.emplace_back(); return &normal_.back(); }
  // [m] penetration
  int depth_size() const { return static_cast<int>(depth_.size()); }
  double depth(int _i) const { return depth_.at(_i); }
  void add_depth(double _v) { depth_.push_back(_v); }
  int wrench_size() const { return static_cast<int>(wrench_.size()); }
  const JointWrench& wrench(int _i) const { return wrench_.at(_i); }
  JointWrench* add_wrench() { wrench_.emplace_back(); return &wrench_.back(); }
  const Time& time() const { return time_; }
  Time* mutable_time() { return &time_; }
  const std::string& world() const { return world_; }
  void set_world(const std::string& _v) { world_ = _v; }

 private:
  std::string collision1_, collision2_, world_;
  std::vector<Vector3d> position_, normal_;
  std::vector<double> depth_;
  std::vector<JointWrench> wrench_;
  Time time_;
};

}  // namespace msgs
}  // namespace gazebo
