// Test plug-in: a model plug-in that looks its sensors up through SensorManager in Load, as Kobuki's does: each
// <sensor_name> by the name as written (a leaf or a scoped name), logging what it found; it activates the ray
// sensors it finds and logs their first range at each WorldUpdateEnd. The test reads car_test_finder_log().
#include <gazebo/gazebo.hh>
#include <gazebo/physics/physics.hh>
#include <gazebo/sensors/sensors.hh>

#include <sstream>
#include <string>
#include <vector>

namespace {
std::string g_log;
double g_last = -1;  // [m] the first range of the last ray sensor with a scan, at the last WorldUpdateEnd
}

extern "C" GZ_PLUGIN_VISIBLE const char* car_test_finder_log() { return g_log.c_str(); }
extern "C" GZ_PLUGIN_VISIBLE double car_test_finder_last_range() { return g_last; }

namespace gazebo {
class SensorFinder : public ModelPlugin {
 public:
  void Load(physics::ModelPtr, sdf::ElementPtr _sdf) override {
    std::ostringstream os;
    g_last = -1;
    // its model's name as Kobuki's plug-in takes it: the <plugin>'s parent <model name>
    os << "model=" << _sdf->GetParent()->Get<std::string>("name") << " ";
    for (sdf::ElementPtr e = _sdf->HasElement("sensor_name") ? _sdf->GetElement("sensor_name") : nullptr; e;
         e = e->GetNextElement("sensor_name")) {
      const std::string name = e->Get<std::string>();
      sensors::SensorPtr s = sensors::SensorManager::Instance()->GetSensor(name);
      os << name << "=";
      if (!s) {
        os << "none ";
        continue;
      }
      os << s->ScopedName() << "," << s->Type() << "," << s->ParentName() << "," << (s->IsActive() ? "on" : "off")
         << " ";
      if (auto ray = std::dynamic_pointer_cast<sensors::RaySensor>(s)) {
        ray->SetActive(true);
        this->rays.push_back(ray);
      }
    }
    g_log = os.str();
    this->end = event::Events::ConnectWorldUpdateEnd([this] {
      for (const auto& r : this->rays) {
        std::vector<double> ranges;
        r->Ranges(ranges);
        if (!ranges.empty()) g_last = ranges[0];
      }
    });
  }

 private:
  std::vector<sensors::RaySensorPtr> rays;
  event::ConnectionPtr end;
};
GZ_REGISTER_MODEL_PLUGIN(SensorFinder)
}  // namespace gazebo
