// The cameras' messages serialised straight from the core's arrays (src/ros/image_msgs.hpp) give the
// same bytes on the wire as the sensor_msgs messages camera_image(), depth_image() and point_cloud() build.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "camera/camera.hpp"
#include "image_msgs.hpp"

namespace {

using ros::serialization::serializeMessage;

// A 4 x 3 frame: depth 1.5 m + 0.25 m per pixel index, pixel 5 without a hit (NaN), colour (10 i, 20, 30).
std::shared_ptr<car_sim::CameraOut> frame(const std::string& encoding) {
  auto o = std::make_shared<car_sim::CameraOut>();
  o->tick = 1234;
  o->width = 4;
  o->height = 3;
  o->f = 2.0;
  o->cx = 1.5;
  o->cy = 1.0;
  o->encoding = encoding;
  const size_t n = 12, ch = encoding == "mono8" ? 1 : 3;
  o->has_depth = true;
  for (size_t i = 0; i < n; ++i) {
    const float d = i == 5 ? std::numeric_limits<float>::quiet_NaN() : 1.5f + 0.25f * static_cast<float>(i);
    o->depth.push_back(d);
    o->points.insert(o->points.end(), {0.1f * static_cast<float>(i), -0.2f, d});
    o->point_rgb.insert(o->point_rgb.end(), {static_cast<uint8_t>(10 * i), 20, 30});
    for (size_t c = 0; c < ch; ++c) o->image.push_back(static_cast<uint8_t>(7 * i + c));
  }
  return o;
}

std::vector<uint8_t> bytes(const ros::SerializedMessage& m) { return {m.buf.get(), m.buf.get() + m.num_bytes}; }

template <class View>
View view(const std::shared_ptr<car_sim::CameraOut>& o) {
  View v;
  v.owner = o;
  v.sample = o->frame_view();
  v.frame = "support_depth";
  v.stamp = ros::Time(1, 234000000);
  return v;
}

TEST(CameraMsgs, ImageViewIsTheImageMessage) {
  for (const char* enc : {"rgb8", "bgr8", "mono8"}) {
    auto o = frame(enc);
    const auto v = view<car_ros::ImageView>(o);
    EXPECT_EQ(bytes(serializeMessage(v)), bytes(serializeMessage(car_ros::camera_image(v.sample, v.frame, v.stamp)))) << enc;
  }
}

TEST(CameraMsgs, DepthViewIsTheDepthImageInMetres) {
  auto o = frame("rgb8");
  const auto v = view<car_ros::DepthView>(o);
  EXPECT_EQ(bytes(serializeMessage(v)), bytes(serializeMessage(car_ros::depth_image(v.sample, false, v.frame, v.stamp))));
}

TEST(CameraMsgs, DepthViewIsTheDepthImageInMillimetres) {
  auto o = frame("rgb8");
  auto v = view<car_ros::DepthView>(o);
  v.millimetres = true;
  const std::vector<uint8_t> b = bytes(serializeMessage(v));
  EXPECT_EQ(b, bytes(serializeMessage(car_ros::depth_image(v.sample, true, v.frame, v.stamp))));
  // the last pixel, 1.5 + 0.25 * 11 = 4.25 m, is 4250 mm in the last two bytes (little-endian)
  EXPECT_EQ(b[b.size() - 2] | (b[b.size() - 1] << 8), 4250);
}

TEST(CameraMsgs, CloudViewIsThePointCloud) {
  auto o = frame("rgb8");
  const auto v = view<car_ros::CloudView>(o);
  const std::vector<uint8_t> b = bytes(serializeMessage(v));
  EXPECT_EQ(b, bytes(serializeMessage(car_ros::point_cloud(v.sample, v.frame, v.stamp))));
  // not dense: pixel 5 has no hit (is_dense is the last byte)
  EXPECT_EQ(b.back(), 0);
  // the last point's rgb: (110, 20, 30) as 0x006E141E, 16 bytes into its 32, which end 1 byte before the end
  uint32_t rgb = 0;
  std::memcpy(&rgb, b.data() + b.size() - 1 - 32 + 16, 4);
  EXPECT_EQ(rgb, 0x006E141Eu);
}

TEST(CameraMsgs, DenseCloudWhenEveryPixelHits) {
  auto o = frame("rgb8");
  o->points[3 * 5 + 2] = 2.0f;
  const auto v = view<car_ros::CloudView>(o);
  const std::vector<uint8_t> b = bytes(serializeMessage(v));
  EXPECT_EQ(b, bytes(serializeMessage(car_ros::point_cloud(v.sample, v.frame, v.stamp))));
  EXPECT_EQ(b.back(), 1);
}

// The views carry their sensor_msgs type's name and MD5 sum (roscpp refuses a publish whose sum differs).
TEST(CameraMsgs, ViewsHaveTheirMessagesTypes) {
  namespace mt = ros::message_traits;
  EXPECT_STREQ(mt::datatype<car_ros::CloudView>(), "sensor_msgs/PointCloud2");
  EXPECT_STREQ(mt::md5sum<car_ros::CloudView>(), mt::md5sum<sensor_msgs::PointCloud2>());
  EXPECT_STREQ(mt::datatype<car_ros::DepthView>(), "sensor_msgs/Image");
  EXPECT_STREQ(mt::md5sum<car_ros::ImageView>(), mt::md5sum<sensor_msgs::Image>());
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}

namespace {

// camera_info of the 4 x 3 frame (its own f = 2, cx = 1.5, cy = 1) through `port`, hackBaseline 0.1 m.
sensor_msgs::CameraInfo info_through(car_sim::ImagePortSettings port) {
  auto o = frame("rgb8");
  const car_sim::ImageSample s = o->frame_view();
  port.baseline = 0.1;
  return car_ros::camera_info(s, port, "cam", ros::Time(1, 0));
}

}  // namespace

// K and P with no <focalLength>, <Cx>, <Cy> (0): the frame's own values; P[3] = -f * hackBaseline.
TEST(CameraInfo, ZeroIntrinsicsAreTheRenderedOnes) {
  const auto ci = info_through({});
  const boost::array<double, 9> K = {2, 0, 1.5, 0, 2, 1, 0, 0, 1};
  const boost::array<double, 12> P = {2, 0, 1.5, -0.2, 0, 2, 1, 0, 0, 0, 1, 0};
  EXPECT_EQ(ci.K, K);
  EXPECT_EQ(ci.P, P);
}

// camera_utils puts a non-zero <focalLength> 3, <Cx> 2.5, <Cy> 0.75 into K and P as written (P[3] = -3 * 0.1).
TEST(CameraInfo, NonZeroIntrinsicsReplaceTheRenderedOnes) {
  car_sim::ImagePortSettings port;
  port.focal_length = 3;
  port.cx = 2.5;
  port.cy = 0.75;
  const auto ci = info_through(port);
  const boost::array<double, 9> K = {3, 0, 2.5, 0, 3, 0.75, 0, 0, 1};
  const boost::array<double, 12> P = {3, 0, 2.5, -3 * 0.1, 0, 3, 0.75, 0, 0, 0, 1, 0};
  EXPECT_EQ(ci.K, K);
  EXPECT_EQ(ci.P, P);
}
