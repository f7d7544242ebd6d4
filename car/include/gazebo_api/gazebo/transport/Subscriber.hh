// car's Gazebo 11 API (docs/PLUGINS.md "Transport"): transport::Subscriber, what Node::Subscribe returns: keep it to
// stay subscribed; its destructor or Unsubscribe ends the subscription, as Gazebo's.
#pragma once

#include <functional>
#include <string>

namespace gazebo {
namespace transport {

class Subscriber {
 public:
  // car: made by Node::Subscribe, with what ends the subscription.
  Subscriber(const std::string& _topic, std::function<void()> _unsubscribe);
  virtual ~Subscriber();

  std::string GetTopic() const;
  void Unsubscribe() const;

 private:
  std::string topic;
  mutable std::function<void()> unsubscribe;
};

}  // namespace transport
}  // namespace gazebo
