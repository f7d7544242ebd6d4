// gazebo_plugins' GazeboRos::resolveTF (Noetic tf's tf::resolve), and a port's frames by each FrameRule
// (src/ros/frames.cpp). Expected names worked out from tf::resolve's three cases and each upstream file's rule
// (docs/COMPAT-spawn.md rule 4).
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "frames.hpp"

using car_ros::resolve_tf;

TEST(ResolveTf, NoPrefixKeepsTheNameAsWritten) { EXPECT_EQ(resolve_tf("", "odom"), "odom"); }

TEST(ResolveTf, PrefixGoesInFrontWithASlash) { EXPECT_EQ(resolve_tf("robot1", "base_footprint"), "robot1/base_footprint"); }

TEST(ResolveTf, PrefixLosesItsLeadingSlash) { EXPECT_EQ(resolve_tf("/robot1", "odom"), "robot1/odom"); }

TEST(ResolveTf, AbsoluteNameTakesNoPrefixAndLosesOneSlash) { EXPECT_EQ(resolve_tf("robot1", "/map"), "map"); }

// ---- a port's frames by its FrameRule (frames.cpp), tf_prefix from a table instead of the parameter server ----

namespace {

using car_sim::FrameRule;

// tf_prefix "up" when searched upwards from /r1, "here" when read in /r1 itself; records the lookups.
struct Lookups {
  std::vector<std::pair<std::string, bool>> asked;
  car_ros::TfPrefixLookup fn() {
    return [this](const std::string& ns, bool searched) {
      asked.emplace_back(ns, searched);
      return std::string(searched ? "up" : "here");
    };
  }
};

car_sim::OutputPort port(FrameRule rule, const std::string& frame, const std::string& child) {
  car_sim::OutputPort p;
  p.ns = "r1";
  p.frame = frame;
  p.child_frame = child;
  p.frame_rule = rule;
  return p;
}

}  // namespace

// The drives, the laser, camera_utils: tf_prefix searched upwards, both frames take it.
TEST(PortFrames, PrefixSearchedPrefixesBothFrames) {
  Lookups l;
  const auto f = car_ros::port_frames(port(FrameRule::PrefixSearched, "odom", "base_footprint"), l.fn());
  EXPECT_EQ(f.frame, "up/odom");
  EXPECT_EQ(f.child_frame, "up/base_footprint");
  EXPECT_EQ(l.asked, (std::vector<std::pair<std::string, bool>>{{"r1", true}}));
}

// p3d, f3d, ft_sensor, range, bumper, block_laser: tf_prefix of the namespace itself, the header frame only.
TEST(PortFrames, PrefixHerePrefixesTheHeaderFrameOnly) {
  Lookups l;
  const auto f = car_ros::port_frames(port(FrameRule::PrefixHere, "world", "base_footprint"), l.fn());
  EXPECT_EQ(f.frame, "here/world");
  EXPECT_EQ(f.child_frame, "base_footprint");
  EXPECT_EQ(l.asked, (std::vector<std::pair<std::string, bool>>{{"r1", false}}));
}

// The IMUs, hector's sensors, velodyne, hand_of_god: no tf_prefix looked up; every leading '/' dropped.
TEST(PortFrames, NoPrefixDropsTheLeadingSlashes) {
  Lookups l;
  const auto f = car_ros::port_frames(port(FrameRule::NoPrefix, "//imu_link", "/child"), l.fn());
  EXPECT_EQ(f.frame, "imu_link");
  EXPECT_EQ(f.child_frame, "/child");
  EXPECT_TRUE(l.asked.empty());
}

// ros_controllers: both frames exactly as configured, a leading '/' kept.
TEST(PortFrames, AsWrittenKeepsBothFrames) {
  Lookups l;
  const auto f = car_ros::port_frames(port(FrameRule::AsWritten, "/odom", "/base_link"), l.fn());
  EXPECT_EQ(f.frame, "/odom");
  EXPECT_EQ(f.child_frame, "/base_link");
  EXPECT_TRUE(l.asked.empty());
}

// The wheel TF's links take the port's prefix as its header frame does.
TEST(PortFrames, WheelLinksTakeThePortsPrefix) {
  Lookups l;
  const auto f = car_ros::port_frames(port(FrameRule::PrefixSearched, "", ""), l.fn());
  EXPECT_EQ(f.header_frame("left_wheel"), "up/left_wheel");
  EXPECT_EQ(f.header_frame("/chassis"), "chassis");
}
