// The camera sample types' messages (sensor_msgs/Image, CameraInfo, PointCloud2) from an ImageSample: the views
// roscpp serialises straight from the core's arrays, and the same messages built as sensor_msgs structs. Names no
// plug-in kind.
#pragma once

#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>

#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "car_sim/ports.hpp"

namespace car_ros {

// A camera frame's big messages as roscpp serialises them straight from the core's arrays: the publishing thread
// hands one of these to ros::Publisher::publish, and roscpp's serialiser (below) writes the wire bytes of the
// sensor_msgs message into its send buffer in one pass; no sensor_msgs message is built and nothing is copied
// twice. Only when someone subscribes: roscpp serialises only for connected subscribers. The bytes equal those
// of camera_image(), depth_image() and point_cloud() (test/ros_msgs/test_camera_msgs.cpp).
struct FrameView {
  std::shared_ptr<const void> owner;  // the output that holds the sample's arrays, kept alive until sent
  car_sim::ImageSample sample;
  std::string frame;
  ros::Time stamp;
};
struct ImageView : FrameView {};
struct DepthView : FrameView {
  bool millimetres = false;  // 16UC1 [mm], else 32FC1 [m]
};
struct CloudView : FrameView {};

// The depth image's millimetres and the cloud's missing points: the core's rules (car_sim/ports.hpp), inline.
using car_sim::depth_mm;
using car_sim::has_point;
// rgb packed as 0x00RRGGBB in a float's bits, as PCL and rviz read it
inline uint32_t packed_rgb(const uint8_t* rgb) {
  return (uint32_t(rgb[0]) << 16) | (uint32_t(rgb[1]) << 8) | uint32_t(rgb[2]);
}

// The colour image, in the frame's encoding.
sensor_msgs::Image camera_image(const car_sim::ImageSample& s, const std::string& frame, const ros::Time& stamp);
// plumb_bob: D from the port (k1 k2 t1 t2 k3), K = [f 0 cx; 0 f cy; 0 0 1], P with -f * baseline.
sensor_msgs::CameraInfo camera_info(const car_sim::ImageSample& s, const car_sim::ImagePortSettings& port,
                                    const std::string& frame, const ros::Time& stamp);
// 32FC1 metres, or 16UC1 millimetres (0 where there is no depth).
sensor_msgs::Image depth_image(const car_sim::ImageSample& s, bool millimetres, const std::string& frame,
                               const ros::Time& stamp);
// Organized H x W cloud: x@0 y@4 z@8 rgb@16 (FLOAT32), point_step 32, optical frame.
sensor_msgs::PointCloud2 point_cloud(const car_sim::ImageSample& s, const std::string& frame, const ros::Time& stamp);
// The cloud's point fields, as the Kinect plug-in writes them: x@0 y@4 z@8 rgb@16 (FLOAT32, count 1), point_step 32.
const std::vector<sensor_msgs::PointField>& cloud_fields();

}  // namespace car_ros

// roscpp's traits and serialisers of the views: each is its sensor_msgs type on the wire.
namespace ros {
namespace message_traits {
#define CAR_VIEW_TRAITS(VIEW, MSG)                                                        \
  template <>                                                                             \
  struct MD5Sum<car_ros::VIEW> {                                                          \
    static const char* value() { return MD5Sum<MSG>::value(); }                           \
    static const char* value(const car_ros::VIEW&) { return value(); }                    \
  };                                                                                      \
  template <>                                                                             \
  struct DataType<car_ros::VIEW> {                                                        \
    static const char* value() { return DataType<MSG>::value(); }                         \
    static const char* value(const car_ros::VIEW&) { return value(); }                    \
  };                                                                                      \
  template <>                                                                             \
  struct Definition<car_ros::VIEW> {                                                      \
    static const char* value() { return Definition<MSG>::value(); }                       \
    static const char* value(const car_ros::VIEW&) { return value(); }                    \
  };
CAR_VIEW_TRAITS(ImageView, sensor_msgs::Image)
CAR_VIEW_TRAITS(DepthView, sensor_msgs::Image)
CAR_VIEW_TRAITS(CloudView, sensor_msgs::PointCloud2)
#undef CAR_VIEW_TRAITS
}  // namespace message_traits

namespace serialization {

namespace car_views {
// std_msgs/Header: seq (roscpp writes it when publishing), stamp, frame_id
inline uint32_t header_length(const car_ros::FrameView& v) { return 4 + 8 + 4 + static_cast<uint32_t>(v.frame.size()); }
template <class Stream>
void write_header(Stream& s, const car_ros::FrameView& v) {
  s.next(static_cast<uint32_t>(0));
  s.next(v.stamp);
  s.next(v.frame);
}
// sensor_msgs/Image up to its data's length: header, height, width, encoding, is_bigendian, step
template <class Stream>
void write_image_head(Stream& s, const car_ros::FrameView& v, const std::string& encoding, uint32_t step,
                      uint32_t bytes) {
  write_header(s, v);
  s.next(static_cast<uint32_t>(v.sample.height));
  s.next(static_cast<uint32_t>(v.sample.width));
  s.next(encoding);
  s.next(static_cast<uint8_t>(0));
  s.next(step);
  s.next(bytes);
}
inline uint32_t image_length(const car_ros::FrameView& v, const std::string& encoding, uint32_t bytes) {
  return header_length(v) + 4 + 4 + 4 + static_cast<uint32_t>(encoding.size()) + 1 + 4 + 4 + bytes;
}
}  // namespace car_views

template <>
struct Serializer<car_ros::ImageView> {
  template <class Stream>
  static void write(Stream& s, const car_ros::ImageView& v) {
    const car_sim::ImageSample& im = v.sample;
    const uint32_t n = static_cast<uint32_t>(im.image_bytes);
    car_views::write_image_head(s, v, im.encoding, im.step, n);
    if (n > 0) std::memcpy(s.advance(n), im.image, n);
  }
  static uint32_t serializedLength(const car_ros::ImageView& v) {
    return car_views::image_length(v, v.sample.encoding, static_cast<uint32_t>(v.sample.image_bytes));
  }
};

template <>
struct Serializer<car_ros::DepthView> {
  static const std::string& encoding(const car_ros::DepthView& v) {
    static const std::string mm = "16UC1", m = "32FC1";
    return v.millimetres ? mm : m;
  }
  static uint32_t bytes(const car_ros::DepthView& v) {
    return static_cast<uint32_t>(v.sample.width) * static_cast<uint32_t>(v.sample.height) * (v.millimetres ? 2u : 4u);
  }
  template <class Stream>
  static void write(Stream& s, const car_ros::DepthView& v) {
    const car_sim::ImageSample& o = v.sample;
    const uint32_t n = bytes(v);
    car_views::write_image_head(s, v, encoding(v), static_cast<uint32_t>(o.width) * (v.millimetres ? 2u : 4u), n);
    uint8_t* px = s.advance(n);
    if (v.millimetres) {
      // [mm], 0 where there is no depth
      const size_t count = static_cast<size_t>(o.width) * o.height;
      for (size_t i = 0; i < count; ++i) {
        const uint16_t d = car_ros::depth_mm(o.depth[i]);
        std::memcpy(px + 2 * i, &d, 2);
      }
    } else {
      std::memcpy(px, o.depth, n);
    }
  }
  static uint32_t serializedLength(const car_ros::DepthView& v) {
    return car_views::image_length(v, encoding(v), bytes(v));
  }
};

template <>
struct Serializer<car_ros::CloudView> {
  template <class Stream>
  static void write(Stream& s, const car_ros::CloudView& v) {
    const car_sim::ImageSample& o = v.sample;
    const size_t n = static_cast<size_t>(o.width) * o.height;
    car_views::write_header(s, v);
    s.next(static_cast<uint32_t>(o.height));
    s.next(static_cast<uint32_t>(o.width));
    s.next(car_ros::cloud_fields());
    s.next(static_cast<uint8_t>(0));  // is_bigendian
    s.next(static_cast<uint32_t>(32));
    s.next(static_cast<uint32_t>(32 * o.width));
    s.next(static_cast<uint32_t>(32 * n));
    uint8_t* p = s.advance(static_cast<uint32_t>(32 * n));
    bool dense = true;
    for (size_t i = 0; i < n; ++i, p += 32) {
      // x y z, 4 bytes of padding, rgb packed in a float's bits, 12 more
      std::memset(p, 0, 32);
      std::memcpy(p, &o.points[3 * i], 12);
      const uint32_t rgb = car_ros::packed_rgb(&o.point_rgb[3 * i]);
      std::memcpy(p + 16, &rgb, 4);
      if (!car_ros::has_point(&o.points[3 * i])) dense = false;
    }
    s.next(static_cast<uint8_t>(dense ? 1 : 0));
  }
  static uint32_t serializedLength(const car_ros::CloudView& v) {
    const uint32_t n = static_cast<uint32_t>(v.sample.width) * static_cast<uint32_t>(v.sample.height);
    return car_views::header_length(v) + 4 + 4 + serializationLength(car_ros::cloud_fields()) + 1 + 4 + 4 + 4 + 32 * n + 1;
  }
};

}  // namespace serialization
}  // namespace ros
