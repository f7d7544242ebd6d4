// velodyne_simulator's plug-ins on ROS: sensor_msgs/PointCloud2 (x y z intensity ring, point_step 32) on
// topicName under robotNamespace, frame tf::resolve(robotNamespace, frameName); published only while subscribed.
#include <sensor_msgs/PointCloud2.h>

#include <cstring>

#include "../adapter.hpp"
#include "../conversions.hpp"
#include "velodyne/velodyne.hpp"

namespace car_ros {

namespace {

// tf::resolve(prefix, frame): an absolute frame loses its '/', a relative one goes under the prefix.
std::string resolve_frame(const std::string& prefix, const std::string& f) {
  if (!f.empty() && f[0] == '/') return f.substr(1);
  const std::string p = frame(prefix);
  return p.empty() ? f : p + "/" + f;
}

class VelodyneAdapter : public Adapter {
 public:
  std::string setup(const car_sim::PluginInfo& p, const car_sim::RobotInfo& robot, NodeContext& node) override {
    // the node handle's namespace is robotNamespace (default "/"); it is also the frame prefix unless it is "/"
    std::string ns = car_sim::plugin_robot_namespace(p.config, robot.name);
    frame_ = resolve_frame(ns, p.config.text("frameName"));
    pub_ = node.nh().advertise<sensor_msgs::PointCloud2>(topic_in(ns, p.config.text("topicName")), 1);
    return pub_.getTopic();
  }

  bool listened() const override { return pub_.getNumSubscribers() > 0; }

  void publish(const car_sim::Output& out, NodeContext& node) override {
    const auto& o = static_cast<const car_sim::VelodyneOut&>(out);
    sensor_msgs::PointCloud2 m;
    m.header.stamp = node.stamp(o.tick);
    m.header.frame_id = frame_;
    const char* names[5] = {"x", "y", "z", "intensity", "ring"};
    const uint32_t offsets[5] = {0, 4, 8, 16, 20};
    for (int k = 0; k < 5; ++k) {
      sensor_msgs::PointField f;
      f.name = names[k];
      f.offset = offsets[k];
      f.datatype = k == 4 ? sensor_msgs::PointField::UINT16 : sensor_msgs::PointField::FLOAT32;
      f.count = 1;
      m.fields.push_back(f);
    }
    const size_t n = o.intensities.size();
    m.point_step = 32;
    m.row_step = static_cast<uint32_t>(32 * n);
    m.height = 1;
    m.width = static_cast<uint32_t>(n);
    m.is_bigendian = false;
    m.is_dense = true;
    m.data.assign(32 * n, 0);
    for (size_t i = 0; i < n; ++i) {
      uint8_t* p = m.data.data() + 32 * i;
      std::memcpy(p, &o.points[3 * i], 12);
      std::memcpy(p + 16, &o.intensities[i], 4);
      std::memcpy(p + 20, &o.rings[i], 2);
    }
    node.publish(pub_, std::move(m));
  }

 private:
  std::string frame_;
  ros::Publisher pub_;
};

}  // namespace

std::unique_ptr<Adapter> make_velodyne_adapter() { return std::make_unique<VelodyneAdapter>(); }

}  // namespace car_ros
