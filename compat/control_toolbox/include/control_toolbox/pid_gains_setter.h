// control_toolbox::PidGainsSetter for Debian, which does not package control_toolbox: the interface of
// control_toolbox 1.19.0 (include/control_toolbox/pid_gains_setter.h), written for car from upstream's behaviour.
// advertise(n) offers the service "set_gains" (control_toolbox/SetPidGains) in n's namespace; a call sets every
// added Pid's gains to p, i, d, [-i_clamp, i_clamp], antiwindup and writes p, i, d, i_clamp, antiwindup as
// parameters there.
#ifndef CONTROL_TOOLBOX__PID_GAINS_SETTER_H
#define CONTROL_TOOLBOX__PID_GAINS_SETTER_H

#include <control_toolbox/SetPidGains.h>
#include <control_toolbox/pid.h>
#include <ros/node_handle.h>

#include <string>
#include <vector>

namespace control_toolbox {

class PidGainsSetter {
 public:
  PidGainsSetter() {}
  ~PidGainsSetter();
  // Adds a Pid (not owned) to those the service sets; returns this setter, so that adds chain.
  PidGainsSetter& add(Pid* pid);
  void advertise(const ros::NodeHandle& n);
  void advertise(const std::string& ns) { advertise(ros::NodeHandle(ns)); }
  bool setGains(control_toolbox::SetPidGains::Request& req, control_toolbox::SetPidGains::Response& resp);

 private:
  ros::NodeHandle node_;
  ros::ServiceServer serve_set_gains_;
  std::vector<Pid*> pids_;
};

}  // namespace control_toolbox

#endif  // CONTROL_TOOLBOX__PID_GAINS_SETTER_H
