// libgazebo_ros_bumper.so on ROS: ContactsState (field-compatible with gazebo_msgs) on bumperTopicName under
// robotNamespace, header frame frameName, while subscribed.
#include <gazebo_msgs/ContactsState.h>

#include <sstream>

#include "../adapter.hpp"
#include "../conversions.hpp"
#include "bumper/bumper.hpp"

namespace car_ros {

namespace {

// The message types, in one place (gazebo_msgs drop-in: change these two lines).
using ContactsStateMsg = gazebo_msgs::ContactsState;
using ContactStateMsg = gazebo_msgs::ContactState;

geometry_msgs::Vector3 vec(const Eigen::Vector3d& v) {
  geometry_msgs::Vector3 m;
  m.x = v.x();
  m.y = v.y();
  m.z = v.z();
  return m;
}

geometry_msgs::Wrench wrench(const car_sim::Wrench& w) {
  geometry_msgs::Wrench m;
  m.force = vec(w.force);
  m.torque = vec(w.torque);
  return m;
}

class BumperAdapter : public Adapter {
 public:
  std::string setup(const car_sim::PluginInfo& p, const car_sim::RobotInfo& robot, NodeContext& node) override {
    frame_ = frame(p.config.text("frameName"));
    pub_ = node.nh().advertise<ContactsStateMsg>(
        topic_in(car_sim::plugin_robot_namespace(p.config, robot.name), p.config.text("bumperTopicName")), 1);
    return pub_.getTopic() + " (link " + p.config.link + ", frame " + frame_ + ")";
  }

  bool listened() const override { return pub_.getNumSubscribers() > 0; }

  void publish(const car_sim::Output& out, NodeContext& node) override {
    const auto& o = static_cast<const car_sim::ContactsOut&>(out);
    ContactsStateMsg m;
    m.header.stamp = node.stamp(o.tick);
    m.header.frame_id = frame_;
    for (size_t i = 0; i < o.states.size(); ++i) {
      const car_sim::ContactPair& c = o.states[i];
      ContactStateMsg s;
      s.collision1_name = c.collision1;
      s.collision2_name = c.collision2;
      std::ostringstream info;
      info << "Debug:  i:(" << i << "/" << o.states.size() << ")     my geom:" << c.collision1
           << "   other geom:" << c.collision2 << "         time:" << m.header.stamp << "\n";
      s.info = info.str();
      for (size_t k = 0; k < c.positions.size(); ++k) {
        s.wrenches.push_back(wrench(c.wrenches[k]));
        s.contact_positions.push_back(vec(c.positions[k]));
        s.contact_normals.push_back(vec(c.normals[k]));
        s.depths.push_back(c.depths[k]);
      }
      s.total_wrench = wrench(c.total);
      m.states.push_back(std::move(s));
    }
    node.publish(pub_, std::move(m));
  }

 private:
  std::string frame_;
  ros::Publisher pub_;
};

}  // namespace

std::unique_ptr<Adapter> make_bumper_adapter() { return std::make_unique<BumperAdapter>(); }

}  // namespace car_ros
