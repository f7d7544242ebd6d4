// car's Gazebo 11 API (docs/PLUGINS.md "Sensor plug-in bases"): gazebo::RayPlugin (gazebo/plugins/RayPlugin.hh),
// the base of ray sensors' plug-ins (gazebo_ros_laser, velodyne, ...): Load takes the parent ray sensor (gzthrow
// "RayPlugin requires a Ray Sensor as its parent" for another), the world, and calls OnNewLaserScans after each of
// the sensor's scans. Link the library RayPlugin (target_link_libraries(... RayPlugin), as with Gazebo 11: it is in
// GAZEBO_LIBRARY_DIRS).
#pragma once

#include "gazebo/common/Plugin.hh"
#include "gazebo/physics/PhysicsTypes.hh"
#include "gazebo/sensors/RaySensor.hh"
#include "gazebo/sensors/SensorTypes.hh"

namespace gazebo {

class GZ_PLUGIN_VISIBLE RayPlugin : public SensorPlugin {
 public:
  RayPlugin();
  virtual ~RayPlugin();
  // After each scan of the parent sensor; does nothing here (subclasses override it).
  virtual void OnNewLaserScans();
  void Load(sensors::SensorPtr _parent, sdf::ElementPtr _sdf);

 protected:
  physics::WorldPtr world;

 private:
  sensors::RaySensorPtr parentSensor;
  event::ConnectionPtr newLaserScansConnection;
};

}  // namespace gazebo
