// gazebo_plugins' helper for plug-ins that talk ROS (car's drop-in; behaviour of gazebo_ros_pkgs noetic-devel,
// gazebo_plugins/include/gazebo_plugins/gazebo_ros_utils.h and src/gazebo_ros_utils.cpp; car/docs/PLUGINS.md
// "gazebo_plugins' own headers"). Written for car from that behaviour:
// - GazeboRos(model, sdf, plugin): the namespace is <robotNamespace>, or the model's name when the element is absent
//   or empty, with "/" added; a ros::NodeHandle on it; tf_prefix searched upwards from it; <rosDebugLevel> sets the
//   default logger's level.
// - getParameter: the element's value, or the default with the warning "PLUGIN(ns = NS/): missing <TAG> default is
//   VALUE"; with an options map, a value the map lacks warns "<TAG> no matching key to VALUE" and keeps the default.
// - getParameterBoolean: "true"/"1", "false"/"0" (any case); another value warns and keeps the default.
// - getJoint: the model's joint named by the element (or the default name); none: gzthrow.
// - isInitialized: ROS_FATAL when ros::init has not run (car's node has run it).
#pragma once

#include <boost/algorithm/string.hpp>
#include <boost/lexical_cast.hpp>
#include <boost/shared_ptr.hpp>
#include <gazebo/common/common.hh>
#include <gazebo/gazebo_config.h>
#include <gazebo/physics/physics.hh>
#include <map>
#include <ros/ros.h>
#include <sdf/sdf.hh>
#include <sstream>
#include <string>
#include <vector>

// car offers the sensor half (the constructor and helpers on a sensors::SensorPtr) where its Gazebo API has sensors.
#if __has_include(<gazebo/sensors/Sensor.hh>)
#include <gazebo/sensors/Sensor.hh>
#define CAR_GAZEBO_ROS_UTILS_SENSORS 1
#endif

#ifndef GAZEBO_SENSORS_USING_DYNAMIC_POINTER_CAST
// Gazebo 7 and later: sensor pointers are std::shared_ptr.
#define GAZEBO_SENSORS_USING_DYNAMIC_POINTER_CAST using std::dynamic_pointer_cast
#endif

namespace gazebo {

#ifdef CAR_GAZEBO_ROS_UTILS_SENSORS
// The model's name from a sensor's scoped name "WORLD::MODEL::LINK::SENSOR" (its second part); "" when it has fewer.
inline std::string GetModelName(const sensors::SensorPtr& parent) {
  std::string scoped = parent->ScopedName();
  boost::replace_all(scoped, "::", ",");
  std::vector<std::string> parts;
  boost::split(parts, scoped, boost::is_any_of(","));
  return parts.size() < 2 ? std::string() : parts[1];
}

// A sensor plug-in's <robotNamespace>: as written; empty: the model's name; absent: "". pInfo: logs which it was.
inline std::string GetRobotNamespace(const sensors::SensorPtr& parent, const sdf::ElementPtr& sdf,
                                     const char* pInfo = NULL) {
  std::string ns;
  std::stringstream how;
  if (!sdf->HasElement("robotNamespace")) {
    how << "The 'robotNamespace' param did not exit";
  } else {
    ns = sdf->Get<std::string>("robotNamespace");
    if (ns.empty()) {
      how << "The 'robotNamespace' param was empty";
      ns = GetModelName(parent);
    } else {
      how << "Using the 'robotNamespace' param: '" << ns << "'";
    }
  }
  if (pInfo != NULL) ROS_INFO_NAMED("utils", "%s Plugin: %s", pInfo, how.str().c_str());
  return ns;
}
#endif

class GazeboRos {
 public:
  // A model plug-in's: namespace <robotNamespace> (absent or empty: the model's name) with "/" added.
  GazeboRos(physics::ModelPtr& _parent, sdf::ElementPtr _sdf, const std::string& _plugin);
#ifdef CAR_GAZEBO_ROS_UTILS_SENSORS
  // A sensor plug-in's: namespace <robotNamespace> as written (empty: the model's name; absent: ""), no "/" added.
  GazeboRos(sensors::SensorPtr _parent, sdf::ElementPtr _sdf, const std::string& _plugin);
#endif

  // "PLUGIN(ns = NAMESPACE)", for log lines.
  const char* info() const;
  // The node handle on the namespace.
  boost::shared_ptr<ros::NodeHandle>& node();
  const boost::shared_ptr<ros::NodeHandle>& node() const;
  // tf::resolve(tf_prefix, _name): a leading "/" is dropped and takes no prefix; else "PREFIX/" in front when set.
  std::string resolveTF(const std::string& _name);
  void getParameterBoolean(bool& _value, const char* _tag_name, const bool& _default);
  void getParameterBoolean(bool& _value, const char* _tag_name);
  physics::JointPtr getJoint(physics::ModelPtr& _parent, const char* _tag_name, const std::string& _joint_default_name);
  void isInitialized();

  // The element's value, else _default with a warning.
  template <class T>
  void getParameter(T& _value, const char* _tag_name, const T& _default) {
    _value = _default;
    if (sdf_->HasElement(_tag_name)) {
      getParameter<T>(_value, _tag_name);
      return;
    }
    ROS_WARN_NAMED("utils", "%s: missing <%s> default is %s", info(), _tag_name,
                   boost::lexical_cast<std::string>(_default).c_str());
  }

  // The element's value when there is one; _value is left as it is otherwise.
  template <class T>
  void getParameter(T& _value, const char* _tag_name) {
    if (sdf_->HasElement(_tag_name)) _value = sdf_->GetElement(_tag_name)->Get<T>();
    ROS_DEBUG_NAMED("utils", "%s: <%s> = %s", info(), _tag_name, boost::lexical_cast<std::string>(_value).c_str());
  }

  // The element's text looked up in _options, else _default (with a warning for an absent element).
  template <class T>
  void getParameter(T& _value, const char* _tag_name, const std::map<std::string, T>& _options, const T& _default) {
    _value = _default;
    if (sdf_->HasElement(_tag_name)) {
      getParameter<T>(_value, _tag_name, _options);
      return;
    }
    ROS_WARN_NAMED("utils", "%s: missing <%s> default is %s", info(), _tag_name,
                   boost::lexical_cast<std::string>(_default).c_str());
  }

  // The element's text looked up in _options; a text the map lacks warns and leaves _value as it is.
  template <class T>
  void getParameter(T& _value, const char* _tag_name, const std::map<std::string, T>& _options) {
    if (!sdf_->HasElement(_tag_name)) return;
    const std::string text = sdf_->GetElement(_tag_name)->Get<std::string>();
    const auto found = _options.find(text);
    if (found == _options.end()) {
      ROS_WARN_NAMED("utils", "%s: <%s> no matching key to %s", info(), _tag_name, text.c_str());
      return;
    }
    _value = found->second;
    ROS_DEBUG_NAMED("utils", "%s: <%s> = %s := %s", info(), _tag_name, found->first.c_str(),
                    boost::lexical_cast<std::string>(_value).c_str());
  }

 private:
  // <rosDebugLevel> and tf_prefix, read by the constructors.
  void readCommonParameter();

  sdf::ElementPtr sdf_;
  std::string plugin_;
  std::string namespace_;
  boost::shared_ptr<ros::NodeHandle> rosnode_;
  std::string tf_prefix_;
  std::string info_text;
};

typedef boost::shared_ptr<GazeboRos> GazeboRosPtr;

}  // namespace gazebo
