// The test plug-ins' event log: "WHAT@SIMTIME" entries, space-separated, that a test reads back through the
// plug-in's extern "C" accessor (time_reset.cc, world_events.cc, forces.cc).
#pragma once

#include <sstream>
#include <string>

namespace car_test {

// Appends `what` at the world's sim time [s], and "/EVENT_TIME" [s] when event_time >= 0 (an event that carries
// its own time, e.g. WorldUpdateBegin's UpdateInfo::simTime).
inline void log_event(std::string& log, const std::string& what, double sim_time, double event_time = -1.0) {
  std::ostringstream os;
  os << what << "@" << sim_time;
  if (event_time >= 0) os << "/" << event_time;
  log += (log.empty() ? "" : " ") + os.str();
}

}  // namespace car_test
