// The converters of the camera sample types: ImageSample -> sensor_msgs/Image (the frame's colour image),
// CameraInfoSample -> sensor_msgs/CameraInfo, DepthImageSample -> sensor_msgs/Image (32FC1 or 16UC1),
// DepthCloudSample -> sensor_msgs/PointCloud2 (organized). The big messages are serialised by roscpp straight from
// the output's arrays on the publishing thread (image_msgs.hpp), which keeps the output until they are sent. Names
// no plug-in kind.
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>

#include "conversions.hpp"
#include "converters.hpp"
#include "image_msgs.hpp"

namespace car_ros {

namespace {

// A frame's view for the serialisers: the sample's arrays, the output that holds them, its frame and stamp.
template <class V>
V frame_view(const PublishContext& c, const car_sim::ImageSample& s, const std::string& frame) {
  V v;
  v.owner = c.owner;
  v.sample = s;
  v.frame = frame;
  v.stamp = c.stamp;
  return v;
}

// A part nobody took as the frame was made is not in it (a subscriber that came since gets the next frame).
bool listened(const OutPort& p) { return p.pub.getNumSubscribers() > 0; }

}  // namespace

template <>
std::string advertise<car_sim::ImageSample>(OutPort& p, const SetupContext& c) {
  p.pub = c.node.advertise<sensor_msgs::Image>(p.port.topic, p.port.queue);
  return "image " + p.port.topic;
}
// at most one per period of sim time where the kind throttles its images (PeriodGate, as camera_info)
template <>
void convert<car_sim::ImageSample>(OutPort& p, const car_sim::ImageSample& s, PublishContext& c) {
  if (!listened(p) || !s.image) return;
  if (!p.gate.due(static_cast<int64_t>(c.stamp.toNSec()))) return;
  c.node.publish(p.pub, frame_view<ImageView>(c, s, p.frames.frame));
}

// one message per period of camera_info's own (OutputPort::image.period)
template <>
std::string advertise<car_sim::CameraInfoSample>(OutPort& p, const SetupContext& c) {
  p.pub = c.node.advertise<sensor_msgs::CameraInfo>(p.port.topic, p.port.queue);
  p.gate = car_sim::PeriodGate(p.port.image.period);
  return "camera_info " + p.port.topic;
}
// at most one per period of sim time (PeriodGate: upstream's rule, time going back restarting the count)
template <>
void convert<car_sim::CameraInfoSample>(OutPort& p, const car_sim::CameraInfoSample& s, PublishContext& c) {
  if (!p.gate.due(static_cast<int64_t>(c.stamp.toNSec()))) return;
  c.node.publish(p.pub, camera_info(s, p.port.image, p.frames.frame, c.stamp));
}

template <>
std::string advertise<car_sim::DepthImageSample>(OutPort& p, const SetupContext& c) {
  p.pub = c.node.advertise<sensor_msgs::Image>(p.port.topic, p.port.queue);
  return std::string("depth image ") + (p.port.image.millimetres ? "(16UC1) " : "") + p.port.topic;
}
template <>
void convert<car_sim::DepthImageSample>(OutPort& p, const car_sim::DepthImageSample& s, PublishContext& c) {
  if (!listened(p) || !s.depth) return;
  DepthView v = frame_view<DepthView>(c, s, p.frames.frame);
  v.millimetres = p.port.image.millimetres;
  c.node.publish(p.pub, std::move(v));
}

template <>
std::string advertise<car_sim::DepthCloudSample>(OutPort& p, const SetupContext& c) {
  p.pub = c.node.advertise<sensor_msgs::PointCloud2>(p.port.topic, p.port.queue);
  return "cloud " + p.port.topic;
}
template <>
void convert<car_sim::DepthCloudSample>(OutPort& p, const car_sim::DepthCloudSample& s, PublishContext& c) {
  if (!listened(p) || !s.points) return;
  c.node.publish(p.pub, frame_view<CloudView>(c, s, p.frames.frame));
}

}  // namespace car_ros
