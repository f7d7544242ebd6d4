// car_gazebo's sensors (docs/PLUGINS.md "Sensors"): Gazebo 11's sensor classes over the outputs of car's own kind
// for each sensor's type, which the plug-in table's shared-library entry runs for them and hands over on the
// sensor's update_rate while it is active (car_sim/shared_plugin.hpp). No measuring here: only copies.
#include <algorithm>
#include <boost/make_shared.hpp>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>

#include "car_sim/model.hpp"
#include "car_sim/plugin.hpp"
#include "gazebo/common/Console.hh"
#include "gazebo/rendering/Camera.hh"
#include "gazebo/rendering/DepthCamera.hh"
#include "gazebo/sensors/sensors.hh"
#include "hub.hpp"

namespace gazebo {
namespace sensors {

class SensorPrivate {
 public:
  std::string name, type, world, model, link;
  ignition::math::Pose3d pose;
  double rate = 0.0;  // [Hz]
  bool active = false, visualize = false;
  common::Time last;
  std::vector<std::pair<std::string, std::string>> keys;
  car_gazebo::SlotList<> updated;
};

namespace {

template <class List>
event::ConnectionPtr connect_to(const std::shared_ptr<void>& owner, List* list, int id) {
  std::weak_ptr<void> weak = owner;
  return boost::make_shared<event::Connection>([weak, list, id] {
    if (auto alive = weak.lock()) list->disconnect(id);
  });
}

}  // namespace

Sensor::Sensor(const car_sim::SensorSpec& _spec, const std::string& _world, const std::string& _model,
               const std::vector<std::pair<std::string, std::string>>& _keys)
    : dataPtr(std::make_shared<SensorPrivate>()) {
  dataPtr->name = _spec.name;
  dataPtr->type = _spec.type;
  dataPtr->world = _world;
  dataPtr->model = _model;
  dataPtr->link = _spec.link;
  dataPtr->pose = car_gazebo::ign(_spec.pose);
  dataPtr->rate = _spec.update_rate;
  // Gazebo's Sensor::Load: <always_on> makes it active
  dataPtr->active = _spec.always_on;
  dataPtr->visualize = _spec.visualize;
  dataPtr->keys = _keys;
}

Sensor::~Sensor() = default;

std::string Sensor::Name() const { return dataPtr->name; }
std::string Sensor::ScopedName() const { return dataPtr->world + "::" + ParentName() + "::" + dataPtr->name; }
std::string Sensor::ParentName() const { return dataPtr->model + "::" + dataPtr->link; }
std::string Sensor::WorldName() const { return dataPtr->world; }
std::string Sensor::Type() const { return dataPtr->type; }
double Sensor::UpdateRate() const { return dataPtr->rate; }
ignition::math::Pose3d Sensor::Pose() const { return dataPtr->pose; }
bool Sensor::Visualize() const { return dataPtr->visualize; }
void Sensor::SetActive(const bool _value) { dataPtr->active = _value; }
bool Sensor::IsActive() const { return dataPtr->active; }
common::Time Sensor::LastUpdateTime() const { return dataPtr->last; }
common::Time Sensor::LastMeasurementTime() const { return dataPtr->last; }

event::ConnectionPtr Sensor::ConnectUpdated(std::function<void()> _subscriber) {
  const int id = dataPtr->updated.connect(std::move(_subscriber));
  return connect_to(dataPtr, &dataPtr->updated, id);
}

void Sensor::CarUpdate(const common::Time& _time, const car_sim::Output* _sample) {
  dataPtr->last = _time;
  CarMeasure(_sample);
  dataPtr->updated.fire();
}

std::string Sensor::CarKey(const std::string& _key) const {
  for (const auto& [k, v] : dataPtr->keys)
    if (k == _key) return v;
  return "";
}

double Sensor::CarNumber(const std::string& _key, double _default) const {
  const std::string v = CarKey(_key);
  if (v.empty()) return _default;
  try {
    return std::stod(v);
  } catch (const std::exception&) {
    return _default;
  }
}

// ---- SensorManager: Gazebo's GetSensor (SensorManager.cc): the scoped name first, then a unique leaf name ----

namespace {
std::mutex g_manager_mutex;
}

SensorManager* SensorManager::Instance() {
  static SensorManager manager;
  return &manager;
}

SensorPtr SensorManager::GetSensor(const std::string& _name) const {
  std::lock_guard<std::mutex> lock(g_manager_mutex);
  for (const auto& s : sensors)
    if (s->ScopedName() == _name) return s;
  SensorPtr found;
  for (const auto& s : sensors) {
    if (s->Name() != _name) continue;
    if (found) {
      gzerr << "Unable to get a sensor, multiple sensors with the same name[" << _name
            << "]. Use a scoped name instead, world_name::model_name::link_name::sensor_name.\n";
      return nullptr;
    }
    found = s;
  }
  return found;
}

Sensor_V SensorManager::GetSensors() const {
  std::lock_guard<std::mutex> lock(g_manager_mutex);
  return sensors;
}

void SensorManager::CarAdd(const SensorPtr& _sensor) {
  std::lock_guard<std::mutex> lock(g_manager_mutex);
  sensors.push_back(_sensor);
}

void SensorManager::CarRemove(const SensorPtr& _sensor) {
  std::lock_guard<std::mutex> lock(g_manager_mutex);
  sensors.erase(std::remove(sensors.begin(), sensors.end(), _sensor), sensors.end());
}

SensorPtr get_sensor(const std::string& _name) { return SensorManager::Instance()->GetSensor(_name); }

// ---- RaySensor: car's laser's LaserScanSample ----

ignition::math::Angle RaySensor::AngleMin() const { return CarNumber("ray/scan/horizontal/min_angle", 0.0); }
ignition::math::Angle RaySensor::AngleMax() const { return CarNumber("ray/scan/horizontal/max_angle", 0.0); }
double RaySensor::AngleResolution() const {
  // Gazebo's: the span over RangeCount() - 1 gaps
  const int n = RangeCount();
  return n > 1 ? (AngleMax() - AngleMin()).Radian() / (n - 1) : 0.0;
}
double RaySensor::RangeMin() const { return CarNumber("ray/range/min", 0.0); }
double RaySensor::RangeMax() const { return CarNumber("ray/range/max", 0.0); }
double RaySensor::RangeResolution() const { return CarNumber("ray/range/resolution", 0.0); }
int RaySensor::RayCount() const { return static_cast<int>(CarNumber("ray/scan/horizontal/samples", 1)); }
int RaySensor::RangeCount() const {
  return static_cast<int>(RayCount() * CarNumber("ray/scan/horizontal/resolution", 1.0));
}
int RaySensor::VerticalRayCount() const { return static_cast<int>(CarNumber("ray/scan/vertical/samples", 1)); }
int RaySensor::VerticalRangeCount() const {
  return static_cast<int>(VerticalRayCount() * CarNumber("ray/scan/vertical/resolution", 1.0));
}
ignition::math::Angle RaySensor::VerticalAngleMin() const { return CarNumber("ray/scan/vertical/min_angle", 0.0); }
ignition::math::Angle RaySensor::VerticalAngleMax() const { return CarNumber("ray/scan/vertical/max_angle", 0.0); }
double RaySensor::VerticalAngleResolution() const {
  const int n = VerticalRangeCount();
  return n > 1 ? (VerticalAngleMax() - VerticalAngleMin()).Radian() / (n - 1) : 0.0;
}

double RaySensor::Range(const unsigned int _index) const {
  if (ranges.empty()) {
    gzwarn << "ranges not constructed yet (sensor " << Name() << " has not measured)\n";
    return 0.0;
  }
  if (_index >= ranges.size()) {
    gzerr << "Invalid range index[" << _index << "] (sensor " << Name() << " has " << ranges.size() << ")\n";
    return 0.0;
  }
  return ranges[_index];
}

void RaySensor::Ranges(std::vector<double>& _ranges) const { _ranges = ranges; }

double RaySensor::Retro(const unsigned int _index) const {
  if (_index >= retros.size()) {
    gzerr << "Invalid retro index[" << _index << "] (sensor " << Name() << " has " << retros.size() << ")\n";
    return 0.0;
  }
  return retros[_index];
}

// As Gazebo 11's RaySensor::Topic: "~/" + parent + "/" + name + "/scan" with "::" as "/"
std::string RaySensor::Topic() const {
  std::string topic = "~/" + ParentName() + "/" + Name() + "/scan";
  for (size_t at = topic.find("::"); at != std::string::npos; at = topic.find("::", at + 1)) topic.replace(at, 2, "/");
  return topic;
}

namespace {
const char* const kLaserScanStamped = "gazebo.msgs.LaserScanStamped";

}  // namespace

bool RaySensor::IsActive() const {
  if (Sensor::IsActive()) return true;
  car_gazebo::Hub* hub = car_gazebo::Hub::named(WorldName());
  return hub && hub->subscribed(ScanTopic(), kLaserScanStamped);
}

// Topic() decoded as transport::Node does ("~/" -> "/gazebo/WORLD/"), made on first use
const std::string& RaySensor::ScanTopic() const {
  if (decodedTopic.empty()) decodedTopic = "/gazebo/" + WorldName() + "/" + Topic().substr(2);
  return decodedTopic;
}

void RaySensor::CarMeasure(const car_sim::Output* _sample) {
  const car_sim::LaserScanSample* s = _sample ? _sample->sample_of<car_sim::LaserScanSample>() : nullptr;
  if (!s) return;
  ranges.assign(s->ranges.begin(), s->ranges.end());
  retros.assign(s->intensities.begin(), s->intensities.end());
  // Gazebo's RaySensor::UpdateImpl: the scan on its topic, while it has a subscriber
  car_gazebo::Hub* hub = car_gazebo::Hub::named(WorldName());
  const std::string& topic = ScanTopic();
  if (!hub || !hub->subscribed(topic, kLaserScanStamped)) return;
  auto msg = boost::make_shared<msgs::LaserScanStamped>();
  msgs::Set(msg->mutable_time(), LastMeasurementTime());
  msgs::LaserScan* scan = msg->mutable_scan();
  scan->set_frame(ParentName());
  scan->set_angle_min(AngleMin().Radian());
  scan->set_angle_max(AngleMax().Radian());
  scan->set_angle_step(AngleResolution());
  scan->set_count(RangeCount());
  scan->set_vertical_angle_min(VerticalAngleMin().Radian());
  scan->set_vertical_angle_max(VerticalAngleMax().Radian());
  scan->set_vertical_angle_step(VerticalAngleResolution());
  scan->set_vertical_count(VerticalRangeCount());
  scan->set_range_min(RangeMin());
  scan->set_range_max(RangeMax());
  for (double r : ranges) scan->add_ranges(r);
  for (double i : retros) scan->add_intensities(i);
  hub->publish(topic, kLaserScanStamped, msg);
}

// ---- ImuSensor: car's imu_sensor kind's ImuSample ----

ignition::math::Quaterniond ImuSensor::Orientation() const { return orientation; }
ignition::math::Vector3d ImuSensor::AngularVelocity() const { return angularVelocity; }
ignition::math::Vector3d ImuSensor::LinearAcceleration() const { return linearAcceleration; }

void ImuSensor::CarMeasure(const car_sim::Output* _sample) {
  const std::optional<car_sim::ImuSample> s = _sample ? _sample->sample_of<car_sim::ImuSample>() : std::nullopt;
  if (!s) return;
  orientation =
      ignition::math::Quaterniond(s->orientation.w(), s->orientation.x(), s->orientation.y(), s->orientation.z());
  angularVelocity = car_gazebo::ign(s->angular_velocity);
  linearAcceleration = car_gazebo::ign(s->linear_acceleration);
}

// ---- ContactSensor: car's bumper kind's ContactPairs ----

namespace {
void set(msgs::Vector3d* m, const Eigen::Vector3d& v) {
  m->set_x(v.x());
  m->set_y(v.y());
  m->set_z(v.z());
}
}  // namespace

msgs::Contacts ContactSensor::Contacts() const { return contacts; }

unsigned int ContactSensor::GetCollisionCount() const { return CarKey("contact/collision").empty() ? 0 : 1; }

std::string ContactSensor::GetCollisionName(unsigned int _index) const {
  if (_index >= GetCollisionCount()) return "";
  return CarKey("contact/collision");
}

void ContactSensor::CarMeasure(const car_sim::Output* _sample) {
  const car_sim::ContactsSample* sample = _sample ? _sample->sample_of<car_sim::ContactsSample>() : nullptr;
  const std::vector<car_sim::ContactPair>* pairs = sample ? &sample->states : nullptr;
  contacts = msgs::Contacts();
  const common::Time t = LastUpdateTime();
  contacts.mutable_time()->set_sec(t.sec);
  contacts.mutable_time()->set_nsec(t.nsec);
  if (!pairs) return;
  for (const car_sim::ContactPair& p : *pairs) {
    msgs::Contact* c = contacts.add_contact();
    c->set_collision1(p.collision1);
    c->set_collision2(p.collision2);
    c->set_world(WorldName());
    *c->mutable_time() = contacts.time();
    for (size_t k = 0; k < p.positions.size(); ++k) {
      set(c->add_position(), p.positions[k]);
      set(c->add_normal(), p.normals[k]);
      c->add_depth(p.depths[k]);
      msgs::JointWrench* w = c->add_wrench();
      w->set_body_1_name(p.collision1);
      w->set_body_2_name(p.collision2);
      set(w->mutable_body_1_wrench()->mutable_force(), p.wrenches[k].force);
      set(w->mutable_body_1_wrench()->mutable_torque(), p.wrenches[k].torque);
      set(w->mutable_body_2_wrench()->mutable_force(), -p.wrenches[k].force);
      set(w->mutable_body_2_wrench()->mutable_torque(), -p.wrenches[k].torque);
    }
  }
}

// ---- CameraSensor and DepthCameraSensor: car's ray-cast cameras' ImageSamples ----

CameraSensor::CameraSensor(const car_sim::SensorSpec& _spec, const std::string& _world, const std::string& _model,
                           const std::vector<std::pair<std::string, std::string>>& _keys)
    : Sensor(_spec, _world, _model, _keys) {
  camera = std::make_shared<rendering::Camera>(Name(), static_cast<unsigned int>(CarNumber("camera/image/width", 320)),
                                               static_cast<unsigned int>(CarNumber("camera/image/height", 240)),
                                               CarKey("camera/image/format").empty() ? "R8G8B8"
                                                                                     : CarKey("camera/image/format"),
                                               CarNumber("camera/horizontal_fov", 1.047));
}

unsigned int CameraSensor::ImageWidth() const { return camera->ImageWidth(); }
unsigned int CameraSensor::ImageHeight() const { return camera->ImageHeight(); }
const unsigned char* CameraSensor::ImageData() const { return camera->ImageData(); }
rendering::CameraPtr CameraSensor::Camera() const { return camera; }

void CameraSensor::CarMeasure(const car_sim::Output* _sample) {
  const std::optional<car_sim::ImageSample> s = _sample ? _sample->sample_of<car_sim::ImageSample>() : std::nullopt;
  if (!s || !s->image) return;
  camera->CarFrame(s->image, s->image_bytes);
}

DepthCameraSensor::DepthCameraSensor(const car_sim::SensorSpec& _spec, const std::string& _world,
                                     const std::string& _model,
                                     const std::vector<std::pair<std::string, std::string>>& _keys)
    : CameraSensor(_spec, _world, _model, _keys) {
  depthCamera = std::make_shared<rendering::DepthCamera>(Name(), ImageWidth(), ImageHeight(), camera->ImageFormat(),
                                                         camera->HFOV().Radian());
  camera = depthCamera;
}

const float* DepthCameraSensor::DepthData() const { return depthCamera->DepthData(); }
rendering::DepthCameraPtr DepthCameraSensor::DepthCamera() const { return depthCamera; }

void DepthCameraSensor::CarMeasure(const car_sim::Output* _sample) {
  const std::optional<car_sim::ImageSample> s = _sample ? _sample->sample_of<car_sim::ImageSample>() : std::nullopt;
  if (!s) return;
  // Gazebo 11's DepthCamera::PostRender: the depth frame's event first, then Camera::PostRender's image frame
  if (s->depth) depthCamera->CarDepthFrame(s->depth);
  if (s->image) depthCamera->CarFrame(s->image, s->image_bytes);
}

}  // namespace sensors

// ---- rendering::Camera and DepthCamera: a frame's copy and its event ----

namespace rendering {

class CameraEvents {
 public:
  car_gazebo::SlotList<const unsigned char*, unsigned int, unsigned int, unsigned int, const std::string&> image;
  car_gazebo::SlotList<const float*, unsigned int, unsigned int, unsigned int, const std::string&> depth;
};

namespace {
// [bytes] per pixel of Gazebo's image formats
unsigned int bytes_per_pixel(const std::string& f) {
  if (f == "L8" || f == "BAYER_RGGB8" || f == "BAYER_BGGR8" || f == "BAYER_GBRG8" || f == "BAYER_GRBG8") return 1;
  if (f == "L16" || f == "L_INT16") return 2;
  if (f == "R16G16B16" || f == "RGB_INT16") return 6;
  return 3;
}
}  // namespace

Camera::Camera(const std::string& _name, unsigned int _width, unsigned int _height, const std::string& _format,
               double _hfov)
    : name(_name), format(_format), width(_width), height(_height), depth(bytes_per_pixel(_format)), hfov(_hfov),
      events(std::make_shared<CameraEvents>()) {}

Camera::~Camera() = default;
std::string Camera::Name() const { return name; }
unsigned int Camera::ImageWidth() const { return width; }
unsigned int Camera::ImageHeight() const { return height; }
unsigned int Camera::ImageDepth() const { return depth; }
std::string Camera::ImageFormat() const { return format; }
ignition::math::Angle Camera::HFOV() const { return hfov; }
const unsigned char* Camera::ImageData(const unsigned int _i) const {
  return _i == 0 && !image.empty() ? image.data() : nullptr;
}

event::ConnectionPtr Camera::ConnectNewImageFrame(
    std::function<void(const unsigned char*, unsigned int, unsigned int, unsigned int, const std::string&)>
        _subscriber) {
  const int id = events->image.connect(std::move(_subscriber));
  std::weak_ptr<CameraEvents> weak = events;
  return boost::make_shared<event::Connection>([weak, id] {
    if (auto e = weak.lock()) e->image.disconnect(id);
  });
}

void Camera::CarFrame(const unsigned char* _data, size_t _bytes) {
  image.assign(_data, _data + _bytes);
  events->image.fire(image.data(), width, height, depth, format);
}

const float* DepthCamera::DepthData() const { return depthData.empty() ? nullptr : depthData.data(); }

event::ConnectionPtr DepthCamera::ConnectNewDepthFrame(
    std::function<void(const float*, unsigned int, unsigned int, unsigned int, const std::string&)> _subscriber) {
  const int id = events->depth.connect(std::move(_subscriber));
  std::weak_ptr<CameraEvents> weak = events;
  return boost::make_shared<event::Connection>([weak, id] {
    if (auto e = weak.lock()) e->depth.disconnect(id);
  });
}

// never fired: a connection that holds nothing
event::ConnectionPtr DepthCamera::ConnectNewRGBPointCloud(
    std::function<void(const float*, unsigned int, unsigned int, unsigned int, const std::string&)>) {
  return boost::make_shared<event::Connection>([] {});
}
event::ConnectionPtr DepthCamera::ConnectNewReflectanceFrame(
    std::function<void(const float*, unsigned int, unsigned int, unsigned int, const std::string&)>) {
  return boost::make_shared<event::Connection>([] {});
}
event::ConnectionPtr DepthCamera::ConnectNewNormalsPointCloud(
    std::function<void(const float*, unsigned int, unsigned int, unsigned int, const std::string&)>) {
  return boost::make_shared<event::Connection>([] {});
}

void DepthCamera::CarDepthFrame(const float* _depth) {
  depthData.assign(_depth, _depth + static_cast<size_t>(width) * height);
  events->depth.fire(depthData.data(), width, height, 1, "FLOAT32");
}

}  // namespace rendering
}  // namespace gazebo
