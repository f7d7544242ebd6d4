// car's Gazebo 11 API (docs/PLUGINS.md): transport's pointer types, boost::shared_ptr as in Gazebo 11.
#pragma once

#include <boost/shared_ptr.hpp>

namespace gazebo {
namespace transport {

class Node;
class Publisher;
typedef boost::shared_ptr<Node> NodePtr;
typedef boost::shared_ptr<Publisher> PublisherPtr;

}  // namespace transport
}  // namespace gazebo
