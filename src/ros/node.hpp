// car's simulator node: the ROS skin over car_sim::World. It paces the world against the wall clock (rtf),
// publishes /clock, runs Gazebo-style services under /gazebo (services.cpp), and feeds every plug-in instance's
// outputs to its kind's adapter (adapters/). All maths lives in the core.
#pragma once

#include <car/DeleteModel.h>
#include <car/GetModelState.h>
#include <car/GetWorldProperties.h>
#include <car/ModelStates.h>
#include <car/SetModelState.h>
#include <car/SpawnModel.h>
#include <ros/ros.h>
#include <std_srvs/Empty.h>
#include <tf2_ros/transform_broadcaster.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "adapter.hpp"
#include "car_sim/world.hpp"

namespace car_ros {

class SimNode : public NodeContext {
 public:
  SimNode();
  bool init();
  void run();

  // NodeContext
  ros::NodeHandle& nh() override { return nh_; }
  car_sim::World& world() override { return *world_; }
  tf2_ros::TransformBroadcaster& tf() override { return tf_; }
  ros::Time stamp(uint64_t tick) const override;

 private:
  // One adapter per plug-in instance of a robot.
  struct PluginIO {
    car_sim::PluginInfo info;
    std::unique_ptr<Adapter> adapter;
    bool active = false;
  };
  struct RobotIO {
    ros::Publisher joint_states;  // every non-fixed joint, in the spawn namespace
    std::vector<PluginIO> plugins;
  };

  void log_world(const std::string& file);
  void publish_clock();
  void publish_outputs();
  void update_activity();
  // Adapters for a spawned robot's plug-ins, plus the ground-truth publisher the node attaches.
  void make_io(const std::string& robot);
  uint64_t period_of(double rate) const;

  // services.cpp
  void advertise_services();
  bool spawn(car::SpawnModel::Request& req, car::SpawnModel::Response& res);
  bool remove(car::DeleteModel::Request& req, car::DeleteModel::Response& res);
  bool get_state(car::GetModelState::Request& req, car::GetModelState::Response& res);
  bool set_state(car::SetModelState::Request& req, car::SetModelState::Response& res);
  bool properties(car::GetWorldProperties::Request&, car::GetWorldProperties::Response& res);
  bool reset_simulation(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool reset_world(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool pause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool unpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);

  ros::NodeHandle nh_, pnh_, gz_;
  std::unique_ptr<car_sim::World> world_;
  double rtf_ = 1.0, clock_rate_ = 100.0, joint_state_rate_ = 50.0, model_states_rate_ = 100.0;
  int solver_iterations_ = 10;
  bool paused_ = false;
  ros::Publisher clock_pub_, model_states_pub_;
  std::vector<ros::ServiceServer> services_;
  std::map<std::string, RobotIO> io_;
  // (robot, plug-in) -> its adapter, for routing outputs
  std::map<std::pair<std::string, std::string>, Adapter*> route_;
  tf2_ros::TransformBroadcaster tf_;
};

}  // namespace car_ros
