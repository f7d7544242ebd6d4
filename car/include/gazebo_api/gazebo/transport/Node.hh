// car's Gazebo 11 API (docs/PLUGINS.md "Transport"): transport::Node, as far as the factory and velodyne tutorials and
// camera plug-ins use it: Init with a world's name; Advertise<msgs::Factory> on ~/factory, which inserts models into
// that world; and Advertise and Subscribe for msgs::Vector3d, msgs::ImageStamped and msgs::LaserScanStamped (a ray
// sensor's scans) on any topic, within this
// process. car has no Gazebo transport between processes: other message types fail to link.
#pragma once

// as Gazebo 11's Node.hh: boost::bind with its placeholders _1, _2, ... in the global namespace, quietly
#ifndef BOOST_BIND_GLOBAL_PLACEHOLDERS
#define BOOST_BIND_GLOBAL_PLACEHOLDERS
#endif
#include <boost/bind.hpp>
#include <boost/enable_shared_from_this.hpp>
#include <boost/shared_ptr.hpp>
#include <functional>
#include <string>

#include "gazebo/msgs/msgs.hh"
#include "gazebo/transport/Publisher.hh"
#include "gazebo/transport/Subscriber.hh"
#include "gazebo/transport/TransportTypes.hh"

namespace gazebo {
namespace transport {

class Node : public boost::enable_shared_from_this<Node> {
 public:
  Node();
  virtual ~Node();
  // The namespace: a world's name ("" : the world of the plug-in being loaded). Always true.
  bool Init(const std::string& _space = "");
  std::string GetTopicNamespace() const;
  // "~/x" -> "/gazebo/<namespace>/x"; other names as they are.
  std::string DecodeTopicName(const std::string& _topic);
  // Offered for M = msgs::Factory on "~/factory" (or "/gazebo/<namespace>/factory") only: another topic throws
  // std::invalid_argument naming it; and for M = msgs::Vector3d, ImageStamped and LaserScanStamped on any topic ("~/" decoded as
  // above); _queueLimit and _hzRate have no effect.
  template <typename M>
  PublisherPtr Advertise(const std::string& _topic, unsigned int _queueLimit = 1000, double _hzRate = 0);

  // Offered for M = msgs::Vector3d, ImageStamped and LaserScanStamped: the callback gets each message published on the topic in this node's world by
  // the subscribers present at Publish, at the delivery point: the end of the step it was published in (after the
  // sensors), or the node's next turn while paused; never inside Publish. _latching: the topic's last message, if
  // any, comes at the next delivery point too.
  template <typename M, typename T>
  SubscriberPtr Subscribe(const std::string& _topic, void (T::*_fp)(const boost::shared_ptr<M const>&), T* _obj,
                          bool _latching = false) {
    return this->SubscribeCallback<M>(
        _topic, [_fp, _obj](const boost::shared_ptr<M const>& _msg) { (_obj->*_fp)(_msg); }, _latching);
  }
  template <typename M>
  SubscriberPtr Subscribe(const std::string& _topic, void (*_fp)(const boost::shared_ptr<M const>&),
                          bool _latching = false) {
    return this->SubscribeCallback<M>(_topic, _fp, _latching);
  }

 private:
  // car: both Subscribe calls' work.
  template <typename M>
  SubscriberPtr SubscribeCallback(const std::string& _topic, std::function<void(const boost::shared_ptr<M const>&)> _cb,
                                  bool _latching);

  std::string topicNamespace;
};

template <>
PublisherPtr Node::Advertise<msgs::Factory>(const std::string& _topic, unsigned int _queueLimit, double _hzRate);
template <>
PublisherPtr Node::Advertise<msgs::Vector3d>(const std::string& _topic, unsigned int _queueLimit, double _hzRate);
template <>
SubscriberPtr Node::SubscribeCallback<msgs::Vector3d>(
    const std::string& _topic, std::function<void(const boost::shared_ptr<msgs::Vector3d const>&)> _cb, bool _latching);
template <>
PublisherPtr Node::Advertise<msgs::LaserScanStamped>(const std::string& _topic, unsigned int _queueLimit,
                                                     double _hzRate);
template <>
SubscriberPtr Node::SubscribeCallback<msgs::LaserScanStamped>(
    const std::string& _topic, std::function<void(const boost::shared_ptr<msgs::LaserScanStamped const>&)> _cb,
    bool _latching);
template <>
PublisherPtr Node::Advertise<msgs::ImageStamped>(const std::string& _topic, unsigned int _queueLimit, double _hzRate);
template <>
SubscriberPtr Node::SubscribeCallback<msgs::ImageStamped>(
    const std::string& _topic, std::function<void(const boost::shared_ptr<msgs::ImageStamped const>&)> _cb,
    bool _latching);

}  // namespace transport
}  // namespace gazebo
