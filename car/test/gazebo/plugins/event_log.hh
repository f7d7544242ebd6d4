// The test plug-ins' logs, which a test reads back through the plug-in's extern "C" accessor: an event log of
// "WHAT@SIMTIME" entries, space-separated (time_reset.cc, world_events.cc, forces.cc), and a stream a plug-in writes
// and car_test_NAME_log() hands over (CAR_TEST_PLUGIN_LOG).
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

// At file scope, after the Gazebo includes (GZ_PLUGIN_VISIBLE): the plug-in's log g_log, and
// extern "C" const char* car_test_NAME_log(), which returns what was written since its last call and empties it.
#define CAR_TEST_PLUGIN_LOG(NAME)                                   \
  namespace {                                                       \
  std::ostringstream g_log;                                         \
  std::string g_text;                                               \
  }                                                                 \
  extern "C" GZ_PLUGIN_VISIBLE const char* car_test_##NAME##_log() { \
    g_text = g_log.str();                                           \
    g_log.str("");                                                  \
    return g_text.c_str();                                          \
  }
