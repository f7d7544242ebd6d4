// car's Gazebo 11 API (docs/PLUGINS.md "Transport"): gazebo::msgs::Image (image.proto), hand-written (vector3d.pb.h):
// width and height [pixels], pixel_format (common::Image::PixelFormat), step [bytes per row] and the data bytes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace gazebo {
namespace msgs {

class Image {
 public:
  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }
  uint32_t pixel_format() const { return pixel_format_; }
  uint32_t step() const { return step_; }
  const std::string& data() const { return data_; }
  void set_width(uint32_t _v) { width_ = _v; }
  void set_height(uint32_t _v) { height_ = _v; }
  void set_pixel_format(uint32_t _v) { pixel_format_ = _v; }
  void set_step(uint32_t _v) { step_ = _v; }
  void set_data(const std::string& _v) { data_ = _v; }
  void set_data(const void* _v, size_t _size) { data_.assign(static_cast<const char*>(_v), _size); }
  std::string* mutable_data() { return &data_; }

 private:
  uint32_t width_ = 0, height_ = 0, pixel_format_ = 0, step_ = 0;
  std::string data_;
};

}  // namespace msgs
}  // namespace gazebo
