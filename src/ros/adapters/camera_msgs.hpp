// Messages of the camera kinds (camera, openni_kinect): image, camera_info, depth image, organized cloud.
#pragma once

#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>

#include <string>

#include "../adapter.hpp"
#include "camera/camera.hpp"

namespace car_ros {

// The colour image, in the frame's encoding.
sensor_msgs::Image camera_image(const car_sim::CameraOut& o, const std::string& frame, const ros::Time& stamp);
// plumb_bob: D from distortionK1..K3/T1..T2, K = [f 0 cx; 0 f cy; 0 0 1], P with -f * hackBaseline.
sensor_msgs::CameraInfo camera_info(const car_sim::CameraOut& o, const car_sim::PluginConfig& cfg,
                                    const std::string& frame, const ros::Time& stamp);
// 32FC1 metres, or 16UC1 millimetres (0 where there is no depth).
sensor_msgs::Image depth_image(const car_sim::CameraOut& o, bool millimetres, const std::string& frame,
                               const ros::Time& stamp);
// Organized H x W cloud: x@0 y@4 z@8 rgb@16 (FLOAT32), point_step 32, optical frame.
sensor_msgs::PointCloud2 point_cloud(const car_sim::CameraOut& o, const std::string& frame, const ros::Time& stamp);

// The publishers of one camera: image and camera_info under <robotNamespace>/<cameraName>/, camera_info
// throttled to the plug-in's updateRate (0 = with every image).
class CameraTopics {
 public:
  // Returns the topics, for the log line.
  std::string advertise(ros::NodeHandle& nh, const car_sim::PluginConfig& c, const std::string& model_name);
  bool listened() const;
  // Image (when subscribed) and camera_info (when due) of a frame; returns the frame's stamp.
  void publish(const car_sim::CameraOut& o, const ros::Time& stamp, NodeContext& node);
  const std::string& base() const { return base_; }
  const std::string& frame_id() const { return frame_; }
  ros::Publisher extra_info;  // a second camera_info topic published with the first (the Kinect's depth info)

 private:
  car_sim::PluginConfig cfg_;
  std::string base_, frame_;
  ros::Publisher image_, info_;
  double info_period_ = 0.0;  // [s]
  ros::Time last_info_;
};

}  // namespace car_ros
