// Test plug-in for Gazebo's RayPlugin base and a ray sensor's scan topic (docs/PLUGINS.md "Sensor plug-in bases"),
// written as gazebo_ros_laser is: a RayPlugin that switches its sensor off (SetActive(false)) and subscribes to the
// sensor's Topic() for msgs::LaserScanStamped. It logs, read through car_test_ray_plugin_probe_log():
//   topic=<Topic()> at load; each scan message as "scan@<sec>.<nsec> frame=<frame> count=<count> min=<angle_min>
//   step=<angle_step> range=<range_min>..<range_max> ranges=<r0>,<r1>,..."; and its number of OnNewLaserScans
//   calls through car_test_ray_plugin_probe_scans().
#include <gazebo/common/Plugin.hh>
#include <gazebo/plugins/RayPlugin.hh>
#include <gazebo/sensors/RaySensor.hh>
#include <gazebo/transport/transport.hh>

#include <sstream>
#include <string>

#include "event_log.hh"

CAR_TEST_PLUGIN_LOG(ray_plugin_probe)

namespace {
int g_scans = 0;
}  // namespace

extern "C" GZ_PLUGIN_VISIBLE int car_test_ray_plugin_probe_scans() {
  const int n = g_scans;
  g_scans = 0;
  return n;
}

namespace gazebo {
class RayPluginProbe : public RayPlugin {
 public:
  void Load(sensors::SensorPtr _parent, sdf::ElementPtr _sdf) override {
    RayPlugin::Load(_parent, _sdf);
    GAZEBO_SENSORS_USING_DYNAMIC_POINTER_CAST;
    ray = dynamic_pointer_cast<sensors::RaySensor>(_parent);
    g_log << "topic=" << ray->Topic() << " ";
    node = transport::NodePtr(new transport::Node());
    node->Init(_parent->WorldName());
    ray->SetActive(false);
    sub = node->Subscribe(ray->Topic(), &RayPluginProbe::OnScan, this);
  }
  void OnNewLaserScans() override { ++g_scans; }
  void OnScan(ConstLaserScanStampedPtr& _msg) {
    const msgs::LaserScan& s = _msg->scan();
    g_log << "scan@" << _msg->time().sec() << "." << _msg->time().nsec() << " frame=" << s.frame()
          << " count=" << s.count() << " min=" << s.angle_min() << " step=" << s.angle_step() << " range=" << s.range_min()
          << ".." << s.range_max() << " ranges=";
    for (int i = 0; i < s.ranges_size(); ++i) g_log << (i ? "," : "") << s.ranges(i);
    g_log << " ";
  }

 private:
  sensors::RaySensorPtr ray;
  transport::NodePtr node;
  transport::SubscriberPtr sub;
};
GZ_REGISTER_SENSOR_PLUGIN(RayPluginProbe)
}  // namespace gazebo
