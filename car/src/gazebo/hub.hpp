// car_gazebo's per-world state (private): the physics::World handle, the event lists and the two step hooks on
// car's world that raise Gazebo's update events in Gazebo's order.
#pragma once

#include <cstdint>
#include <boost/shared_ptr.hpp>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "car_sim/world.hpp"
#include "gazebo/common/Event.hh"
#include "gazebo/common/UpdateInfo.hh"
#include "gazebo/physics/PhysicsTypes.hh"
#include <Eigen/Geometry>
#include <ignition/math/Pose3.hh>

namespace car_gazebo {

// The plug-in whose code runs now on this thread (its Load, Init, Reset or one of its event callbacks; null: none).
// A connection belongs to the plug-in that makes it, so that a plug-in kept after its model went (host.cpp, "parked")
// is cut from every event.
const void*& current_owner();
class CurrentOwner {
 public:
  explicit CurrentOwner(const void* owner) : previous_(current_owner()) { current_owner() = owner; }
  ~CurrentOwner() { current_owner() = previous_; }

 private:
  const void* previous_;
};

// One event's callbacks, in the order connected. A callback may disconnect (itself or another) while the event
// runs: it is marked and dropped afterwards.
template <class... Args>
class SlotList {
 public:
  int connect(std::function<void(Args...)> fn) {
    slots_.push_back(std::make_unique<Slot>(Slot{next_, std::move(fn), false, current_owner()}));
    return next_++;
  }
  // Disconnects every callback a plug-in connected.
  void disconnect_owner(const void* owner) {
    for (auto& s : slots_)
      if (s->owner == owner) s->removed = true;
    dirty_ = true;
    if (!running_) drop();
  }
  void disconnect(int id) {
    for (auto& s : slots_)
      if (s->id == id) s->removed = true;
    dirty_ = true;
    if (!running_) drop();
  }
  void fire(Args... args) {
    if (slots_.empty()) return;
    running_ = true;
    const size_t n = slots_.size();
    try {
      for (size_t k = 0; k < n; ++k)
        if (!slots_[k]->removed) {
          CurrentOwner as(slots_[k]->owner);
          slots_[k]->fn(args...);
        }
    } catch (...) {
      running_ = false;
      drop();
      throw;
    }
    running_ = false;
    drop();
  }
  bool empty() const { return slots_.empty(); }

 private:
  struct Slot {
    int id;
    std::function<void(Args...)> fn;
    bool removed;
    const void* owner;
  };
  void drop() {
    if (!dirty_) return;
    std::vector<std::unique_ptr<Slot>> keep;
    for (auto& s : slots_)
      if (!s->removed) keep.push_back(std::move(s));
    slots_.swap(keep);
    dirty_ = false;
  }
  std::vector<std::unique_ptr<Slot>> slots_;
  int next_ = 0;
  bool running_ = false, dirty_ = false;
};

class Hub : public std::enable_shared_from_this<Hub> {
 public:
  explicit Hub(car_sim::World* core);
  ~Hub();
  // The hub of a car world, made on first use; it lives while a plug-in of that world holds it.
  static std::shared_ptr<Hub> of(car_sim::World* core);
  // The hub whose plug-in is running now (Load, Init, Reset, an event); else the only one there is; else null.
  static Hub* current();

  car_sim::World* core;
  gazebo::physics::WorldPtr world;
  SlotList<const gazebo::common::UpdateInfo&> begin, before;
  SlotList<> end, stop, time_reset;
  // car's own work of the physics step, after it and before WorldUpdateEnd, while physics is enabled (ODE's island
  // rule for disabled links, Link::SetEnabled); plug-ins do not connect here, and disconnect_owner leaves it
  SlotList<> islands;
  SlotList<bool> pause;
  // whether an update event is running (work that must not run inside a step is deferred)
  bool in_step = false;
  // the world's end has begun (its stop event ran): plug-ins are deleted from now on, none is parked
  bool stopping = false;
  // Plug-ins kept after their model went, because threads they started still ran (host.cpp): cut from every event,
  // deleted at the world's end once those threads have ended.
  std::vector<std::shared_ptr<void>> parked;
  // Cuts a plug-in's callbacks from every event.
  void disconnect_owner(const void* owner) {
    begin.disconnect_owner(owner);
    before.disconnect_owner(owner);
    end.disconnect_owner(owner);
    stop.disconnect_owner(owner);
    time_reset.disconnect_owner(owner);
    pause.disconnect_owner(owner);
  }

  // Gazebo's factory: a model's SDF text (or a file, by its URI) inserted at the end of the next step, named
  // `name` when given (else the document's), at `pose` when given (else the document's). Errors are gzerr lines, as
  // Gazebo's World::ProcessFactoryMsgs prints them.
  struct Insert {
    std::string sdf, file;
    std::optional<ignition::math::Pose3d> pose;
    bool allow_renaming = true;
  };
  void insert(Insert what);
  // The hub of the world named `name` ("" or the current one's name: the current one); null when none.
  static Hub* named(const std::string& name);

  // car's transport within this world (docs/PLUGINS.md "Transport"): subscribers by topic and message type; a
  // published message goes to the subscribers of its topic and type present now, at the end of the step (deferred
  // work); the topic's last message is kept for latching subscribers.
  using Delivery = std::function<void(const boost::shared_ptr<const void>&)>;
  int subscribe(const std::string& topic, const std::string& type, Delivery cb, bool latching);
  void unsubscribe(int id);
  void publish(const std::string& topic, const std::string& type, boost::shared_ptr<const void> msg);
  // whether a subscriber of that topic and type is present now (Gazebo's Publisher::HasConnections)
  bool subscribed(const std::string& topic, const std::string& type) const;

 private:
  struct Subscription {
    int id;
    std::string topic, type;
    Delivery cb;
  };
  std::vector<Subscription> subscriptions_;
  int next_subscription_ = 0;
  std::map<std::string, std::pair<std::string, boost::shared_ptr<const void>>> latest_;  // topic -> (type, message)
  // delivers msg to those of `ids` still subscribed (at the delivery point)
  void deliver(const std::vector<int>& ids, const boost::shared_ptr<const void>& msg);
  void before_physics(uint64_t tick);
  void after_physics(uint64_t tick);
  gazebo::common::UpdateInfo info_;
  uint64_t before_hook_ = 0, after_hook_ = 0, pause_hook_ = 0, stop_hook_ = 0, time_reset_hook_ = 0;
};

// Makes a hub current for the plug-in code run in its scope.
class CurrentHub {
 public:
  explicit CurrentHub(Hub* hub);
  ~CurrentHub();

 private:
  Hub* previous_;
};

// Sim time of a tick as Gazebo's common::Time.
gazebo::common::Time time_of(uint64_t tick, double dt);

inline ignition::math::Vector3d ign(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
inline Eigen::Vector3d eig(const ignition::math::Vector3d& v) { return {v.X(), v.Y(), v.Z()}; }
inline ignition::math::Pose3d ign(const Eigen::Isometry3d& T) {
  const Eigen::Quaterniond q(T.linear());
  return ignition::math::Pose3d(ign(Eigen::Vector3d(T.translation())),
                                ignition::math::Quaterniond(q.w(), q.x(), q.y(), q.z()));
}
inline Eigen::Isometry3d eig(const ignition::math::Pose3d& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(p.Rot().W(), p.Rot().X(), p.Rot().Y(), p.Rot().Z()).normalized().toRotationMatrix();
  T.translation() = eig(p.Pos());
  return T;
}

}  // namespace car_gazebo
