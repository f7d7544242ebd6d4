// The output half of the ROS bridge for the camera sample types: Image -> sensor_msgs/Image (the frame's colour
// image), CameraInfo -> sensor_msgs/CameraInfo, DepthImage -> sensor_msgs/Image (32FC1 or 16UC1), DepthCloud ->
// sensor_msgs/PointCloud2 (organized). The big messages are serialised by roscpp straight from the output's arrays
// on the publishing thread (image_msgs.hpp), which keeps the output until they are sent. Names no plug-in kind.
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>

#include "conversions.hpp"
#include "image_msgs.hpp"
#include "outputs.hpp"

namespace car_ros {

std::string OutputPorts::setup_image(Port& p, NodeContext& node) {
  using T = car_sim::SampleType;
  const car_sim::OutputPort& op = p.port;
  switch (op.type) {
    case T::Image:
      p.pub = node.advertise<sensor_msgs::Image>(op.topic, op.queue);
      return "image " + op.topic;
    case T::CameraInfo:
      p.pub = node.advertise<sensor_msgs::CameraInfo>(op.topic, op.queue);
      return "camera_info " + op.topic;
    case T::DepthImage:
      p.pub = node.advertise<sensor_msgs::Image>(op.topic, op.queue);
      return std::string("depth image ") + (op.image.millimetres ? "(16UC1) " : "") + op.topic;
    case T::DepthCloud:
      p.pub = node.advertise<sensor_msgs::PointCloud2>(op.topic, op.queue);
      return "cloud " + op.topic;
    default: return "";
  }
}

namespace {

// A frame's view for the serialisers: the sample's arrays, the output that holds them, its frame and stamp.
template <class V>
V frame_view(const std::shared_ptr<const car_sim::Output>& out, car_sim::ImageSample s, const std::string& frame,
             const ros::Time& stamp) {
  V v;
  v.owner = out;
  v.sample = std::move(s);
  v.frame = frame;
  v.stamp = stamp;
  return v;
}

}  // namespace

void OutputPorts::publish_image(Port& p, const std::shared_ptr<const car_sim::Output>& out, const ros::Time& stamp,
                                NodeContext& node) {
  using T = car_sim::SampleType;
  car_sim::ImageSample s;
  if (!out->image_sample(p.port.image.frame, &s)) return;
  // a part nobody took as the frame was made is not in it (a subscriber that came since gets the next frame)
  const bool listened = p.pub.getNumSubscribers() > 0;
  switch (p.port.type) {
    case T::Image: {
      if (!listened || !s.image) return;
      // at most one per period of sim time where the kind throttles its images (PeriodGate, as camera_info)
      if (!p.gate.due(static_cast<int64_t>(stamp.toNSec()))) return;
      node.publish(p.pub, frame_view<ImageView>(out, std::move(s), p.frame, stamp));
      return;
    }
    case T::CameraInfo: {
      // at most one per period of sim time (PeriodGate: upstream's rule, time going back restarting the count)
      if (!p.gate.due(static_cast<int64_t>(stamp.toNSec()))) return;
      node.publish(p.pub, camera_info(s, p.port.image, p.frame, stamp));
      return;
    }
    case T::DepthImage: {
      if (!listened || !s.depth) return;
      DepthView v = frame_view<DepthView>(out, std::move(s), p.frame, stamp);
      v.millimetres = p.port.image.millimetres;
      node.publish(p.pub, std::move(v));
      return;
    }
    case T::DepthCloud: {
      if (!listened || !s.points) return;
      node.publish(p.pub, frame_view<CloudView>(out, std::move(s), p.frame, stamp));
      return;
    }
    default: return;
  }
}

}  // namespace car_ros
