// car's Gazebo 11 API: transport within one world, for the messages car carries (Vector3d, ImageStamped, LaserScanStamped):
// Subscriber, Node::Subscribe, Advertise and Publisher::Publish of each, and the hub's delivery (docs/PLUGINS.md
// "Transport").
// Gazebo's transport hands a message to its subscribers on its own threads, some time after Publish; car delivers at
// one point of its step instead: the end of the step the message was published in.
#include <algorithm>
#include <stdexcept>

#include "car_sim/world.hpp"
#include "gazebo/common/Console.hh"
#include "gazebo/transport/transport.hh"
#include "hub.hpp"

namespace car_gazebo {

int Hub::subscribe(const std::string& topic, const std::string& type, Delivery cb, bool latching) {
  const int id = next_subscription_++;
  subscriptions_.push_back({id, topic, type, std::move(cb)});
  const auto last = latest_.find(topic);
  if (latching && last != latest_.end() && last->second.first == type) {
    std::weak_ptr<Hub> weak = shared_from_this();
    boost::shared_ptr<const void> msg = last->second.second;
    core->defer([weak, id, msg] {
      if (auto h = weak.lock()) h->deliver({id}, msg);
    });
  }
  return id;
}

void Hub::unsubscribe(int id) {
  subscriptions_.erase(std::remove_if(subscriptions_.begin(), subscriptions_.end(),
                                      [id](const Subscription& s) { return s.id == id; }),
                       subscriptions_.end());
}

void Hub::publish(const std::string& topic, const std::string& type, boost::shared_ptr<const void> msg) {
  latest_[topic] = {type, msg};
  // the subscribers present now (Gazebo's publication goes to those connected when it is sent)
  std::vector<int> ids;
  for (const auto& s : subscriptions_)
    if (s.topic == topic && s.type == type) ids.push_back(s.id);
  if (ids.empty()) return;
  std::weak_ptr<Hub> weak = shared_from_this();
  core->defer([weak, ids, msg] {
    if (auto h = weak.lock()) h->deliver(ids, msg);
  });
}

bool Hub::subscribed(const std::string& topic, const std::string& type) const {
  for (const auto& s : subscriptions_)
    if (s.topic == topic && s.type == type) return true;
  return false;
}

void Hub::deliver(const std::vector<int>& ids, const boost::shared_ptr<const void>& msg) {
  CurrentHub in(this);
  for (int id : ids) {
    // a callback may unsubscribe itself or another: look each one up when its turn comes
    const auto it = std::find_if(subscriptions_.begin(), subscriptions_.end(),
                                 [id](const Subscription& s) { return s.id == id; });
    if (it == subscriptions_.end()) continue;
    const Delivery cb = it->cb;
    cb(msg);
  }
}

}  // namespace car_gazebo

namespace gazebo {
namespace transport {

namespace {

car_gazebo::Hub& hub_of(const std::string& world) {
  car_gazebo::Hub* h = car_gazebo::Hub::named(world);
  if (!h)
    throw std::logic_error("no world named '" + world +
                           "' has a plug-in running: car's transport carries messages within a world");
  return *h;
}

// The messages car's transport carries, by Gazebo's type names
template <class M>
const char* type_name();
template <>
const char* type_name<msgs::Vector3d>() {
  return "gazebo.msgs.Vector3d";
}
template <>
const char* type_name<msgs::ImageStamped>() {
  return "gazebo.msgs.ImageStamped";
}
template <>
const char* type_name<msgs::LaserScanStamped>() {
  return "gazebo.msgs.LaserScanStamped";
}

// Node::Advertise, Publisher::Publish and Node::Subscribe for a message M that car carries
template <class M>
PublisherPtr advertise(Node& node, const std::string& topic) {
  return PublisherPtr(new Publisher(node.DecodeTopicName(topic), type_name<M>(), node.GetTopicNamespace()));
}

template <class M>
void publish(const std::string& world, const std::string& topic, const M& message) {
  hub_of(world).publish(topic, type_name<M>(), boost::shared_ptr<const void>(new M(message)));
}

template <class M>
SubscriberPtr subscribe(Node& node, const std::string& _topic,
                        std::function<void(const boost::shared_ptr<M const>&)> cb, bool latching) {
  const std::string topic = node.DecodeTopicName(_topic);
  car_gazebo::Hub& hub = hub_of(node.GetTopicNamespace());
  const int id = hub.subscribe(
      topic, type_name<M>(),
      [cb](const boost::shared_ptr<const void>& msg) { cb(boost::static_pointer_cast<const M>(msg)); }, latching);
  std::weak_ptr<car_gazebo::Hub> weak = hub.shared_from_this();
  return SubscriberPtr(new Subscriber(topic, [weak, id] {
    if (auto h = weak.lock()) h->unsubscribe(id);
  }));
}

}  // namespace

Subscriber::Subscriber(const std::string& _topic, std::function<void()> _unsubscribe)
    : topic(_topic), unsubscribe(std::move(_unsubscribe)) {}
Subscriber::~Subscriber() { Unsubscribe(); }
std::string Subscriber::GetTopic() const { return topic; }
void Subscriber::Unsubscribe() const {
  if (unsubscribe) unsubscribe();
  unsubscribe = nullptr;
}

// Node::Advertise, Publisher::Publish and Node::SubscribeCallback for a message M that car carries (type_name<M>)
#define CAR_TRANSPORT_MESSAGE(M)                                                                             \
  template <>                                                                                                \
  PublisherPtr Node::Advertise<M>(const std::string& _topic, unsigned int, double) {                         \
    return advertise<M>(*this, _topic);                                                                      \
  }                                                                                                          \
  template <>                                                                                                \
  void Publisher::Publish<M>(const M& _message, bool) {                                                      \
    publish(this->world, this->topic, _message);                                                             \
  }                                                                                                          \
  template <>                                                                                                \
  SubscriberPtr Node::SubscribeCallback<M>(const std::string& _topic,                                        \
                                           std::function<void(const boost::shared_ptr<M const>&)> _cb,      \
                                           bool _latching) {                                                 \
    return subscribe<M>(*this, _topic, std::move(_cb), _latching);                                           \
  }

CAR_TRANSPORT_MESSAGE(msgs::Vector3d)
CAR_TRANSPORT_MESSAGE(msgs::LaserScanStamped)
CAR_TRANSPORT_MESSAGE(msgs::ImageStamped)
#undef CAR_TRANSPORT_MESSAGE

}  // namespace transport
}  // namespace gazebo
