// gazebo::RayPlugin for car (docs/PLUGINS.md "Sensor plug-in bases"), as Gazebo 11's plugins/RayPlugin.cc behaves; the
// library libRayPlugin.so is itself a sensor plug-in, as upstream's.
#include "gazebo/plugins/RayPlugin.hh"

#include <functional>

#include "gazebo/common/Exception.hh"
#include "gazebo/physics/physics.hh"

namespace gazebo {

GZ_REGISTER_SENSOR_PLUGIN(RayPlugin)

RayPlugin::RayPlugin() = default;

RayPlugin::~RayPlugin() {
  this->newLaserScansConnection.reset();
  this->parentSensor.reset();
  this->world.reset();
}

void RayPlugin::Load(sensors::SensorPtr _parent, sdf::ElementPtr /*_sdf*/) {
  this->parentSensor = std::dynamic_pointer_cast<sensors::RaySensor>(_parent);
  if (!this->parentSensor) gzthrow("RayPlugin requires a Ray Sensor as its parent");
  this->world = physics::get_world(this->parentSensor->WorldName());
  // Gazebo's LaserShape()->ConnectNewLaserScans: in car, the sensor's update after each scan
  this->newLaserScansConnection = this->parentSensor->ConnectUpdated(std::bind(&RayPlugin::OnNewLaserScans, this));
}

void RayPlugin::OnNewLaserScans() {}

}  // namespace gazebo
