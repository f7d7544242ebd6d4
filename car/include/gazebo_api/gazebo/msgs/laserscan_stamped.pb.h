// car's Gazebo 11 API (docs/PLUGINS.md "Sensors"): gazebo::msgs::LaserScanStamped (laserscan_stamped.proto),
// hand-written (vector3d.pb.h): the time of the scan and the scan.
#pragma once

#include <string>

#include "gazebo/msgs/laserscan.pb.h"
#include "gazebo/msgs/time.pb.h"

namespace gazebo {
namespace msgs {

class LaserScanStamped {
 public:
  const Time& time() const { return time_; }
  Time* mutable_time() { return &time_; }
  const LaserScan& scan() const { return scan_; }
  LaserScan* mutable_scan() { return &scan_; }
  std::string GetTypeName() const { return "gazebo.msgs.LaserScanStamped"; }

 private:
  Time time_;
  LaserScan scan_;
};

}  // namespace msgs
}  // namespace gazebo
