// car's Gazebo 11 API (docs/PLUGINS.md): gazebo/transport/TransportTypes.hh, the transport layer's class names and
// pointer types as Gazebo 11 declares them (boost::shared_ptr). car offers Node, Publisher and Subscriber
// (gazebo/transport/Node.hh, docs/PLUGINS.md "Transport"); the other classes stay incomplete, so code that uses one
// fails to build.
#pragma once

#include <boost/shared_ptr.hpp>

namespace gazebo {
namespace transport {

class Connection;
class Node;
class Publication;
class Publisher;
class Subscriber;
class SubscriptionTransport;

typedef boost::shared_ptr<Connection> ConnectionPtr;
typedef boost::shared_ptr<Node> NodePtr;
typedef boost::shared_ptr<Publication> PublicationPtr;
typedef boost::shared_ptr<Publisher> PublisherPtr;
typedef boost::shared_ptr<Subscriber> SubscriberPtr;
typedef boost::shared_ptr<SubscriptionTransport> SubscriptionTransportPtr;

}  // namespace transport
}  // namespace gazebo
