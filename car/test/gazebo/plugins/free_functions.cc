// Test plug-in for physics::get_world / has_world and common::Time's wall clock and sleeps (docs/PLUGINS.md). Load
// logs, read through car_test_free_functions_log():
//   world=1 when get_world() and get_world(<its world's name>) are its model's world; has=1 for that name;
//   missing=<has_world("nowhere")> and the text of get_world("nowhere")'s exception;
//   wall=1 when GetWallTime lies between two CLOCK_REALTIME readings taken around it; iso=<length> of
//   GetWallTimeAsISOString ("YYYY-MM-DDTHH:MM:SS.ffffff": 26);
//   msleep=1 when MSleep(2) returned zero after at least 2 ms of CLOCK_MONOTONIC; skip=1 when Sleep(-1 s) returned at
//   once (zero) without sleeping.
#include <time.h>

#include <gazebo/common/common.hh>
#include <gazebo/gazebo.hh>
#include <gazebo/physics/physics.hh>

#include <sstream>
#include <string>

#include "event_log.hh"

CAR_TEST_PLUGIN_LOG(free_functions)

namespace {
double now(clockid_t clock) {
  struct timespec t;
  clock_gettime(clock, &t);
  return t.tv_sec + t.tv_nsec * 1e-9;
}
}  // namespace

namespace gazebo {
class FreeFunctions : public ModelPlugin {
 public:
  void Load(physics::ModelPtr _model, sdf::ElementPtr) override {
    physics::WorldPtr w = _model->GetWorld();
    g_log << "world=" << (physics::get_world() == w && physics::get_world(w->Name()) == w)
          << " has=" << physics::has_world(w->Name()) << " missing=" << physics::has_world("nowhere");
    try {
      physics::get_world("nowhere");
      g_log << " no-throw";
    } catch (const common::Exception& e) {
      g_log << " threw=" << e.GetErrorStr();
    }
    const double before = now(CLOCK_REALTIME);
    const double wall = common::Time::GetWallTime().Double();
    const double after = now(CLOCK_REALTIME);
    g_log << " wall=" << (before <= wall + 1e-6 && wall <= after + 1e-6)
          << " iso=" << common::Time::GetWallTimeAsISOString().size();
    const double t0 = now(CLOCK_MONOTONIC);
    const common::Time left = common::Time::MSleep(2);
    const double slept = now(CLOCK_MONOTONIC) - t0;
    g_log << " msleep=" << (left == common::Time::Zero && slept >= 0.002);
    g_log << " skip=" << (common::Time::Sleep(common::Time(-1, 0)) == common::Time::Zero);
  }
};
GZ_REGISTER_MODEL_PLUGIN(FreeFunctions)
}  // namespace gazebo
