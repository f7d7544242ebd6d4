// sim_node: car's simulator as a ROS node, named gazebo by default so its services live under /gazebo.
#include <malloc.h>

#include <cstdio>

#include "master_watch.hpp"
#include "node.hpp"

int main(int argc, char** argv) {
  // Camera frames are several MB each: keep freed blocks in the heap instead of returning them to the kernel,
  // so the next frame does not pay page faults (glibc otherwise mmaps blocks over 128 kB).
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
  // line by line, to a log file too: users' Gazebo plug-ins print with printf and std::cout (the hello world
  // tutorial), and a node stopped by roslaunch would lose a full buffer
  setvbuf(stdout, nullptr, _IOLBF, 0);
  ros::init(argc, argv, "gazebo");
  // before any NodeHandle: roscpp's time is the node's sim time, set by the node (docs/COMPAT-plugins.md)
  car_ros::start_with_sim_time();
  car_ros::SimNode node;
  if (!node.init()) return 1;
  // a restarted roscore gets this node's topics and services again, and the node's own /use_sim_time
  car_ros::MasterWatch watch([] { ros::param::set("/use_sim_time", true); });
  node.run();
  return 0;
}
