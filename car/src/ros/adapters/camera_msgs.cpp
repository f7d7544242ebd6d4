#include "camera_msgs.hpp"

#include <cmath>
#include <cstring>

#include "../adapter.hpp"
#include "../conversions.hpp"

namespace car_ros {

sensor_msgs::Image camera_image(const car_sim::CameraOut& o, const std::string& frame, const ros::Time& stamp) {
  sensor_msgs::Image im;
  im.header.stamp = stamp;
  im.header.frame_id = frame;
  im.height = o.height;
  im.width = o.width;
  im.encoding = o.encoding;
  im.is_bigendian = 0;
  im.step = static_cast<uint32_t>(o.step());
  im.data.assign(o.image.begin(), o.image.end());
  return im;
}

sensor_msgs::CameraInfo camera_info(const car_sim::CameraOut& o, const car_sim::PluginConfig& cfg,
                                    const std::string& frame, const ros::Time& stamp) {
  sensor_msgs::CameraInfo ci;
  ci.header.stamp = stamp;
  ci.header.frame_id = frame;
  ci.width = o.width;
  ci.height = o.height;
  ci.distortion_model = "plumb_bob";
  ci.D = {cfg.number("distortionK1"), cfg.number("distortionK2"), cfg.number("distortionT1"),
          cfg.number("distortionT2"), cfg.number("distortionK3")};
  ci.K = {o.f, 0, o.cx, 0, o.f, o.cy, 0, 0, 1};
  ci.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  ci.P = {o.f, 0, o.cx, -o.f * cfg.number("hackBaseline"), 0, o.f, o.cy, 0, 0, 0, 1, 0};
  return ci;
}

sensor_msgs::Image depth_image(const car_sim::CameraOut& o, bool mm, const std::string& frame, const ros::Time& stamp) {
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
    for (size_t i = 0; i < o.depth.size(); ++i)
      px[i] = std::isfinite(o.depth[i]) ? static_cast<uint16_t>(std::lround(o.depth[i] * 1000.0f)) : 0;
  } else {
    d.encoding = "32FC1";
    d.step = o.width * 4;
    d.data.resize(static_cast<size_t>(d.step) * o.height);
    std::memcpy(d.data.data(), o.depth.data(), d.data.size());
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

sensor_msgs::PointCloud2 point_cloud(const car_sim::CameraOut& o, const std::string& frame, const ros::Time& stamp) {
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
    // rgb packed as 0x00RRGGBB in a float's bits, as PCL and rviz read it
    const uint32_t rgb = (uint32_t(o.point_rgb[3 * i]) << 16) | (uint32_t(o.point_rgb[3 * i + 1]) << 8) |
                         uint32_t(o.point_rgb[3 * i + 2]);
    std::memcpy(p + 16, &rgb, 4);
    if (!std::isfinite(o.points[3 * i + 2])) dense = false;
  }
  pc.is_dense = dense;
  return pc;
}

std::string CameraTopics::advertise(ros::NodeHandle& nh, const car_sim::PluginConfig& c,
                                    const std::string& model_name) {
  cfg_ = c;
  frame_ = frame(c.text("frameName"));
  base_ = car_sim::plugin_robot_namespace(c, model_name);
  const std::string cam = frame(c.text("cameraName"));
  if (!cam.empty()) base_ = base_.empty() ? cam : base_ + "/" + cam;
  image_ = nh.advertise<sensor_msgs::Image>(topic_in(base_, c.text("imageTopicName")), 2);
  info_ = nh.advertise<sensor_msgs::CameraInfo>(topic_in(base_, c.text("cameraInfoTopicName")), 2);
  const double r = c.number("updateRate");
  info_period_ = r > 0 ? 1.0 / r : 0.0;
  return image_.getTopic() + ", " + info_.getTopic();
}

bool CameraTopics::listened() const {
  for (const ros::Publisher* p : {&image_, &info_, &extra_info})
    if (*p && p->getNumSubscribers() > 0) return true;
  return false;
}

void CameraTopics::publish(const std::shared_ptr<const car_sim::CameraOut>& o, const ros::Time& stamp,
                           NodeContext& node) {
  // the frame has no image when nobody took one as it was made (a depth camera's parts)
  if (image_.getNumSubscribers() > 0 && !o->image.empty()) {
    ImageView v;
    v.out = o;
    v.frame = frame_;
    v.stamp = stamp;
    node.publish(image_, std::move(v));
  }
  const bool info_due =
      info_period_ <= 0.0 || (stamp - last_info_).toSec() >= info_period_ - 1e-9 || stamp < last_info_;
  if (!info_due) return;
  sensor_msgs::CameraInfo ci = camera_info(*o, cfg_, frame_, stamp);
  if (extra_info) node.publish(extra_info, ci);
  node.publish(info_, std::move(ci));
  last_info_ = stamp;
}

}  // namespace car_ros
