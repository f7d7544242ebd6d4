// Test plug-in: a model plug-in that reads its settings through GazeboRos (gazebo_plugins/gazebo_ros_utils.h), as
// gazebo_ros_diff_drive does, and prints what it got on one gzmsg line (test/test_gazebo_ros_utils.cpp reads it).
#include <gazebo/common/common.hh>
#include <gazebo/gazebo.hh>
#include <gazebo/physics/physics.hh>
#include <gazebo_plugins/gazebo_ros_utils.h>

#include <map>
#include <string>

namespace gazebo {
class UtilsProbe : public ModelPlugin {
 public:
  void Load(physics::ModelPtr _model, sdf::ElementPtr _sdf) override {
    GazeboRosPtr ros(new GazeboRos(_model, _sdf, "UtilsProbe"));
    ros->isInitialized();
    double rate = 0.0;
    ros->getParameter<double>(rate, "updateRate", 50.0);
    std::string topic;
    ros->getParameter<std::string>(topic, "commandTopic", "cmd_vel");
    bool tf = false;
    ros->getParameterBoolean(tf, "publishTf", true);
    int source = -1;
    const std::map<std::string, int> sources = {{"encoder", 0}, {"world", 1}};
    ros->getParameter<int>(source, "odometrySource", sources, 1);
    physics::JointPtr joint = ros->getJoint(_model, "leftJoint", "axle");
    gzmsg << "info=" << ros->info() << " ns=" << ros->node()->getNamespace() << " rate=" << rate
          << " topic=" << topic << " tf=" << tf << " source=" << source << " joint=" << joint->GetName()
          << " frame=" << ros->resolveTF("odom") << "\n";
  }
};
GZ_REGISTER_MODEL_PLUGIN(UtilsProbe)
}  // namespace gazebo
