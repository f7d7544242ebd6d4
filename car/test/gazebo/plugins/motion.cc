// Test plug-in for the joint motor, gravity mode, applied wrench and pose calls (docs/PLUGINS.md), one <mode> per
// test; what it saw goes to a log the test reads through car_test_motion_log().
//   motor:   SetParam("fmax", <fmax>) on joint axle in Load (as gazebo_ros_diff_drive), SetParam("vel", <vel>) every
//            WorldUpdateBegin; logs GetParam of fmax, vel and friction after Load's call.
//   gravity: SetGravityMode(false) on the canonical link in Load; logs GetGravityMode.
//   force:   AddForce (1, 0, 0) and AddTorque (0, 0, 2) on the canonical link every WorldUpdateBegin, then logs
//            WorldForce().X() and WorldTorque().Z() (first two steps).
//   pose:    SetLinkWorldPose (1, 2, 3) for link wheel in Load; logs the wheel's WorldPose and RelativePose positions.
//   physics_off: SetPhysicsEnabled(false) in Load.
//   gzthrow: gzthrow in Load.
//   bad_param: SetParam("erp", 0, 0.2) and SetParam("fmax", 0, 1) (an int); logs both results.
//   set_position: SetVelocity(0, 2) on axle, then SetPosition(0, <position>, <preserve>) in Load; logs the result,
//            Position and GetVelocity.
#include <gazebo/common/common.hh>
#include <gazebo/gazebo.hh>
#include <gazebo/physics/physics.hh>

#include <sstream>
#include <string>

#include "event_log.hh"

CAR_TEST_PLUGIN_LOG(motion)

namespace gazebo {
class Motion : public ModelPlugin {
 public:
  void Load(physics::ModelPtr _model, sdf::ElementPtr _sdf) override {
    model = _model;
    const std::string mode = _sdf->Get<std::string>("mode");
    physics::JointPtr axle = _model->GetJoint("axle");
    physics::LinkPtr body = _model->GetLink();
    if (mode == "motor") {
      vel = _sdf->Get<double>("vel");
      axle->SetParam("fmax", 0, _sdf->Get<double>("fmax"));
      g_log << "fmax=" << axle->GetParam("fmax", 0) << " vel=" << axle->GetParam("vel", 0)
            << " friction=" << axle->GetParam("friction", 0);
      update = event::Events::ConnectWorldUpdateBegin(
          [this, axle](const common::UpdateInfo&) { axle->SetParam("vel", 0, vel); });
    } else if (mode == "gravity") {
      body->SetGravityMode(false);
      g_log << "gravity=" << body->GetGravityMode();
    } else if (mode == "force") {
      update = event::Events::ConnectWorldUpdateBegin([this, body](const common::UpdateInfo&) {
        body->AddForce(ignition::math::Vector3d(1, 0, 0));
        body->AddTorque(ignition::math::Vector3d(0, 0, 2));
        if (++steps <= 2) g_log << "f=" << body->WorldForce().X() << " t=" << body->WorldTorque().Z() << " ";
      });
    } else if (mode == "pose") {
      _model->SetLinkWorldPose(ignition::math::Pose3d(1, 2, 3, 0, 0, 0), "wheel");
      physics::LinkPtr wheel = _model->GetLink("wheel");
      g_log << "world=" << wheel->WorldPose().Pos() << " relative=" << wheel->RelativePose().Pos();
    } else if (mode == "physics_off") {
      _model->GetWorld()->SetPhysicsEnabled(false);
    } else if (mode == "gzthrow") {
      gzthrow("no <bodyName> given");
    } else if (mode == "set_position") {
      axle->SetVelocity(0, 2.0);
      const bool ok = axle->SetPosition(0, _sdf->Get<double>("position"), _sdf->Get<bool>("preserve"));
      g_log << "ok=" << ok << " position=" << axle->Position(0) << " velocity=" << axle->GetVelocity(0);
    } else if (mode == "bad_param") {
      const bool erp = axle->SetParam("erp", 0, 0.2);
      const bool as_int = axle->SetParam("fmax", 0, 1);
      g_log << "erp=" << erp << " int=" << as_int;
    }
  }

 private:
  physics::ModelPtr model;
  event::ConnectionPtr update;
  double vel = 0.0;
  int steps = 0;
};
GZ_REGISTER_MODEL_PLUGIN(Motion)
}  // namespace gazebo
