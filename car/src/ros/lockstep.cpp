#include "lockstep.hpp"

#include <sstream>

#include "params.hpp"

namespace car_ros {

namespace {

// ~lockstep as a list of strings, or one string of pairs separated by commas or spaces.
std::vector<std::string> entries(ros::NodeHandle& pnh) {
  std::vector<std::string> out;
  XmlRpc::XmlRpcValue v;
  if (!pnh.getParam("lockstep", v)) return out;
  auto split = [&out](std::string s) {
    for (char& c : s)
      if (c == ',') c = ' ';
    std::istringstream in(s);
    std::string e;
    while (in >> e) out.push_back(e);
  };
  if (v.getType() == XmlRpc::XmlRpcValue::TypeString) {
    split(static_cast<std::string>(v));
  } else if (v.getType() == XmlRpc::XmlRpcValue::TypeArray) {
    for (int i = 0; i < v.size(); ++i) {
      if (v[i].getType() == XmlRpc::XmlRpcValue::TypeString)
        split(static_cast<std::string>(v[i]));
      else
        ROS_WARN("car: parameter ~lockstep: entry %d is not a string (left out)", i);
    }
  } else {
    ROS_WARN("car: parameter ~lockstep must be a string or a list of strings TRIGGER:RESPONSE (left out)");
  }
  return out;
}

}  // namespace

bool Lockstep::configure(ros::NodeHandle& nh, ros::NodeHandle& pnh) {
  nh_ = nh;
  double timeout = 5.0;
  if (!finite_param(pnh, "lockstep_timeout", 5.0, timeout) || timeout <= 0.0) {
    ROS_WARN("car: parameter ~lockstep_timeout must be > 0 [s], got %g: using 5", timeout);
    timeout = 5.0;
  }
  timeout_s_ = timeout;
  for (const std::string& e : entries(pnh)) {
    const size_t colon = e.find(':');
    if (colon == std::string::npos || colon == 0 || colon + 1 == e.size() ||
        e.find(':', colon + 1) != std::string::npos) {
      ROS_WARN("car: parameter ~lockstep: '%s' is not TRIGGER:RESPONSE (left out)", e.c_str());
      continue;
    }
    Pair p;
    p.trigger = nh_.resolveName(e.substr(0, colon));
    p.response = nh_.resolveName(e.substr(colon + 1));
    pairs_.push_back(std::move(p));
  }
  for (size_t i = 0; i < pairs_.size(); ++i) {
    subscribe(pairs_[i]);
    ROS_INFO("car: lockstep: after a step that publishes %s, wait for %s (at most %g s of wall time)",
             pairs_[i].trigger.c_str(), pairs_[i].response.c_str(), timeout_s_);
  }
  return enabled();
}

void Lockstep::subscribe(Pair& p) {
  const size_t i = static_cast<size_t>(&p - pairs_.data());
  // any type (md5 "*"), never deserialised; tcp_nodelay: an answer is one small message waited for
  p.sub = nh_.subscribe<topic_tools::ShapeShifter>(
      p.response, 100, [this, i](const topic_tools::ShapeShifter::ConstPtr&) { on_answer(i); },
      ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
}

void Lockstep::resubscribe() {
  // during a wait (a spawn service run while waiting) an answer queued for the old subscriber would be lost with
  // it: later, when the wait is over
  for (const Pair& p : pairs_)
    if (p.pending) {
      resubscribe_due_ = true;
      return;
    }
  resubscribe_due_ = false;
  for (Pair& p : pairs_) {
    ros::Subscriber old = p.sub;
    subscribe(p);
    old.shutdown();
  }
}

void Lockstep::on_answer(size_t i) {
  Pair& p = pairs_[i];
  ++p.answers;
  if (p.suspended) {
    p.suspended = false;
    ROS_INFO("car: lockstep: %s answers again: waiting for it after %s", p.response.c_str(), p.trigger.c_str());
  }
}

void Lockstep::published(const std::string& topic, uint32_t subscribers) {
  if (subscribers == 0) return;
  for (Pair& p : pairs_) {
    // someone must be able to answer: a node publishing the response to us
    if (p.trigger == topic && !p.suspended && p.sub.getNumPublishers() > 0) {
      p.fired = true;
      fired_ = true;
    }
  }
}

void Lockstep::begin(clock::time_point now, double stamp) {
  for (Pair& p : pairs_) {
    if (!p.fired) continue;
    p.fired = false;
    p.pending = true;
    p.answers_at_begin = p.answers;
    p.trigger_stamp = stamp;
  }
  fired_ = false;
  since_ = now;
}

bool Lockstep::waiting(clock::time_point now) {
  bool any = false;
  const bool late = now - since_ > std::chrono::duration<double>(timeout_s_);
  for (Pair& p : pairs_) {
    if (!p.pending) continue;
    if (p.answers > p.answers_at_begin) {
      p.pending = false;
    } else if (late) {
      p.pending = false;
      p.suspended = true;
      ROS_WARN("car: lockstep: nothing on %s within %g s of wall time after %s at sim time %.3f s: stepping on "
               "without waiting for %s until a message on it arrives",
               p.response.c_str(), timeout_s_, p.trigger.c_str(), p.trigger_stamp, p.response.c_str());
    } else {
      any = true;
    }
  }
  if (!any && resubscribe_due_) resubscribe();
  return any;
}

void Lockstep::reset() {
  for (Pair& p : pairs_) p.pending = p.fired = false;
  fired_ = false;
}

}  // namespace car_ros
