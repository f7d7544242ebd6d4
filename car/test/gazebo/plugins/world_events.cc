// Test plug-in: a world plug-in that logs its calls and the world's pause and stop events (read by the test through
// car_test_world_log()), and acts on the world from its <action>: "pause" sets the world paused in the first
// WorldUpdateBegin, "reset" calls World::Reset there, "topic" advertises a ~/factory publisher on another topic.
#include <gazebo/common/common.hh>
#include <gazebo/gazebo.hh>
#include <gazebo/physics/physics.hh>

#include <string>

#include "event_log.hh"

namespace {
std::string g_log;
}

extern "C" GZ_PLUGIN_VISIBLE const char* car_test_world_log() { return g_log.c_str(); }
extern "C" GZ_PLUGIN_VISIBLE void car_test_world_clear() { g_log.clear(); }

namespace gazebo {
class WorldEvents : public WorldPlugin {
 public:
  ~WorldEvents() override { Log("unload"); }
  void Load(physics::WorldPtr _world, sdf::ElementPtr _sdf) override {
    this->world = _world;
    this->action = _sdf->HasElement("action") ? _sdf->Get<std::string>("action") : "";
    Log("load " + _world->Name() + (_world->IsPaused() ? " paused" : " running"));
    this->pause = event::Events::ConnectPause([this](bool _p) { Log(_p ? "pause" : "unpause"); });
    this->stop = event::Events::ConnectStop([this] { Log("stop"); });
    this->begin = event::Events::ConnectWorldUpdateBegin([this](const common::UpdateInfo&) {
      if (this->done) return;
      this->done = true;
      if (this->action == "pause") this->world->SetPaused(true);
      if (this->action == "reset") this->world->Reset();
    });
    if (this->action == "topic") {
      transport::NodePtr node(new transport::Node());
      node->Init(_world->Name());
      node->Advertise<msgs::Factory>("~/world_control");
    }
  }
  void Init() override { Log("init"); }
  void Reset() override { Log("reset"); }

 private:
  void Log(const std::string& what) { car_test::log_event(g_log, what, this->world->SimTime().Double()); }
  physics::WorldPtr world;
  std::string action;
  bool done = false;
  event::ConnectionPtr pause, stop, begin;
};
GZ_REGISTER_WORLD_PLUGIN(WorldEvents)
}  // namespace gazebo
