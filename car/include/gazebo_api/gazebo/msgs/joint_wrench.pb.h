// car's Gazebo 11 API (docs/PLUGINS.md): gazebo::msgs::JointWrench, hand-written (vector3d.pb.h): the wrench on
// each of a contact's two bodies.
#pragma once

#include <cstdint>
#include <string>

#include "gazebo/msgs/wrench.pb.h"

namespace gazebo {
namespace msgs {

class JointWrench {
 public:
  const std::string& body_1_name() const { return body_1_name_; }
  const std::string& body_2_name() const { return body_2_name_; }
  uint32_t body_1_id() const { return body_1_id_; }
  uint32_t body_2_id() const { return body_2_id_; }
  const Wrench& body_1_wrench() const { return body_1_wrench_; }
  const Wrench& body_2_wrench() const { return body_2_wrench_; }
  void set_body_1_name(const std::string& _v) { body_1_name_ = _v; }
  void set_body_2_name(const std::string& _v) { body_2_name_ = _v; }
  void set_body_1_id(uint32_t _v) { body_1_id_ = _v; }
  void set_body_2_id(uint32_t _v) { body_2_id_ = _v; }
  Wrench* mutable_body_1_wrench() { return &body_1_wrench_; }
  Wrench* mutable_body_2_wrench() { return &body_2_wrench_; }

 private:
  std::string body_1_name_, body_2_name_;
  uint32_t body_1_id_ = 0, body_2_id_ = 0;
  Wrench body_1_wrench_, body_2_wrench_;
};

}  // namespace msgs
}  // namespace gazebo
