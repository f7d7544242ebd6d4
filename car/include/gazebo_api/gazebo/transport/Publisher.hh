// car's Gazebo 11 API (docs/PLUGINS.md "Transport"): transport::Publisher. msgs::Factory on ~/factory: Publish hands
// the message to the world at once (Gazebo's transport delivers it later); the model appears at the end of the next
// step, as with World::InsertModelFile. msgs::Vector3d: the topic's subscribers get it at the delivery point
// (Node::Subscribe).
#pragma once

#include <string>

#include "gazebo/msgs/msgs.hh"
#include "gazebo/transport/TransportTypes.hh"

namespace gazebo {
namespace transport {

class Publisher {
 public:
  // car: made by Node::Advertise.
  Publisher(const std::string& _topic, const std::string& _msgType, const std::string& _world);
  virtual ~Publisher();
  std::string GetTopic() const;
  std::string GetMsgType() const;
  template <typename M>
  void Publish(const M& _message, bool _block = false);

 private:
  std::string topic, msgType, world;
};

template <>
void Publisher::Publish<msgs::Factory>(const msgs::Factory& _message, bool _block);
template <>
void Publisher::Publish<msgs::Vector3d>(const msgs::Vector3d& _message, bool _block);
template <>
void Publisher::Publish<msgs::ImageStamped>(const msgs::ImageStamped& _message, bool _block);
template <>
void Publisher::Publish<msgs::LaserScanStamped>(const msgs::LaserScanStamped& _message, bool _block);

}  // namespace transport
}  // namespace gazebo
