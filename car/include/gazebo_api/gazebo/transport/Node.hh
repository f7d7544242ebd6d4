// car's Gazebo 11 API (docs/PLUGINS.md): transport::Node, only as far as the factory tutorial uses it: Init with a
// world's name, and Advertise<msgs::Factory> on ~/factory, which inserts models into that world. car has no Gazebo
// transport: Subscribe and the other message types are not declared, another topic is an error at Advertise.
#pragma once

#include <boost/enable_shared_from_this.hpp>
#include <string>

#include "gazebo/msgs/msgs.hh"
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
  // std::invalid_argument naming it.
  template <typename M>
  PublisherPtr Advertise(const std::string& _topic, unsigned int _queueLimit = 1000, double _hzRate = 0);

 private:
  std::string topicNamespace;
};

template <>
PublisherPtr Node::Advertise<msgs::Factory>(const std::string& _topic, unsigned int _queueLimit, double _hzRate);

}  // namespace transport
}  // namespace gazebo
