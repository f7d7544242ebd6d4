// Registering a running node with a restarted master, through the master and slave XML-RPC APIs
// (http://wiki.ros.org/ROS/Master_API, http://wiki.ros.org/ROS/Slave_API): the calls roscpp makes when a
// publisher, subscriber or service is made, made again for each one that still exists.
#include "master_watch.hpp"

#include <ros/connection_manager.h>
#include <ros/master.h>
#include <ros/network.h>
#include <ros/ros.h>
#include <ros/service_manager.h>
#include <ros/xmlrpc_manager.h>

#include <chrono>
#include <cstdio>
#include <vector>

namespace car_ros {

namespace {

using XmlRpc::XmlRpcValue;

XmlRpcValue args(std::initializer_list<XmlRpcValue> values) {
  XmlRpcValue a;
  a.setSize(static_cast<int>(values.size()));
  int i = 0;
  for (const auto& v : values) a[i++] = v;
  return a;
}

// A call to the master; false (and nothing logged) when it does not answer.
bool master_call(const std::string& method, const XmlRpcValue& request, XmlRpcValue& payload) {
  XmlRpcValue result;
  return ros::master::execute(method, request, result, payload, false);
}

// A call to this node's own slave API (what roscpp answers other nodes and the master with).
bool self_call(const std::string& method, const XmlRpcValue& request, XmlRpcValue& payload) {
  auto manager = ros::XMLRPCManager::instance();
  std::string host;
  uint32_t port = 0;
  if (!ros::network::splitURI(manager->getServerURI(), host, port)) return false;
  XmlRpc::XmlRpcClient* client = manager->getXMLRPCClient(host, static_cast<int>(port), "/");
  XmlRpcValue result;
  const bool ok = client->execute(method.c_str(), request, result) &&
                  manager->validateXmlrpcResponse(method, result, payload);
  manager->releaseXMLRPCClient(client);
  return ok;
}

// [[topic, type], ...] from getPublications / getSubscriptions of this node.
std::vector<std::pair<std::string, std::string>> own_topics(const std::string& method) {
  std::vector<std::pair<std::string, std::string>> out;
  XmlRpcValue payload;
  if (!self_call(method, args({ros::this_node::getName()}), payload) || payload.getType() != XmlRpcValue::TypeArray)
    return out;
  for (int i = 0; i < payload.size(); ++i)
    out.emplace_back(static_cast<std::string>(payload[i][0]), static_cast<std::string>(payload[i][1]));
  return out;
}

}  // namespace

MasterWatch::MasterWatch(std::function<void()> on_restart, double period_s)
    : on_restart_(std::move(on_restart)), period_s_(period_s), thread_([this] { loop(); }) {}

MasterWatch::~MasterWatch() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

int MasterWatch::master_pid() const {
  XmlRpcValue payload;
  if (!master_call("getPid", args({ros::this_node::getName()}), payload) || payload.getType() != XmlRpcValue::TypeInt)
    return -1;
  return static_cast<int>(payload);
}

void MasterWatch::remember_services() {
  // getSystemState: [publishers, subscribers, services], each [[name, [node, ...]], ...]
  XmlRpcValue payload;
  if (!master_call("getSystemState", args({ros::this_node::getName()}), payload) || payload.size() < 3) return;
  const XmlRpcValue& services = payload[2];
  for (int i = 0; i < services.size(); ++i)
    for (int j = 0; j < services[i][1].size(); ++j)
      if (static_cast<std::string>(services[i][1][j]) == ros::this_node::getName())
        services_.insert(static_cast<std::string>(services[i][0]));
}

void MasterWatch::register_again() {
  const std::string me = ros::this_node::getName();
  const std::string api = ros::XMLRPCManager::instance()->getServerURI();
  int pubs = 0, subs = 0, srvs = 0, failed = 0;
  XmlRpcValue payload;
  for (const auto& [topic, type] : own_topics("getPublications")) {
    if (master_call("registerPublisher", args({me, topic, type, api}), payload)) ++pubs; else ++failed;
  }
  for (const auto& [topic, type] : own_topics("getSubscriptions")) {
    // the new master answers with the topic's publishers; roscpp connects to them on a publisherUpdate
    if (!master_call("registerSubscriber", args({me, topic, type, api}), payload)) { ++failed; continue; }
    XmlRpcValue ignored;
    self_call("publisherUpdate", args({std::string("/master"), topic, payload}), ignored);
    ++subs;
  }
  char service_api[256];
  std::snprintf(service_api, sizeof service_api, "rosrpc://%s:%u", ros::network::getHost().c_str(),
                ros::ConnectionManager::instance()->getTCPPort());
  for (auto it = services_.begin(); it != services_.end();) {
    // a service this node has since shut down is forgotten, not registered
    if (!ros::ServiceManager::instance()->lookupServicePublication(*it)) { it = services_.erase(it); continue; }
    if (master_call("registerService", args({me, *it, std::string(service_api), api}), payload)) ++srvs; else ++failed;
    ++it;
  }
  ROS_WARN("car: the ROS master at %s restarted; registered %d publishers, %d subscribers and %d services again%s",
           ros::master::getURI().c_str(), pubs, subs, srvs, failed ? " (some registrations failed)" : "");
}

void MasterWatch::loop() {
  int known = -1;  // the pid of the master this node is registered with; -1 before the first answer
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_) {
    lock.unlock();
    const int pid = master_pid();
    if (pid >= 0) {
      if (known >= 0 && pid != known) {
        register_again();
        if (on_restart_) on_restart_();
      }
      known = pid;
      remember_services();
    }
    lock.lock();
    wake_.wait_for(lock, std::chrono::duration<double>(period_s_), [this] { return stop_; });
  }
}

}  // namespace car_ros
