// Master restart: roscpp registers a node's publishers, subscribers and services with the master once, when they
// are made, so a roscore restarted under a running node leaves it unknown to the new master (ROS 1's usual
// behaviour, and Gazebo's). MasterWatch notices a new master and registers them again.
#pragma once

#include <condition_variable>
#include <functional>
#include <mutex>
#include <set>
#include <string>
#include <thread>

namespace car_ros {

// Polls the master's pid on its own thread every period of wall time (it is about the master process, not the
// simulation). While a master answers, it notes which services this node provides (only the master lists them);
// when a master with another pid answers (a restarted roscore), it registers every publisher, subscriber and
// service of this node with it, hands each subscriber the publishers the new master knows, then calls on_restart
// (for the node's own parameters, e.g. /use_sim_time). Parameters other nodes set (robot_description) are theirs.
class MasterWatch {
 public:
  explicit MasterWatch(std::function<void()> on_restart = {}, double period_s = 1.0);
  ~MasterWatch();  // stops and joins the thread
  MasterWatch(const MasterWatch&) = delete;
  MasterWatch& operator=(const MasterWatch&) = delete;

 private:
  void loop();
  // The master's pid; -1 when no master answers.
  int master_pid() const;
  void remember_services();
  void register_again();

  std::function<void()> on_restart_;
  double period_s_;
  std::set<std::string> services_;  // fully qualified names this node provides
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace car_ros
