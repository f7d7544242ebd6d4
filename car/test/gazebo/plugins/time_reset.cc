// Test plug-in: a world plug-in that logs event::Events::timeReset ("timereset@SIMTIME") and its own Reset
// ("reset@SIMTIME"), read by the test through car_test_time_reset_log(), and counts the time resets that came on
// another thread than the one that loaded it (car_test_time_reset_elsewhere()). With <action>resettime</action> it
// calls World::ResetTime in its first WorldUpdateBegin.
#include <gazebo/common/common.hh>
#include <gazebo/gazebo.hh>
#include <gazebo/physics/physics.hh>

#include <string>
#include <thread>

#include "event_log.hh"

namespace {
std::string g_log;
int g_elsewhere = 0;
}  // namespace

extern "C" GZ_PLUGIN_VISIBLE const char* car_test_time_reset_log() { return g_log.c_str(); }
extern "C" GZ_PLUGIN_VISIBLE int car_test_time_reset_elsewhere() { return g_elsewhere; }
extern "C" GZ_PLUGIN_VISIBLE void car_test_time_reset_clear() {
  g_log.clear();
  g_elsewhere = 0;
}

namespace gazebo {
class TimeReset : public WorldPlugin {
 public:
  void Load(physics::WorldPtr _world, sdf::ElementPtr _sdf) override {
    this->world = _world;
    this->thread = std::this_thread::get_id();
    const bool reset_time = _sdf->HasElement("action") && _sdf->Get<std::string>("action") == "resettime";
    this->timeReset = event::Events::ConnectTimeReset([this] {
      if (std::this_thread::get_id() != this->thread) ++g_elsewhere;
      Log("timereset");
    });
    if (reset_time)
      this->begin = event::Events::ConnectWorldUpdateBegin([this](const common::UpdateInfo&) {
        if (this->done) return;
        this->done = true;
        this->world->ResetTime();
      });
  }
  void Reset() override { Log("reset"); }

 private:
  void Log(const std::string& what) { car_test::log_event(g_log, what, this->world->SimTime().Double()); }
  physics::WorldPtr world;
  std::thread::id thread;
  bool done = false;
  event::ConnectionPtr timeReset, begin;
};
GZ_REGISTER_WORLD_PLUGIN(TimeReset)
}  // namespace gazebo
