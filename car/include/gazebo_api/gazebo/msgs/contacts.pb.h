// car's Gazebo 11 API (docs/PLUGINS.md): gazebo::msgs::Contacts, hand-written (vector3d.pb.h): a contact sensor's
// contacts of one update.
#pragma once

#include <vector>

#include "gazebo/msgs/contact.pb.h"
#include "gazebo/msgs/time.pb.h"

namespace gazebo {
namespace msgs {

class Contacts {
 public:
  int contact_size() const { return static_cast<int>(contact_.size()); }
  const Contact& contact(int _i) const { return contact_.at(_i); }
  Contact* add_contact() { contact_.emplace_back(); return &contact_.back(); }
  void clear_contact() { contact_.clear(); }
  const Time& time() const { return time_; }
  Time* mutable_time() { return &time_; }

 private:
  std::vector<Contact> contact_;
  Time time_;
};

}  // namespace msgs
}  // namespace gazebo
