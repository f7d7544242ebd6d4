// car's simulator node: the ROS skin over car_sim::World. It paces the world against the wall clock (rtf),
// publishes /clock, runs Gazebo-style services under /gazebo (services.cpp), subscribes every input port
// (inputs.cpp), feeds every plug-in instance's outputs to its output ports (outputs.cpp) and serves its calls
// (calls.cpp). All maths lives in the core.
#pragma once

#include <gazebo_msgs/DeleteModel.h>
#include <gazebo_msgs/GetModelState.h>
#include <gazebo_msgs/GetWorldProperties.h>
#include <gazebo_msgs/ModelStates.h>
#include <gazebo_msgs/SetModelState.h>
#include <gazebo_msgs/SpawnModel.h>
// gazebo_ros API services (services.cpp)
#include <gazebo_msgs/ApplyBodyWrench.h>
#include <gazebo_msgs/ApplyJointEffort.h>
#include <gazebo_msgs/BodyRequest.h>
#include <gazebo_msgs/GetJointProperties.h>
#include <gazebo_msgs/GetLinkProperties.h>
#include <gazebo_msgs/GetLinkState.h>
#include <gazebo_msgs/GetModelProperties.h>
#include <gazebo_msgs/GetPhysicsProperties.h>
#include <gazebo_msgs/JointRequest.h>
#include <gazebo_msgs/LinkStates.h>
#include <gazebo_msgs/SetLinkState.h>
#include <gazebo_msgs/SetModelConfiguration.h>
#include <gazebo_msgs/SetPhysicsProperties.h>
#include <ros/ros.h>
#include <std_srvs/Empty.h>
#include <tf2_ros/transform_broadcaster.h>

#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "calls.hpp"
#include "context.hpp"
#include "inputs.hpp"
#include "outputs.hpp"
#include "lockstep.hpp"
#include "pacer.hpp"
#include "poll_gate.hpp"
#include "publish_queue.hpp"
#include "car_sim/world.hpp"

namespace car_ros {

// model_paths.cpp: (package, folder) of every <export><gazebo_ros gazebo_model_path="..."/> on ROS_PACKAGE_PATH,
// and GAZEBO_MODEL_PATH extended by them (as gazebo_ros's paths plug-in).
std::vector<std::pair<std::string, std::string>> exported_model_paths();
void add_exported_model_paths();
// dropin.cpp: a world name as gzserver resolves it: a path as given, else under each GAZEBO_RESOURCE_PATH entry,
// else "worlds/empty.world" = "" (car's built-in empty world); throws car_sim::LoadError naming what was searched.
std::string resolve_world_name(const std::string& name);
// node.cpp: ros::start() without roscpp's own /clock subscriber, then roscpp's time at sim time 0. The node sets
// roscpp's time itself, to the step's sim time (ros::Time::setNow; docs/COMPAT-plugins.md "ROS time in car's node").
void start_with_sim_time();

class SimNode : public NodeContext {
 public:
  SimNode();
  bool init();
  void run();

  // NodeContext
  ros::NodeHandle& nh() override { return nh_; }
  car_sim::World& world() override { return *world_; }
  // /tf is advertised on the first transform a plug-in sends, as Gazebo's plug-ins do (docs/COMPAT-dropins.md)
  tf2_ros::TransformBroadcaster& tf() override {
    if (!tf_) tf_ = std::make_unique<tf2_ros::TransformBroadcaster>();
    return *tf_;
  }
  ros::Time stamp(uint64_t tick) const override;
  void flush_published() override { publisher_.flush(); }

 protected:
  void post(std::function<void()> job, size_t bytes) override { publisher_.post(std::move(job), bytes); }
  void published(const std::string& topic, uint32_t subscribers) override { lockstep_.published(topic, subscribers); }
  void listeners_changed() override { update_activity(); }

 private:
  // The bridge of one plug-in instance of a robot: its input, output and service ports.
  struct PluginIO {
    car_sim::PluginInfo info;
    std::unique_ptr<InputPorts> inputs;
    std::unique_ptr<OutputPorts> outputs;
    std::unique_ptr<ServicePorts> services;
    bool active = false;
    uint32_t parts = ~0u;  // the output parts last handed to the plug-in (Plugin::set_parts)
  };
  struct RobotIO {
    ros::Publisher joint_states;  // every non-fixed joint, in the spawn namespace
    std::vector<PluginIO> plugins;
  };

  void log_world(const std::string& file);
  // Gazebo plug-ins of the world: the world's <plugin>s' messages from `from` on, gzserver's -s plug-ins, the work
  // they deferred (inserted models: true when robots came), the topics of robots a plug-in inserted.
  void log_world_plugins(size_t from);
  void load_system_plugins();
  bool run_deferred();
  void take_new_robots();
  void publish_clock();
  void publish_outputs();
  // Switches the lazy plug-ins on or off, and hands each the output parts someone takes: at a robot's spawn, when a
  // plug-in's ports change and when a port's subscribers change (roscpp's connect callbacks).
  void update_activity();
  // The bridge for a spawned robot's plug-ins, plus the ground-truth publisher the node attaches.
  void make_io(const std::string& robot);
  // A plug-in instance's ports changed (a controller loaded or unloaded): its bridge reads them again.
  void ports_changed(const std::string& robot, const std::string& plugin);
  uint64_t period_of(double rate) const;
  // The steps between two /clock, joint_states and model_states messages (from the rates, once the world's step
  // is known: init()), so a step only compares its tick with them.
  void set_periods();

  // services.cpp
  void advertise_services();
  bool spawn(gazebo_msgs::SpawnModel::Request& req, gazebo_msgs::SpawnModel::Response& res);
  bool remove(gazebo_msgs::DeleteModel::Request& req, gazebo_msgs::DeleteModel::Response& res);
  bool get_state(gazebo_msgs::GetModelState::Request& req, gazebo_msgs::GetModelState::Response& res);
  bool set_state(gazebo_msgs::SetModelState::Request& req, gazebo_msgs::SetModelState::Response& res);
  bool properties(gazebo_msgs::GetWorldProperties::Request&, gazebo_msgs::GetWorldProperties::Response& res);
  bool reset_simulation(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool reset_world(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool pause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool unpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  // gazebo_ros API (docs/COMPAT.md)
  bool get_link_state(gazebo_msgs::GetLinkState::Request& req, gazebo_msgs::GetLinkState::Response& res);
  bool set_link_state(gazebo_msgs::SetLinkState::Request& req, gazebo_msgs::SetLinkState::Response& res);
  bool link_properties(gazebo_msgs::GetLinkProperties::Request& req, gazebo_msgs::GetLinkProperties::Response& res);
  bool model_properties(gazebo_msgs::GetModelProperties::Request& req, gazebo_msgs::GetModelProperties::Response& res);
  bool joint_properties(gazebo_msgs::GetJointProperties::Request& req, gazebo_msgs::GetJointProperties::Response& res);
  bool set_configuration(gazebo_msgs::SetModelConfiguration::Request& req,
                         gazebo_msgs::SetModelConfiguration::Response& res);
  bool apply_wrench(gazebo_msgs::ApplyBodyWrench::Request& req, gazebo_msgs::ApplyBodyWrench::Response& res);
  bool apply_effort(gazebo_msgs::ApplyJointEffort::Request& req, gazebo_msgs::ApplyJointEffort::Response& res);
  bool clear_wrenches(gazebo_msgs::BodyRequest::Request& req, gazebo_msgs::BodyRequest::Response&);
  bool clear_efforts(gazebo_msgs::JointRequest::Request& req, gazebo_msgs::JointRequest::Response&);
  bool get_physics(gazebo_msgs::GetPhysicsProperties::Request&, gazebo_msgs::GetPhysicsProperties::Response& res);
  bool set_physics(gazebo_msgs::SetPhysicsProperties::Request& req, gazebo_msgs::SetPhysicsProperties::Response& res);
  // A named entity's world-frame state: "" / world / map / "/map" -> nullopt with *world = true; a model,
  // "MODEL::LINK" or a plain link name -> its state; none -> nullopt with *world = false.
  std::optional<car_sim::ModelState> entity_state(const std::string& name, bool* world) const;
  void publish_link_states();
  // dropin.cpp: the rest of gazebo_ros's API surface (docs/COMPAT-dropins.md)
  void advertise_dropin();
  void publish_performance();
  // roscpp's time (ros::Time::now() in every thread of the process) to a tick's sim time, when it is not already
  void set_ros_time(uint64_t tick);
  // every input port read from TF looks its transform up now (before a step)
  void poll_tf_inputs();

  ros::NodeHandle nh_, pnh_, gz_;
  std::unique_ptr<car_sim::World> world_;
  double rtf_ = 1.0, clock_rate_ = 100.0, joint_state_rate_ = 50.0, model_states_rate_ = 100.0;
  int solver_iterations_ = 10;
  uint64_t clock_period_ = 10, joint_state_period_ = 20, model_states_period_ = 10;  // [steps]
  size_t known_robots_ = 0;  // robots with topics (make_io); more after a plug-in inserted a model
  ros::Publisher clock_pub_, model_states_pub_, link_states_pub_;
  ros::Subscriber set_model_state_sub_, set_link_state_sub_;  // the /gazebo/set_*_state topics
  // the pacing restarts from now: at the start, after a pause, a reset (time back to 0) or a new real-time factor
  bool repace_ = true;
  // rtf > 0: the steps' wall-time schedule; a lag over 10 ms is dropped, not made up
  Pacer pacer_{std::chrono::milliseconds(10)};
  std::vector<ros::ServiceServer> services_;
  std::map<std::string, RobotIO> io_;
  // robot -> plug-in -> its output ports and its inputs read from TF (nullptr: none), for routing outputs (looked
  // up by the output's own strings: no copy per output)
  struct Route {
    OutputPorts* outputs = nullptr;
    InputPorts* polled = nullptr;
  };
  std::map<std::string, std::map<std::string, Route>> route_;
  std::unique_ptr<tf2_ros::TransformBroadcaster> tf_;
  // docs/COMPAT-dropins.md: car-only topics per robot (joint_states, /gazebo/ground_truth/<model>); stop after
  // ~iters steps (gzserver --iters, 0 = never); dynamic_reconfigure server (type-erased) and performance metrics
  bool car_extras_ = true;
  // ~lockstep: steps wait for the node under test's answer to a trigger topic (docs/COMPAT-dropins.md)
  Lockstep lockstep_;
  bool lockstep_waited_ = false;  // the loop waited for an answer since the last step
  int64_t iters_ = 0;
  uint64_t pause_at_tick_ = 0;  // ~pause_at: the step after which the run pauses itself (0 = none)
  std::shared_ptr<void> reconfigure_;
  bool reconfigure_ready_ = false;
  ros::Publisher performance_pub_;
  std::chrono::steady_clock::time_point perf_wall_ = std::chrono::steady_clock::now();
  uint64_t perf_tick_ = 0;
  uint64_t ros_time_tick_ = 0;  // the tick whose sim time roscpp's time is (start_with_sim_time: 0)
  // What waits in roscpp's publish queues: at most 32 MB (three Kinect clouds) before the publishing thread waits
  // for roscpp's poll thread (poll_gate.hpp), told by publisher_ after each job. Destroyed after publisher_, whose
  // last jobs pass through it.
  PollGate roscpp_{32u << 20};
  // Last member: destroyed first, so it sends what is queued while every publisher above still exists.
  // Bound: 64 MB or 4096 messages waiting (6 Kinect clouds of 10 MB).
  PublishQueue publisher_{64u << 20, 4096, [this](size_t bytes) { roscpp_.published(bytes); }};
};

}  // namespace car_ros
