// control_toolbox::Pid for Debian, which does not package control_toolbox: the interface of control_toolbox 1.19.0
// (ros-controls/control_toolbox noetic-devel, include/control_toolbox/pid.h), written for car from upstream's
// behaviour (car's docs/COMPAT-control.md "control_toolbox"). No upstream code is in this file.
//
// command = p_term + i_term + d_term, with error = target - state:
//   p_term = p * error
//   i_error += error * dt; i_term = i * i_error, clamped to [i_min, i_max] (antiwindup false: i_error itself keeps
//            growing); antiwindup true: i_error is clamped to [i_min / i, i_max / i] before the product
//   d_term = d * error_dot, error_dot = (error - last error) / dt in computeCommand(error, dt)
// dt 0, or a NaN or infinite error (or error_dot), gives 0 and leaves the state as it was.
#ifndef CONTROL_TOOLBOX__PID_H
#define CONTROL_TOOLBOX__PID_H

#include <control_msgs/PidState.h>
#include <control_toolbox/ParametersConfig.h>
#include <dynamic_reconfigure/server.h>
#include <ros/ros.h>

#include <boost/shared_ptr.hpp>
#include <boost/thread/recursive_mutex.hpp>
#include <mutex>
#include <string>

class TiXmlElement;

namespace control_toolbox {

class Pid {
 public:
  // The gains: p, i, d and the bounds [i_min, i_max] of the integral term.
  struct Gains {
    Gains(double p, double i, double d, double i_max, double i_min)
        : p_gain_(p), i_gain_(i), d_gain_(d), i_max_(i_max), i_min_(i_min), antiwindup_(false) {}
    Gains(double p, double i, double d, double i_max, double i_min, bool antiwindup)
        : p_gain_(p), i_gain_(i), d_gain_(d), i_max_(i_max), i_min_(i_min), antiwindup_(antiwindup) {}
    Gains() : p_gain_(0.0), i_gain_(0.0), d_gain_(0.0), i_max_(0.0), i_min_(0.0), antiwindup_(false) {}
    double p_gain_;
    double i_gain_;
    double d_gain_;
    double i_max_;
    double i_min_;
    bool antiwindup_;
  };

  Pid(double p = 0.0, double i = 0.0, double d = 0.0, double i_max = 0.0, double i_min = -0.0,
      bool antiwindup = false);
  // Copies the gains only: the copy starts reset, without the dynamic_reconfigure server or the state topic.
  Pid(const Pid& source);
  ~Pid();

  // Sets the gains and resets.
  void initPid(double p, double i, double d, double i_max, double i_min, bool antiwindup = false);
  // As above, and starts dynamic_reconfigure in the namespace "pid" (the node handle is not used, as upstream).
  void initPid(double p, double i, double d, double i_max, double i_min, const ros::NodeHandle& /*node*/);
  void initPid(double p, double i, double d, double i_max, double i_min, bool antiwindup,
               const ros::NodeHandle& /*node*/);
  // init(ros::NodeHandle(prefix), quiet).
  bool initParam(const std::string& prefix, const bool quiet = false);
  // Reads p (required: false and, unless quiet, "No p gain specified for pid.  Namespace: NS"), i, d, i_clamp,
  // i_clamp_min, i_clamp_max, antiwindup and publish_state from the node handle's namespace, resets, starts
  // dynamic_reconfigure there and, with publish_state, the topic "state" (control_msgs/PidState).
  bool init(const ros::NodeHandle& n, const bool quiet = false);
  // Attributes p, i, d, iClamp, antiwindup of an XML element (absent: 0); dynamic_reconfigure in "pid".
  bool initXml(TiXmlElement* config);
  void initDynamicReconfig(ros::NodeHandle& node);

  // Zeroes the errors and the command; the next computeCommand(error, dt) takes error / dt as the derivative.
  void reset();
  // Sets the derivative and integral errors, zeroes the rest; the next computeCommand(error, dt) keeps d_error.
  void reset(double d_error, double i_error);

  void getGains(double& p, double& i, double& d, double& i_max, double& i_min);
  void getGains(double& p, double& i, double& d, double& i_max, double& i_min, bool& antiwindup);
  Gains getGains();
  void setGains(double p, double i, double d, double i_max, double i_min, bool antiwindup = false);
  void setGains(const Gains& gains);

  void updateDynamicReconfig();
  void updateDynamicReconfig(Gains gains_config);
  void updateDynamicReconfig(control_toolbox::ParametersConfig config);
  void dynamicReconfigCallback(control_toolbox::ParametersConfig& config, uint32_t /*level*/);

  // The command for error (target - state) over dt, the derivative from the last error.
  double computeCommand(double error, ros::Duration dt);
  // The command for error and its derivative error_dot over dt.
  double computeCommand(double error, double error_dot, ros::Duration dt);
  // -computeCommand(...) (error = state - target).
  ROS_DEPRECATED double updatePid(double p_error, ros::Duration dt);
  ROS_DEPRECATED double updatePid(double error, double error_dot, ros::Duration dt);

  void setCurrentCmd(double cmd);
  double getCurrentCmd();
  void getCurrentPIDErrors(double* pe, double* ie, double* de);
  // Logs the gains, the errors and the command (ROS_INFO, logger "pid").
  void printValues();

  // Copies the gains only and resets, as the copy constructor.
  Pid& operator=(const Pid& source);

 private:
  // The gains, written by dynamic_reconfigure's thread and read by the control loop: copied under the lock.
  Gains gains_;
  mutable std::mutex gains_mutex_;
  Gains lockedGains() const;
  boost::shared_ptr<ros::Publisher> state_publisher_;
  control_msgs::PidState state_msg_;
  bool publish_state_ = false;

  bool valid_p_error_last_ = false;
  double p_error_last_ = 0.0;
  double p_error_ = 0.0;
  double i_error_ = 0.0;
  double d_error_ = 0.0;
  double cmd_ = 0.0;

  bool dynamic_reconfig_initialized_ = false;
  typedef dynamic_reconfigure::Server<control_toolbox::ParametersConfig> DynamicReconfigServer;
  boost::shared_ptr<DynamicReconfigServer> param_reconfig_server_;
  DynamicReconfigServer::CallbackType param_reconfig_callback_;
  boost::recursive_mutex param_reconfig_mutex_;
};

}  // namespace control_toolbox

#endif  // CONTROL_TOOLBOX__PID_H
