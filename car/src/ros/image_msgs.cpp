// The camera sample types' messages built as sensor_msgs structs (the views' reference, and camera_info).
#include "image_msgs.hpp"

#include <cmath>
#include <cstring>

namespace car_ros {

sensor_msgs::Image camera_image(const car_sim::ImageSample& o, const std::string& frame, const ros::Time& stamp) {
  sensor_msgs::Image im;
  im.header.stamp = stamp;
  im.header.frame_id = frame;
  im.height = o.height;
  im.width = o.width;
  im.encoding = o.encoding;
  im.is_bigendian = 0;
  im.step = o.step;
  im.data.assign(o.image, o.image + o.image_bytes);
  return im;
}

sensor_msgs::CameraInfo camera_info(const car_sim::ImageSample& o, const car_sim::ImagePortSettings& port,
                                    const std::string& frame, const ros::Time& stamp) {
  sensor_msgs::CameraInfo ci;
  ci.header.stamp = stamp;
  ci.header.frame_id = frame;
  ci.width = o.width;
  ci.height = o.height;
  ci.distortion_model = "plumb_bob";
  ci.D.assign(port.distortion.begin(), port.distortion.end());
  // [px]: the plug-in's non-zero <focalLength>, <Cx>, <Cy>, else the values the image was rendered with
  const double f = port.focal_length != 0 ? port.focal_length : o.f;
  const double cx = port.cx != 0 ? port.cx : o.cx;
  const double cy = port.cy != 0 ? port.cy : o.cy;
  ci.K = {f, 0, cx, 0, f, cy, 0, 0, 1};
  ci.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  ci.P = {f, 0, cx, -f * port.baseline, 0, f, cy, 0, 0, 0, 1, 0};
  return ci;
}

sensor_msgs::Image depth_image(const car_sim::ImageSample& o, bool mm, const std::string& frame, const ros::Time& stamp) {
  sensor_msgs::Image d;
  d.header.stamp = stamp;
  d.header.frame_id = frame;
  d.height = o.height;
  d.width = o.width;
  d.is_bigendian = 0;
  if (mm) {
    d.encoding = "16UC1";
    d.step = o.width * 2;
    d.data.resize(static_cast<size_t>(d.step) * o.height);
    auto* px = reinterpret_cast<uint16_t*>(d.data.data());
    for (size_t i = 0; i < static_cast<size_t>(o.width) * o.height; ++i) px[i] = depth_mm(o.depth[i]);
  } else {
    d.encoding = "32FC1";
    d.step = o.width * 4;
    d.data.resize(static_cast<size_t>(d.step) * o.height);
    std::memcpy(d.data.data(), o.depth, d.data.size());
  }
  return d;
}

const std::vector<sensor_msgs::PointField>& cloud_fields() {
  static const std::vector<sensor_msgs::PointField> fields = [] {
    std::vector<sensor_msgs::PointField> v;
    const char* names[4] = {"x", "y", "z", "rgb"};
    const uint32_t offsets[4] = {0, 4, 8, 16};
    for (int k = 0; k < 4; ++k) {
      sensor_msgs::PointField f;
      f.name = names[k];
      f.offset = offsets[k];
      f.datatype = sensor_msgs::PointField::FLOAT32;
      f.count = 1;
      v.push_back(f);
    }
    return v;
  }();
  return fields;
}

sensor_msgs::PointCloud2 point_cloud(const car_sim::ImageSample& o, const std::string& frame, const ros::Time& stamp) {
  sensor_msgs::PointCloud2 pc;
  pc.header.stamp = stamp;
  pc.header.frame_id = frame;
  pc.height = o.height;
  pc.width = o.width;
  pc.fields = cloud_fields();
  pc.is_bigendian = false;
  pc.point_step = 32;
  pc.row_step = 32 * o.width;
  const size_t n = static_cast<size_t>(o.width) * o.height;
  pc.data.assign(32 * n, 0);
  bool dense = true;
  for (size_t i = 0; i < n; ++i) {
    uint8_t* p = pc.data.data() + 32 * i;
    std::memcpy(p, &o.points[3 * i], 12);
    const uint32_t rgb = packed_rgb(&o.point_rgb[3 * i]);
    std::memcpy(p + 16, &rgb, 4);
    if (!has_point(&o.points[3 * i])) dense = false;
  }
  pc.is_dense = dense;
  return pc;
}

}  // namespace car_ros
