// car's Gazebo 11 API (docs/PLUGINS.md): gazebo::msgs::Time, hand-written (vector3d.pb.h).
#pragma once

#include <cstdint>

namespace gazebo {
namespace msgs {

class Time {
 public:
  int32_t sec() const { return sec_; }
  int32_t nsec() const { return nsec_; }
  void set_sec(int32_t _v) { sec_ = _v; }
  void set_nsec(int32_t _v) { nsec_ = _v; }

 private:
  int32_t sec_ = 0, nsec_ = 0;
};

}  // namespace msgs
}  // namespace gazebo
