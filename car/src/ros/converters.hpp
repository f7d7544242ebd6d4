// The output half of the ROS bridge by sample type: one converter per alternative of car_sim::Sample (the core's
// table of sample types), as ros_gz_bridge has one factory per message pair. Names no plug-in kind.
#pragma once

#include <ros/ros.h>
#include <std_msgs/Header.h>

#include <memory>
#include <string>

#include "context.hpp"
#include "frames.hpp"

namespace car_ros {

// One output port of a plug-in instance, with its publisher.
struct OutPort {
  car_sim::OutputPort port;
  ros::Publisher pub;
  PortFrames frames;  // as published
  // a port with a min_period (range's throttle) or a CameraInfo port's period: when its next message is due
  car_sim::PeriodGate gate;
};

// What a converter's advertise may use besides its port.
struct SetupContext {
  const car_sim::PluginInfo& plugin;
  NodeContext& node;
};

// What a converter's convert may use besides its port and sample.
struct PublishContext {
  // the output the sample is from: the camera types' messages, serialised straight from its arrays on the
  // publishing thread, keep it until they are sent
  const std::shared_ptr<const car_sim::Output>& owner;
  const car_sim::RobotModel& model;
  ros::Time stamp;           // the output's tick
  std_msgs::Header header;   // the stamp and the port's frame
  NodeContext& node;
};

// The converter of sample type S. advertise<S>: the port's publisher (and what else the port keeps), and what it
// offers for the plug-in's log line ("" for nothing). convert<S>: one sample's messages, on the publishing thread.
// Each is defined beside its to_msg, in outputs.cpp (the camera types in outputs_image.cpp); the table in
// outputs.cpp takes every alternative's, so a sample type without its converter does not link.
template <class S>
std::string advertise(OutPort& p, const SetupContext& c);
template <class S>
void convert(OutPort& p, const S& sample, PublishContext& c);

// A message with the port's header, on its publisher.
template <class M>
void send(const OutPort& p, M msg, const PublishContext& c) {
  msg.header = c.header;
  c.node.publish(p.pub, std::move(msg));
}

// ---- cameras (outputs_image.cpp)
template <>
std::string advertise<car_sim::ImageSample>(OutPort& p, const SetupContext& c);
template <>
void convert<car_sim::ImageSample>(OutPort& p, const car_sim::ImageSample& s, PublishContext& c);
template <>
std::string advertise<car_sim::CameraInfoSample>(OutPort& p, const SetupContext& c);
template <>
void convert<car_sim::CameraInfoSample>(OutPort& p, const car_sim::CameraInfoSample& s, PublishContext& c);
template <>
std::string advertise<car_sim::DepthImageSample>(OutPort& p, const SetupContext& c);
template <>
void convert<car_sim::DepthImageSample>(OutPort& p, const car_sim::DepthImageSample& s, PublishContext& c);
template <>
std::string advertise<car_sim::DepthCloudSample>(OutPort& p, const SetupContext& c);
template <>
void convert<car_sim::DepthCloudSample>(OutPort& p, const car_sim::DepthCloudSample& s, PublishContext& c);

}  // namespace car_ros
