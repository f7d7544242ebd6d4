// car's Gazebo 11 API (docs/PLUGINS.md): #include <gazebo/msgs/msgs.hh>, the messages car offers as plain classes
// with protobuf's accessors (not protobuf): msgs::Factory (a model to insert, Gazebo's ~/factory topic) with
// msgs::Pose, the contact messages a ContactSensor gives (contact.pb.h, ...), msgs::ImageStamped with msgs::Image,
// msgs::LaserScanStamped with msgs::LaserScan (a ray sensor's scans on its topic),
// and the conversions to ignition-math and common::Time.
// The other messages are not declared.
#pragma once

#include <ignition/math/Pose3.hh>
#include <ignition/math/Vector3.hh>
#include <string>

#include "gazebo/common/Time.hh"
#include "gazebo/msgs/contact.pb.h"
#include "gazebo/msgs/contacts.pb.h"
#include "gazebo/msgs/image.pb.h"
#include "gazebo/msgs/image_stamped.pb.h"
#include "gazebo/msgs/MessageTypes.hh"
#include "gazebo/msgs/joint_wrench.pb.h"
#include "gazebo/msgs/laserscan.pb.h"
#include "gazebo/msgs/laserscan_stamped.pb.h"
#include "gazebo/msgs/time.pb.h"
#include "gazebo/msgs/vector3d.pb.h"
#include "gazebo/msgs/wrench.pb.h"

namespace gazebo {
namespace msgs {

// A pose, world frame: position [m] and orientation.
class Pose {
 public:
  // car: the value, as msgs::Set writes it.
  ignition::math::Pose3d value;
};

// A model to insert (factory.proto): its SDF text or its file (model://NAME or a path), where (replacing the
// document's <pose>) and whether a name taken may become NAME_0, NAME_1, ... (default true, as upstream).
class Factory {
 public:
  void set_sdf(const std::string& _v) { sdf_ = _v; has_sdf_ = true; }
  const std::string& sdf() const { return sdf_; }
  bool has_sdf() const { return has_sdf_; }
  void set_sdf_filename(const std::string& _v) { file_ = _v; has_file_ = true; }
  const std::string& sdf_filename() const { return file_; }
  bool has_sdf_filename() const { return has_file_; }
  Pose* mutable_pose() { has_pose_ = true; return &pose_; }
  const Pose& pose() const { return pose_; }
  bool has_pose() const { return has_pose_; }
  void set_allow_renaming(bool _v) { allow_renaming_ = _v; }
  bool allow_renaming() const { return allow_renaming_; }
  std::string GetTypeName() const { return "gazebo.msgs.Factory"; }

 private:
  std::string sdf_, file_;
  bool has_sdf_ = false, has_file_ = false, has_pose_ = false, allow_renaming_ = true;
  Pose pose_;
};

void Set(Pose* _p, const ignition::math::Pose3d& _v);
ignition::math::Pose3d ConvertIgn(const Pose& _p);

inline ignition::math::Vector3d ConvertIgn(const Vector3d& _v) { return {_v.x(), _v.y(), _v.z()}; }

// msgs::Time <-> common::Time (sec, nsec as they are)
void Set(Time* _t, const common::Time& _v);
Time Convert(const common::Time& _t);
common::Time Convert(const Time& _t);

}  // namespace msgs
}  // namespace gazebo
