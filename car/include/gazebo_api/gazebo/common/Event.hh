// car's Gazebo 11 API (docs/PLUGINS.md): an event connection. Keep the ConnectionPtr: the callback is connected
// while it lives, and disconnected when its last copy goes (reset() it to disconnect), as in Gazebo 11.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>

#include "gazebo/common/CommonTypes.hh"

namespace gazebo {
namespace event {

class Connection {
 public:
  // car: made by event::Events; disconnects in its destructor.
  explicit Connection(std::function<void()> _disconnect);
  ~Connection();
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;
  int Id() const;

 private:
  std::function<void()> disconnect;
  int id;
};

}  // namespace event
}  // namespace gazebo
