// Test plug-in: 1 N along world x on its model's <link> (default: the canonical link) every WorldUpdateBegin, and a
// log of its calls and events with the sim time each sees, which the test reads through car_test_forces_log().
#include <gazebo/common/common.hh>
#include <gazebo/gazebo.hh>
#include <gazebo/physics/physics.hh>

#include <string>

#include "event_log.hh"

namespace {
std::string g_log;
}

extern "C" GZ_PLUGIN_VISIBLE const char* car_test_forces_log() { return g_log.c_str(); }
extern "C" GZ_PLUGIN_VISIBLE void car_test_forces_clear() { g_log.clear(); }

namespace gazebo {
class Forces : public ModelPlugin {
 public:
  ~Forces() override { Log("unload"); }
  void Load(physics::ModelPtr _model, sdf::ElementPtr _sdf) override {
    this->model = _model;
    this->link = _model->GetLink(_sdf->HasElement("link") ? _sdf->Get<std::string>("link") : "canonical");
    Log("load");
    this->begin = event::Events::ConnectWorldUpdateBegin([this](const common::UpdateInfo& _info) {
      Log("begin", _info.simTime);
      this->link->AddForce(ignition::math::Vector3d(1, 0, 0));
    });
    this->before = event::Events::ConnectBeforePhysicsUpdate(
        [this](const common::UpdateInfo& _info) { Log("before", _info.simTime); });
    this->end = event::Events::ConnectWorldUpdateEnd([this] { Log("end"); });
  }
  void Init() override { Log("init"); }
  void Reset() override { Log("reset"); }

 private:
  // what happened, at the world's sim time (and the event's, when it carries one)
  void Log(const std::string& what, const common::Time& event = common::Time(-1, 0)) {
    const double event_time = event.sec >= 0 ? event.Double() : -1.0;
    car_test::log_event(g_log, what, this->model->GetWorld()->SimTime().Double(), event_time);
  }
  physics::ModelPtr model;
  physics::LinkPtr link;
  event::ConnectionPtr begin, before, end;
};
GZ_REGISTER_MODEL_PLUGIN(Forces)
}  // namespace gazebo
