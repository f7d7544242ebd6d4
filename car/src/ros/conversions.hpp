// Every conversion between the core's types and ROS messages, in one place.
#pragma once

#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Transform.h>
#include <geometry_msgs/Twist.h>
#include <ros/time.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <string>

namespace car_ros {

inline ros::Time sim_time(uint64_t tick, double dt) {
  // integer nanoseconds from the tick, so stamps do not accumulate rounding
  const uint64_t ns = static_cast<uint64_t>(std::llround(dt * 1e9)) * tick;
  ros::Time t;
  t.fromNSec(ns);
  return t;
}

inline geometry_msgs::Pose to_pose(const Eigen::Isometry3d& T) {
  geometry_msgs::Pose p;
  p.position.x = T.translation().x();
  p.position.y = T.translation().y();
  p.position.z = T.translation().z();
  const Eigen::Quaterniond q(T.linear());
  p.orientation.x = q.x();
  p.orientation.y = q.y();
  p.orientation.z = q.z();
  p.orientation.w = q.w();
  return p;
}

inline geometry_msgs::Transform to_transform(const Eigen::Isometry3d& T) {
  const geometry_msgs::Pose p = to_pose(T);
  geometry_msgs::Transform t;
  t.translation.x = p.position.x;
  t.translation.y = p.position.y;
  t.translation.z = p.position.z;
  t.rotation = p.orientation;
  return t;
}

inline Eigen::Isometry3d from_pose(const geometry_msgs::Pose& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  Eigen::Quaterniond q(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z);
  // an all-zero quaternion (an unset message field) means no rotation
  if (q.norm() < 1e-12) q = Eigen::Quaterniond::Identity();
  T.linear() = q.normalized().toRotationMatrix();
  return T;
}

inline geometry_msgs::Twist to_twist(const Eigen::Vector3d& linear, const Eigen::Vector3d& angular) {
  geometry_msgs::Twist t;
  t.linear.x = linear.x();
  t.linear.y = linear.y();
  t.linear.z = linear.z();
  t.angular.x = angular.x();
  t.angular.y = angular.y();
  t.angular.z = angular.z();
  return t;
}

}  // namespace car_ros
