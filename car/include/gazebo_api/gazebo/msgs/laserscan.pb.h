// car's Gazebo 11 API (docs/PLUGINS.md "Sensors"): gazebo::msgs::LaserScan (laserscan.proto), hand-written
// (vector3d.pb.h): a ray sensor's scan, as Gazebo's RaySensor fills it: its parent's name (frame), the sensor's world
// pose, the horizontal and vertical angles [rad] and counts, the range limits [m], and the ranges [m] and
// intensities, row by row.
#pragma once

#include <cstdint>
#include <string>

#include "gazebo/msgs/repeated_field.hh"

namespace gazebo {
namespace msgs {

class LaserScan {
 public:
#define CAR_MSGS_FIELD(type, name)                 \
  type name() const { return name##_; }            \
  void set_##name(type _v) { name##_ = _v; }
  CAR_MSGS_FIELD(double, angle_min)
  CAR_MSGS_FIELD(double, angle_max)
  CAR_MSGS_FIELD(double, angle_step)
  CAR_MSGS_FIELD(double, range_min)
  CAR_MSGS_FIELD(double, range_max)
  CAR_MSGS_FIELD(uint32_t, count)
  CAR_MSGS_FIELD(double, vertical_angle_min)
  CAR_MSGS_FIELD(double, vertical_angle_max)
  CAR_MSGS_FIELD(double, vertical_angle_step)
  CAR_MSGS_FIELD(uint32_t, vertical_count)
#undef CAR_MSGS_FIELD
  const std::string& frame() const { return frame_; }
  void set_frame(const std::string& _v) { frame_ = _v; }
  const RepeatedField<double>& ranges() const { return ranges_; }
  RepeatedField<double>* mutable_ranges() { return &ranges_; }
  double ranges(int _i) const { return ranges_.Get(_i); }
  int ranges_size() const { return ranges_.size(); }
  void add_ranges(double _v) { ranges_.Add(_v); }
  void clear_ranges() { ranges_.Clear(); }
  const RepeatedField<double>& intensities() const { return intensities_; }
  RepeatedField<double>* mutable_intensities() { return &intensities_; }
  double intensities(int _i) const { return intensities_.Get(_i); }
  int intensities_size() const { return intensities_.size(); }
  void add_intensities(double _v) { intensities_.Add(_v); }
  void clear_intensities() { intensities_.Clear(); }

 private:
  std::string frame_;
  double angle_min_ = 0, angle_max_ = 0, angle_step_ = 0, range_min_ = 0, range_max_ = 0;
  uint32_t count_ = 0;
  double vertical_angle_min_ = 0, vertical_angle_max_ = 0, vertical_angle_step_ = 0;
  uint32_t vertical_count_ = 0;
  RepeatedField<double> ranges_, intensities_;
};

}  // namespace msgs
}  // namespace gazebo
