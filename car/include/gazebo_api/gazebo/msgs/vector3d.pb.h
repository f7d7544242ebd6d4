// car's Gazebo 11 API (docs/PLUGINS.md): gazebo::msgs::Vector3d. Gazebo's messages are protobuf classes; car's are
// plain hand-written classes with the accessors plug-ins read (x(), set_x(), ...), not protobuf: no serialisation.
#pragma once

namespace gazebo {
namespace msgs {

class Vector3d {
 public:
  double x() const { return x_; }
  double y() const { return y_; }
  double z() const { return z_; }
  void set_x(double _v) { x_ = _v; }
  void set_y(double _v) { y_ = _v; }
  void set_z(double _v) { z_ = _v; }

 private:
  double x_ = 0, y_ = 0, z_ = 0;
};

}  // namespace msgs
}  // namespace gazebo
