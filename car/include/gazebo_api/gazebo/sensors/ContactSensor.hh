// car's Gazebo 11 API (docs/PLUGINS.md "Sensors"): gazebo::sensors::ContactSensor, the contacts car's bumper kind
// finds for a <sensor type="contact"> (its <contact><collision>'s link).
#pragma once

#include <string>

#include "gazebo/msgs/contacts.pb.h"
#include "gazebo/sensors/Sensor.hh"

namespace gazebo {
namespace sensors {

class ContactSensor : public Sensor {
 public:
  using Sensor::Sensor;
  // The contacts of the last measurement: one msgs::Contact per other body, its points, normals (world frame,
  // from collision2 into collision1), depths and the force on collision1 (body_1_wrench, world frame).
  msgs::Contacts Contacts() const;
  // The <contact><collision> it watches: 1 (0 when it names none).
  unsigned int GetCollisionCount() const;
  std::string GetCollisionName(unsigned int _index) const;

 protected:
  void CarMeasure(const car_sim::Output* _sample) override;

 private:
  msgs::Contacts contacts;
};

}  // namespace sensors
}  // namespace gazebo
