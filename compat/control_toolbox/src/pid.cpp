// control_toolbox::Pid, as control_toolbox 1.19.0 behaves (car's docs/COMPAT-control.md "control_toolbox").
#include <control_toolbox/pid.h>

#include <tinyxml.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace control_toolbox {

namespace {

// upstream's namespace for dynamic_reconfigure when no node handle is given
const char* const kDefaultNamespace = "pid";

// boost::algorithm::clamp without its assertion (upstream builds with NDEBUG): lo wins when the bounds cross
double clamp(double v, double lo, double hi) { return v < lo ? lo : (hi < v ? hi : v); }

bool bad(double v) { return std::isnan(v) || std::isinf(v); }

}  // namespace

Pid::Pid(double p, double i, double d, double i_max, double i_min, bool antiwindup) {
  setGains(p, i, d, i_max, i_min, antiwindup);
  reset();
}

Pid::Pid(const Pid& source) {
  gains_ = source.lockedGains();
  reset();
}

Pid::~Pid() = default;

Pid& Pid::operator=(const Pid& source) {
  if (this == &source) return *this;
  const Gains g = source.lockedGains();
  {
    std::lock_guard<std::mutex> lock(gains_mutex_);
    gains_ = g;
  }
  reset();
  return *this;
}

void Pid::initPid(double p, double i, double d, double i_max, double i_min, bool antiwindup) {
  setGains(p, i, d, i_max, i_min, antiwindup);
  reset();
}

void Pid::initPid(double p, double i, double d, double i_max, double i_min, const ros::NodeHandle& /*node*/) {
  initPid(p, i, d, i_max, i_min);
  ros::NodeHandle nh(kDefaultNamespace);
  initDynamicReconfig(nh);
}

void Pid::initPid(double p, double i, double d, double i_max, double i_min, bool antiwindup,
                  const ros::NodeHandle& /*node*/) {
  initPid(p, i, d, i_max, i_min, antiwindup);
  ros::NodeHandle nh(kDefaultNamespace);
  initDynamicReconfig(nh);
}

bool Pid::initParam(const std::string& prefix, const bool quiet) {
  ros::NodeHandle nh(prefix);
  return init(nh, quiet);
}

bool Pid::init(const ros::NodeHandle& node, const bool quiet) {
  ros::NodeHandle nh(node);
  Gains gains;
  // p is required; i and d default to 0
  if (!nh.getParam("p", gains.p_gain_)) {
    if (!quiet) ROS_ERROR("No p gain specified for pid.  Namespace: %s", nh.getNamespace().c_str());
    return false;
  }
  nh.param("i", gains.i_gain_, 0.0);
  nh.param("d", gains.d_gain_, 0.0);
  // i_clamp gives both bounds; i_clamp_min and i_clamp_max override one each, signs forced (min <= 0 <= max)
  double i_clamp;
  nh.param("i_clamp", i_clamp, 0.0);
  gains.i_max_ = std::abs(i_clamp);
  gains.i_min_ = -std::abs(i_clamp);
  if (nh.hasParam("i_clamp_min")) {
    nh.param("i_clamp_min", gains.i_min_, gains.i_min_);
    gains.i_min_ = -std::abs(gains.i_min_);
  }
  if (nh.hasParam("i_clamp_max")) {
    nh.param("i_clamp_max", gains.i_max_, gains.i_max_);
    gains.i_max_ = std::abs(gains.i_max_);
  }
  nh.param("antiwindup", gains.antiwindup_, false);
  nh.param("publish_state", publish_state_, false);
  if (publish_state_) state_publisher_.reset(new ros::Publisher(nh.advertise<control_msgs::PidState>("state", 1)));
  setGains(gains);
  reset();
  initDynamicReconfig(nh);
  return true;
}

bool Pid::initXml(TiXmlElement* config) {
  ros::NodeHandle nh(kDefaultNamespace);
  const auto attr = [config](const char* name) {
    const char* v = config->Attribute(name);
    return v ? std::atof(v) : 0.0;
  };
  const double i_clamp = attr("iClamp");
  setGains(attr("p"), attr("i"), attr("d"), std::abs(i_clamp), -std::abs(i_clamp), attr("antiwindup") != 0.0);
  reset();
  initDynamicReconfig(nh);
  return true;
}

void Pid::initDynamicReconfig(ros::NodeHandle& node) {
  ROS_DEBUG_STREAM_NAMED("pid", "Initializing dynamic reconfigure in namespace " << node.getNamespace());
  param_reconfig_server_.reset(new DynamicReconfigServer(param_reconfig_mutex_, node));
  dynamic_reconfig_initialized_ = true;
  // the server starts from this Pid's gains, then each reconfiguration sets them
  updateDynamicReconfig();
  param_reconfig_callback_ = [this](control_toolbox::ParametersConfig& config, uint32_t level) {
    dynamicReconfigCallback(config, level);
  };
  param_reconfig_server_->setCallback(param_reconfig_callback_);
}

void Pid::reset() {
  reset(0.0, 0.0);
  // as upstream: the first computeCommand(error, dt) after reset() differentiates from a last error of 0
  valid_p_error_last_ = true;
}

void Pid::reset(double d_error, double i_error) {
  p_error_last_ = 0.0;
  p_error_ = 0.0;
  i_error_ = i_error;
  d_error_ = d_error;
  cmd_ = 0.0;
  valid_p_error_last_ = false;
}

void Pid::getGains(double& p, double& i, double& d, double& i_max, double& i_min) {
  bool antiwindup;
  getGains(p, i, d, i_max, i_min, antiwindup);
}

void Pid::getGains(double& p, double& i, double& d, double& i_max, double& i_min, bool& antiwindup) {
  const Gains g = getGains();
  p = g.p_gain_;
  i = g.i_gain_;
  d = g.d_gain_;
  i_max = g.i_max_;
  i_min = g.i_min_;
  antiwindup = g.antiwindup_;
}

Pid::Gains Pid::getGains() { return lockedGains(); }

Pid::Gains Pid::lockedGains() const {
  std::lock_guard<std::mutex> lock(gains_mutex_);
  return gains_;
}

void Pid::setGains(double p, double i, double d, double i_max, double i_min, bool antiwindup) {
  setGains(Gains(p, i, d, i_max, i_min, antiwindup));
}

void Pid::setGains(const Gains& gains) {
  {
    std::lock_guard<std::mutex> lock(gains_mutex_);
    gains_ = gains;
  }
  updateDynamicReconfig(gains);
}

void Pid::updateDynamicReconfig() {
  if (!dynamic_reconfig_initialized_) return;
  updateDynamicReconfig(getGains());
}

void Pid::updateDynamicReconfig(Gains gains_config) {
  if (!dynamic_reconfig_initialized_) return;
  control_toolbox::ParametersConfig config;
  config.p = gains_config.p_gain_;
  config.i = gains_config.i_gain_;
  config.d = gains_config.d_gain_;
  config.i_clamp_max = gains_config.i_max_;
  config.i_clamp_min = gains_config.i_min_;
  config.antiwindup = gains_config.antiwindup_;
  updateDynamicReconfig(config);
}

void Pid::updateDynamicReconfig(control_toolbox::ParametersConfig config) {
  if (!dynamic_reconfig_initialized_) return;
  boost::recursive_mutex::scoped_lock lock(param_reconfig_mutex_);
  param_reconfig_server_->updateConfig(config);
}

void Pid::dynamicReconfigCallback(control_toolbox::ParametersConfig& config, uint32_t /*level*/) {
  ROS_DEBUG_STREAM_NAMED("pid", "Dynamics reconfigure callback recieved.");
  setGains(config.p, config.i, config.d, config.i_clamp_max, config.i_clamp_min, config.antiwindup);
}

double Pid::computeCommand(double error, ros::Duration dt) {
  if (dt == ros::Duration(0.0) || bad(error)) return 0.0;
  double error_dot = d_error_;
  // [1/s] the derivative from the last error, once there is one; a negative dt keeps the last derivative
  if (dt.toSec() > 0.0) {
    if (valid_p_error_last_) error_dot = (error - p_error_last_) / dt.toSec();
    p_error_last_ = error;
    valid_p_error_last_ = true;
  }
  return computeCommand(error, error_dot, dt);
}

double Pid::updatePid(double error, ros::Duration dt) { return -computeCommand(error, dt); }

double Pid::computeCommand(double error, double error_dot, ros::Duration dt) {
  const Gains g = getGains();
  // as upstream, the errors are taken before the checks
  p_error_ = error;
  d_error_ = error_dot;
  if (dt == ros::Duration(0.0) || bad(error) || bad(error_dot)) return 0.0;

  const double p_term = g.p_gain_ * p_error_;
  i_error_ += dt.toSec() * p_error_;
  // antiwindup: the integral itself stays within the bounds of the term
  if (g.antiwindup_ && g.i_gain_ != 0) {
    const double a = g.i_min_ / g.i_gain_, b = g.i_max_ / g.i_gain_;
    i_error_ = clamp(i_error_, std::min(a, b), std::max(a, b));
  }
  double i_term = g.i_gain_ * i_error_;
  // otherwise only the term is bounded, and the integral winds up behind it
  if (!g.antiwindup_) i_term = clamp(i_term, g.i_min_, g.i_max_);
  const double d_term = g.d_gain_ * d_error_;
  cmd_ = p_term + i_term + d_term;

  if (publish_state_ && state_publisher_) {
    state_msg_.header.stamp = ros::Time::now();
    state_msg_.timestep = dt;
    state_msg_.error = error;
    state_msg_.error_dot = error_dot;
    state_msg_.p_error = p_error_;
    state_msg_.i_error = i_error_;
    state_msg_.d_error = d_error_;
    state_msg_.p_term = p_term;
    state_msg_.i_term = i_term;
    state_msg_.d_term = d_term;
    state_msg_.i_max = g.i_max_;
    state_msg_.i_min = g.i_min_;
    state_msg_.output = cmd_;
    state_publisher_->publish(state_msg_);
  }
  return cmd_;
}

double Pid::updatePid(double error, double error_dot, ros::Duration dt) {
  return -computeCommand(error, error_dot, dt);
}

void Pid::setCurrentCmd(double cmd) { cmd_ = cmd; }

double Pid::getCurrentCmd() { return cmd_; }

void Pid::getCurrentPIDErrors(double* pe, double* ie, double* de) {
  *pe = p_error_;
  *ie = i_error_;
  *de = d_error_;
}

void Pid::printValues() {
  const Gains g = getGains();
  ROS_INFO_STREAM_NAMED("pid", "Current Values of PID Class:\n"
                                   << "  P Gain: " << g.p_gain_ << "\n"
                                   << "  I Gain: " << g.i_gain_ << "\n"
                                   << "  D Gain: " << g.d_gain_ << "\n"
                                   << "  I_Max:  " << g.i_max_ << "\n"
                                   << "  I_Min:  " << g.i_min_ << "\n"
                                   << "  Antiwindup:  " << g.antiwindup_ << "\n"
                                   << "  P_Error_Last: " << p_error_last_ << "\n"
                                   << "  P_Error:      " << p_error_ << "\n"
                                   << "  I_Error:       " << i_error_ << "\n"
                                   << "  D_Error:      " << d_error_ << "\n"
                                   << "  Command:      " << cmd_);
}

}  // namespace control_toolbox
