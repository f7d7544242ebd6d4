// gazebo_plugins' GazeboRos for car's drop-in (see include/gazebo_plugins/gazebo_ros_utils.h for the behaviour).
#include <gazebo_plugins/gazebo_ros_utils.h>

#include <ros/console.h>

namespace gazebo {

GazeboRos::GazeboRos(physics::ModelPtr& _parent, sdf::ElementPtr _sdf, const std::string& _plugin)
    : sdf_(_sdf), plugin_(_plugin) {
  namespace_ = _parent->GetName();
  if (!sdf_->HasElement("robotNamespace")) {
    ROS_INFO_NAMED("utils", "%s missing <robotNamespace>, defaults is %s", plugin_.c_str(), namespace_.c_str());
  } else {
    const std::string written = sdf_->GetElement("robotNamespace")->Get<std::string>();
    if (!written.empty()) namespace_ = written;
  }
  if (!namespace_.empty()) namespace_ += "/";
  rosnode_.reset(new ros::NodeHandle(namespace_));
  info_text = plugin_ + "(ns = " + namespace_ + ")";
  readCommonParameter();
}

#ifdef CAR_GAZEBO_ROS_UTILS_SENSORS
GazeboRos::GazeboRos(sensors::SensorPtr _parent, sdf::ElementPtr _sdf, const std::string& _plugin)
    : sdf_(_sdf), plugin_(_plugin) {
  std::stringstream how;
  if (!sdf_->HasElement("robotNamespace")) {
    how << "the 'robotNamespace' param did not exit";
  } else {
    namespace_ = sdf_->Get<std::string>("robotNamespace");
    if (namespace_.empty()) {
      how << "the 'robotNamespace' param was empty";
      namespace_ = GetModelName(_parent);
    } else {
      how << "Using the 'robotNamespace' param: '" << namespace_ << "'";
    }
  }
  rosnode_.reset(new ros::NodeHandle(namespace_));
  info_text = plugin_ + "(ns = " + namespace_ + ")";
  ROS_INFO_NAMED("utils", "%s: %s", info_text.c_str(), how.str().c_str());
  readCommonParameter();
}
#endif

const char* GazeboRos::info() const { return info_text.c_str(); }

boost::shared_ptr<ros::NodeHandle>& GazeboRos::node() { return rosnode_; }

const boost::shared_ptr<ros::NodeHandle>& GazeboRos::node() const { return rosnode_; }

std::string GazeboRos::resolveTF(const std::string& _name) {
  if (!_name.empty() && _name[0] == '/') return _name.substr(1);
  if (tf_prefix_.empty()) return _name;
  return (tf_prefix_[0] == '/' ? tf_prefix_.substr(1) : tf_prefix_) + "/" + _name;
}

void GazeboRos::readCommonParameter() {
  ROS_INFO_NAMED("utils", "Starting plugin %s", info());
  std::string level;
  getParameter<std::string>(level, "rosDebugLevel", "na");
  // the default logger's level, by name in any case; another value leaves it
  const std::map<std::string, ros::console::levels::Level> levels = {
      {"debug", ros::console::levels::Debug}, {"info", ros::console::levels::Info},
      {"warn", ros::console::levels::Warn},   {"error", ros::console::levels::Error},
      {"fatal", ros::console::levels::Fatal}};
  const auto found = levels.find(boost::algorithm::to_lower_copy(level));
  if (found != levels.end() && ros::console::set_logger_level(ROSCONSOLE_DEFAULT_NAME, found->second))
    ros::console::notifyLoggerLevelsChanged();
  if (sdf_->HasElement("rosDebugLevel"))
    ROS_INFO_NAMED("utils", "%s: <rosDebugLevel> = %s", info(), level.c_str());
  // tf::getPrefixParam: tf_prefix searched upwards from the namespace
  std::string key;
  tf_prefix_.clear();
  if (rosnode_->searchParam("tf_prefix", key)) rosnode_->getParam(key, tf_prefix_);
  ROS_INFO_NAMED("utils", "%s: <tf_prefix> = %s", info(), tf_prefix_.c_str());
}

void GazeboRos::getParameterBoolean(bool& _value, const char* _tag_name, const bool& _default) {
  _value = _default;
  if (sdf_->HasElement(_tag_name)) {
    getParameterBoolean(_value, _tag_name);
    return;
  }
  ROS_WARN_NAMED("utils", "%s: missing <%s> default is %s", info(), _tag_name, _default ? "true" : "false");
}

void GazeboRos::getParameterBoolean(bool& _value, const char* _tag_name) {
  if (sdf_->HasElement(_tag_name)) {
    const std::string text = sdf_->GetElement(_tag_name)->Get<std::string>();
    if (boost::iequals(text, "true") || text == "1")
      _value = true;
    else if (boost::iequals(text, "false") || text == "0")
      _value = false;
    else
      ROS_WARN_NAMED("utils", "%s: <%s> must be either true or false but is '%s'", info(), _tag_name, text.c_str());
  }
  ROS_DEBUG_NAMED("utils", "%s: <%s> = %s", info(), _tag_name, _value ? "true" : "false");
}

physics::JointPtr GazeboRos::getJoint(physics::ModelPtr& _parent, const char* _tag_name,
                                      const std::string& _joint_default_name) {
  std::string name;
  getParameter<std::string>(name, _tag_name, _joint_default_name);
  physics::JointPtr joint = _parent->GetJoint(name);
  if (!joint) gzthrow(info() << ": couldn't get wheel hinge joint named " << name);
  return joint;
}

void GazeboRos::isInitialized() {
  if (ros::isInitialized()) return;
  ROS_FATAL_STREAM(info() << "A ROS node for Gazebo has not been initialized, unable to load plugin. "
                          << "Load the Gazebo system plugin 'libgazebo_ros_api_plugin.so' in the gazebo_ros package)");
}

}  // namespace gazebo
