// The ROS rows' consumer: a C++ node that subscribes to /odom and, with --cloud, to /scan and the Kinect's cloud
// (TCP_NODELAY asked for, as a C++ consumer such as rviz would), receives and deserialises every message, and on
// SIGINT/SIGTERM prints how many of each it got. A rospy subscriber spent about as much CPU taking the 10 MB
// clouds apart as the simulator spent making them, on the same two cores. With --cmd V W it also sends one latched
// /cmd_vel (V [m/s] forward, W [rad/s] about z), so the node steps the same motion as the core's row.
// usage: bench_listen [--cmd V W] [--cloud]   (ROS_MASTER_URI as usual)
#include <geometry_msgs/Twist.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud2.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace {
std::atomic<long> odom{0}, scans{0}, clouds{0};
std::atomic<long> cloud_bytes{0};
}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "bench_listen", ros::init_options::AnonymousName);
  bool cloud = false, cmd = false;
  geometry_msgs::Twist twist;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--cloud") == 0) {
      cloud = true;
    } else if (std::strcmp(argv[i], "--cmd") == 0 && i + 2 < argc) {
      cmd = true;
      twist.linear.x = std::atof(argv[++i]);
      twist.angular.z = std::atof(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: bench_listen [--cmd V W] [--cloud]\n");
      return 2;
    }
  }
  ros::NodeHandle nh;
  ros::Publisher cmd_vel;
  if (cmd) {
    cmd_vel = nh.advertise<geometry_msgs::Twist>("/cmd_vel", 1, true);
    cmd_vel.publish(twist);
  }
  const ros::TransportHints fast = ros::TransportHints().tcpNoDelay();
  std::vector<ros::Subscriber> subs;
  subs.push_back(nh.subscribe<nav_msgs::Odometry>("/odom", 1, [](const nav_msgs::Odometry::ConstPtr&) { ++odom; },
                                                  ros::VoidConstPtr(), fast));
  if (cloud) {
    subs.push_back(nh.subscribe<sensor_msgs::LaserScan>("/scan", 1, [](const sensor_msgs::LaserScan::ConstPtr&) { ++scans; },
                                                        ros::VoidConstPtr(), fast));
    subs.push_back(nh.subscribe<sensor_msgs::PointCloud2>(
        "/camera/depth/points", 1,
        [](const sensor_msgs::PointCloud2::ConstPtr& m) {
          ++clouds;
          cloud_bytes += static_cast<long>(m->data.size());
        },
        ros::VoidConstPtr(), fast));
  }
  ros::spin();  // until SIGINT/SIGTERM (roscpp's handler shuts down)
  std::printf("odom %ld scans %ld clouds %ld cloud_bytes %ld\n", odom.load(), scans.load(), clouds.load(),
              cloud_bytes.load());
  return 0;
}
