// control_toolbox::PidGainsSetter, as control_toolbox 1.19.0 behaves.
#include <control_toolbox/pid_gains_setter.h>

#include <cassert>

namespace control_toolbox {

PidGainsSetter::~PidGainsSetter() { serve_set_gains_.shutdown(); }

PidGainsSetter& PidGainsSetter::add(Pid* pid) {
  assert(pid);
  pids_.push_back(pid);
  return *this;
}

void PidGainsSetter::advertise(const ros::NodeHandle& n) {
  node_ = n;
  serve_set_gains_ = node_.advertiseService("set_gains", &PidGainsSetter::setGains, this);
}

bool PidGainsSetter::setGains(control_toolbox::SetPidGains::Request& req,
                              control_toolbox::SetPidGains::Response& /*resp*/) {
  for (Pid* pid : pids_) pid->setGains(req.p, req.i, req.d, req.i_clamp, -req.i_clamp, req.antiwindup);
  node_.setParam("p", req.p);
  node_.setParam("i", req.i);
  node_.setParam("d", req.d);
  node_.setParam("i_clamp", req.i_clamp);
  node_.setParam("antiwindup", static_cast<bool>(req.antiwindup));
  return true;
}

}  // namespace control_toolbox
