// car's Gazebo 11 API (docs/PLUGINS.md): the world's update events, in Gazebo's order within a step:
// WorldUpdateBegin (sim time already counts the coming step), the models' joint controllers, BeforePhysicsUpdate
// (only while physics is enabled), the physics step, WorldUpdateEnd; and pause, stop and time reset. A callback
// connected during a plug-in's Load, Init, Reset or an event belongs to that plug-in's world. Events car does not
// raise (render, sensors, world created, world reset, ...) are not declared: code that connects to them does not
// build.
#pragma once

#include <functional>

#include "gazebo/common/Event.hh"
#include "gazebo/common/UpdateInfo.hh"

namespace gazebo {
namespace event {

class Events {
 public:
  static ConnectionPtr ConnectWorldUpdateBegin(std::function<void(const common::UpdateInfo&)> _subscriber);
  static ConnectionPtr ConnectBeforePhysicsUpdate(std::function<void(const common::UpdateInfo&)> _subscriber);
  static ConnectionPtr ConnectWorldUpdateEnd(std::function<void()> _subscriber);
  // The world's pause flag changed (World::SetPaused, /gazebo/pause_physics and unpause_physics), with its new value.
  static ConnectionPtr ConnectPause(std::function<void(bool)> _subscriber);
  // The world stops: once, when car's world ends (the node shuts down), before any plug-in is deleted.
  static ConnectionPtr ConnectStop(std::function<void()> _subscriber);
  // Sim time went back to 0 (Gazebo's timeReset, raised by World::ResetTime only): once per World::ResetTime and
  // per reset_simulation (World::Reset, before any plug-in's Reset), never for reset_world; SimTime() reads 0.
  static ConnectionPtr ConnectTimeReset(std::function<void()> _subscriber);
};

}  // namespace event
}  // namespace gazebo
