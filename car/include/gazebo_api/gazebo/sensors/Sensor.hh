// car's Gazebo 11 API (docs/PLUGINS.md "Sensors"): gazebo::sensors::Sensor, a handle on one <sensor> of a robot.
// Its measurements are those of car's own kind for the sensor's type (the same samples, seed, noise and
// update_rate; car_sim/shared_plugin.hpp), taken while the sensor is active.
#pragma once

#include <functional>
#include <ignition/math/Pose3.hh>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "gazebo/common/Event.hh"
#include "gazebo/common/Events.hh"
#include "gazebo/common/Time.hh"
#include "gazebo/msgs/msgs.hh"
#include "gazebo/sensors/SensorTypes.hh"
#include "gazebo/transport/TransportTypes.hh"

namespace car_sim {
struct Output;
struct SensorSpec;
}  // namespace car_sim

namespace gazebo {
namespace sensors {

class SensorPrivate;

class Sensor : public std::enable_shared_from_this<Sensor> {
 public:
  // car: made by car_gazebo for a <sensor> of model `_model` in world `_world`; `_keys` are the sensor's keys as
  // car's kind resolved them (flattened paths, defaults filled in).
  Sensor(const car_sim::SensorSpec& _spec, const std::string& _world, const std::string& _model,
         const std::vector<std::pair<std::string, std::string>>& _keys);
  virtual ~Sensor();

  // <sensor name>
  std::string Name() const;
  // "world::model::link::sensor"
  std::string ScopedName() const;
  // the parent link's scoped name, "model::link"
  std::string ParentName() const;
  std::string WorldName() const;
  // <sensor type>: "ray", "contact", "imu", "camera", "depth", ...
  std::string Type() const;
  // [Hz] <update_rate>; 0: every step
  double UpdateRate() const;
  // The sensor frame in its parent link's frame.
  virtual ignition::math::Pose3d Pose() const;
  bool Visualize() const;
  // Measures while active; <always_on> makes it active at load, as Gazebo's Sensor::Load.
  virtual void SetActive(const bool _value);
  virtual bool IsActive() const;
  // Sim time of the last measurement (0 before the first).
  common::Time LastUpdateTime() const;
  common::Time LastMeasurementTime() const;
  // Called after each measurement, on the physics thread.
  event::ConnectionPtr ConnectUpdated(std::function<void()> _subscriber);

  // car: a measurement at sim time `_time` from car's kind's output (nullptr: none this time).
  void CarUpdate(const common::Time& _time, const car_sim::Output* _sample);

 protected:
  // car: takes the sample into the sensor's own data.
  virtual void CarMeasure(const car_sim::Output* _sample) = 0;
  // car: a sensor key as resolved ("" when it has none).
  std::string CarKey(const std::string& _key) const;
  double CarNumber(const std::string& _key, double _default) const;

  std::shared_ptr<SensorPrivate> dataPtr;
};

}  // namespace sensors
}  // namespace gazebo
