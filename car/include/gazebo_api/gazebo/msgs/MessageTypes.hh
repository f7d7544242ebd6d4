// car's Gazebo 11 API (docs/PLUGINS.md "Transport"): gazebo/msgs/MessageTypes.hh, the const message pointers callbacks
// take, for the messages car's transport carries.
#pragma once

#include <boost/shared_ptr.hpp>

#include "gazebo/msgs/image_stamped.pb.h"
#include "gazebo/msgs/laserscan_stamped.pb.h"
#include "gazebo/msgs/vector3d.pb.h"

namespace gazebo {

typedef const boost::shared_ptr<const msgs::Vector3d> ConstVector3dPtr;
typedef const boost::shared_ptr<const msgs::ImageStamped> ConstImageStampedPtr;
typedef const boost::shared_ptr<const msgs::LaserScanStamped> ConstLaserScanStampedPtr;

}  // namespace gazebo
