// car's Gazebo 11 API (docs/PLUGINS.md "Transport"): gazebo::msgs::ImageStamped (image_stamped.proto), hand-written
// (vector3d.pb.h): the time the image was taken and the image.
#pragma once

#include <string>

#include "gazebo/msgs/image.pb.h"
#include "gazebo/msgs/time.pb.h"

namespace gazebo {
namespace msgs {

class ImageStamped {
 public:
  const Time& time() const { return time_; }
  Time* mutable_time() { return &time_; }
  const Image& image() const { return image_; }
  Image* mutable_image() { return &image_; }
  std::string GetTypeName() const { return "gazebo.msgs.ImageStamped"; }

 private:
  Time time_;
  Image image_;
};

}  // namespace msgs
}  // namespace gazebo
