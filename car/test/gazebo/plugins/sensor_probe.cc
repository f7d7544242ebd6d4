// Test plug-in: a sensor plug-in that activates its sensor (unless <inactive/>), and on each of its updates records
// what Gazebo's sensor classes give (ranges, contacts, IMU, camera frames) as numbers "SENSOR/WHAT", which the test
// reads through car_test_probe_value().
#include <gazebo/gazebo.hh>
#include <gazebo/rendering/Camera.hh>
#include <gazebo/sensors/sensors.hh>

#include <map>
#include <string>
#include <vector>

namespace {
std::map<std::string, double> g_values;
}

// NaN when nothing was recorded under that name.
extern "C" GZ_PLUGIN_VISIBLE double car_test_probe_value(const char* _key) {
  const auto it = g_values.find(_key);
  return it == g_values.end() ? std::nan("") : it->second;
}
extern "C" GZ_PLUGIN_VISIBLE void car_test_probe_clear() { g_values.clear(); }

namespace gazebo {
class SensorProbe : public SensorPlugin {
 public:
  void Load(sensors::SensorPtr _sensor, sdf::ElementPtr _sdf) override {
    this->sensor = _sensor;
    Put("loaded", 1);
    Put("gazebo_major", GAZEBO_MAJOR_VERSION);
    // Gazebo's <plugin> sits in its <sensor>
    Put("sdf_parent_is_my_sensor", _sdf->GetParent() && _sdf->GetParent()->GetName() == "sensor" &&
                                       _sdf->GetParent()->Get<std::string>("name") == _sensor->Name());
    if (!_sdf->HasElement("inactive")) this->sensor->SetActive(true);
    this->updated = this->sensor->ConnectUpdated([this] { OnUpdate(); });
    if (auto camera = std::dynamic_pointer_cast<sensors::CameraSensor>(_sensor)) {
      this->frame = camera->Camera()->ConnectNewImageFrame(
          [this](const unsigned char* _image, unsigned int _width, unsigned int _height, unsigned int _depth,
                 const std::string&) {
            Put("frames", Get("frames") + 1);
            Put("frame_width", _width);
            Put("frame_height", _height);
            Put("frame_depth", _depth);
            Put("frame_first_b", _image[2]);
          });
    }
  }

 private:
  void OnUpdate() {
    Put("updates", Get("updates") + 1);
    Put("time", this->sensor->LastUpdateTime().Double());
    if (auto ray = std::dynamic_pointer_cast<sensors::RaySensor>(this->sensor)) {
      std::vector<double> ranges;
      ray->Ranges(ranges);
      Put("ranges", ranges.size());
      Put("range_count", ray->RangeCount());
      Put("angle_min", ray->AngleMin().Radian());
      Put("angle_resolution", ray->AngleResolution());
      Put("range_max", ray->RangeMax());
      for (size_t i = 0; i < ranges.size(); ++i) Put("range" + std::to_string(i), ray->Range(i));
    }
    if (auto contact = std::dynamic_pointer_cast<sensors::ContactSensor>(this->sensor)) {
      const msgs::Contacts contacts = contact->Contacts();
      Put("contacts", contacts.contact_size());
      if (contacts.contact_size() > 0) {
        const msgs::Contact& c = contacts.contact(0);
        Put("points", c.position_size());
        double min_nz = 1e9, min_depth = 1e9, max_depth = -1e9, fz = 0;
        for (int j = 0; j < c.position_size(); ++j) {
          min_nz = std::min(min_nz, c.normal(j).z());
          min_depth = std::min(min_depth, c.depth(j));
          max_depth = std::max(max_depth, c.depth(j));
          fz += c.wrench(j).body_1_wrench().force().z();
        }
        Put("normal_z_min", min_nz);
        Put("depth_min", min_depth);
        Put("depth_max", max_depth);
        Put("force_z", fz);
        Put("collision1_is_mine", c.collision1().find(this->sensor->ParentName()) == 0);
      }
    }
    if (auto imu = std::dynamic_pointer_cast<sensors::ImuSensor>(this->sensor)) {
      Put("acc_x", imu->LinearAcceleration().X());
      Put("acc_y", imu->LinearAcceleration().Y());
      Put("acc_z", imu->LinearAcceleration().Z());
      Put("gyro_z", imu->AngularVelocity().Z());
      Put("orientation_w", imu->Orientation().W());
    }
    if (auto camera = std::dynamic_pointer_cast<sensors::CameraSensor>(this->sensor)) {
      Put("width", camera->ImageWidth());
      Put("height", camera->ImageHeight());
      const unsigned char* data = camera->ImageData();
      // the centre pixel's r g b (3 bytes a pixel)
      const size_t centre = 3 * (static_cast<size_t>(camera->ImageHeight() / 2) * camera->ImageWidth() +
                                 camera->ImageWidth() / 2);
      Put("centre_r", data[centre]);
      Put("centre_g", data[centre + 1]);
      Put("centre_b", data[centre + 2]);
    }
    if (auto depth = std::dynamic_pointer_cast<sensors::DepthCameraSensor>(this->sensor)) {
      const float* d = depth->DepthData();
      Put("centre_depth", d[(depth->ImageHeight() / 2) * depth->ImageWidth() + depth->ImageWidth() / 2]);
    }
  }
  void Put(const std::string& _what, double _v) { g_values[this->sensor->Name() + "/" + _what] = _v; }
  double Get(const std::string& _what) {
    const auto it = g_values.find(this->sensor->Name() + "/" + _what);
    return it == g_values.end() ? 0.0 : it->second;
  }
  sensors::SensorPtr sensor;
  event::ConnectionPtr updated, frame;
};
GZ_REGISTER_SENSOR_PLUGIN(SensorProbe)
}  // namespace gazebo
