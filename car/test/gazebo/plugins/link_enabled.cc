// Test plug-in for Link::SetEnabled / GetEnabled (docs/PLUGINS.md), one <mode> per test. It includes only the two
// headers roboticsgroup's MimicJointPlugin includes (<gazebo/common/Plugin.hh>, <gazebo/physics/physics.hh>): with
// Gazebo 11's include graph they bring event::Events and event::ConnectionPtr, so a missing include fails the build.
//   joined:      SetEnabled(false) on link wheel in Load.
//   alone:       SetEnabled(false) on the canonical link (the model's only one) in Load.
//   alone_force: as alone, then AddForce (0, 0, 0) on it in the second WorldUpdateBegin.
//   joint_force: SetEnabled(false) on both links in Load, then SetForce(0, 0) on joint axle in the second
//                WorldUpdateBegin.
// Logs GetEnabled of the link(s) after Load ("load=") and in the first two WorldUpdateBegin ("begin=", after its
// call) and WorldUpdateEnd ("end="); the test reads the log through car_test_link_enabled_log().
#include <gazebo/common/Plugin.hh>
#include <gazebo/physics/physics.hh>

#include <sstream>
#include <string>

#include "event_log.hh"

CAR_TEST_PLUGIN_LOG(link_enabled)

namespace gazebo {
class LinkEnabled : public ModelPlugin {
 public:
  void Load(physics::ModelPtr _model, sdf::ElementPtr _sdf) override {
    mode = _sdf->Get<std::string>("mode");
    body = _model->GetLink();
    wheel = _model->GetLink("wheel");
    axle = _model->GetJoint("axle");
    if (mode == "joined") wheel->SetEnabled(false);
    if (mode == "alone" || mode == "alone_force" || mode == "joint_force") body->SetEnabled(false);
    if (mode == "joint_force") wheel->SetEnabled(false);
    Log("load");
    begin = event::Events::ConnectWorldUpdateBegin([this](const common::UpdateInfo&) {
      if (++steps > 2) return;
      if (steps == 2 && mode == "alone_force") body->AddForce(ignition::math::Vector3d::Zero);
      if (steps == 2 && mode == "joint_force") axle->SetForce(0, 0.0);
      Log("begin");
    });
    end = event::Events::ConnectWorldUpdateEnd([this] {
      if (steps <= 2) Log("end");
    });
  }

 private:
  // "WHAT=E" with E the enabled flag (1/0) of wheel (joined), of body (alone...), of body then wheel (joint_force)
  void Log(const std::string& what) {
    g_log << what << "=";
    if (mode == "joined") g_log << wheel->GetEnabled();
    if (mode == "alone" || mode == "alone_force" || mode == "joint_force") g_log << body->GetEnabled();
    if (mode == "joint_force") g_log << wheel->GetEnabled();
    g_log << " ";
  }
  std::string mode;
  int steps = 0;
  physics::LinkPtr body, wheel;
  physics::JointPtr axle;
  event::ConnectionPtr begin, end;
};
GZ_REGISTER_MODEL_PLUGIN(LinkEnabled)
}  // namespace gazebo
