// Test plug-in for physics::Base and Entity and the World calls on them (docs/PLUGINS.md "Entities"), one <mode> per
// test; what it saw goes to a log the test reads through car_test_entity_log().
//   lookup:          in Load, World::EntityByName / BaseByName on the model, its link upper (scoped and plain), its
//                    joint elbow, the merged link tool, a name that is nowhere and the world's name; logs KEY=VALUE.
//   pose:            in Load, EntityByName("arm::upper")->WorldPose(), then SetWorldPose (0, 0, 3) through the
//                    EntityPtr; logs both positions.
//   reset_time:      World::ResetTime in the 3rd WorldUpdateBegin.
//   reset_entities:  World::ResetEntities(Base::MODEL) in the 3rd WorldUpdateBegin.
//   reset_links:     World::ResetEntities(Base::LINK) in Load.
//   set_position:    in Load, elbow SetPosition(0, 2) (past the upper limit 1), SetVelocity(0, 0.5),
//                    SetPosition(0, 0.2, true), then SetPosition(0, 0.3); logs position and rate after each.
#include <gazebo/common/common.hh>
#include <gazebo/gazebo.hh>
#include <gazebo/physics/physics.hh>

#include <sstream>
#include <string>

#include "event_log.hh"

CAR_TEST_PLUGIN_LOG(entity)

namespace gazebo {
class EntityProbe : public ModelPlugin {
 public:
  void Load(physics::ModelPtr _model, sdf::ElementPtr _sdf) override {
    world = _model->GetWorld();
    const std::string mode = _sdf->Get<std::string>("mode");
    if (mode == "lookup") {
      Lookup(_model);
    } else if (mode == "pose") {
      physics::EntityPtr upper = world->EntityByName("arm::upper");
      g_log << "before=" << upper->WorldPose().Pos();
      upper->SetWorldPose(ignition::math::Pose3d(0, 0, 3, 0, 0, 0));
      g_log << " after=" << upper->WorldPose().Pos() << " model=" << _model->WorldPose().Pos();
    } else if (mode == "reset_time" || mode == "reset_entities") {
      update = event::Events::ConnectWorldUpdateBegin([this, mode](const common::UpdateInfo&) {
        if (++steps != 3) return;
        if (mode == "reset_time")
          world->ResetTime();
        else
          world->ResetEntities(physics::Base::MODEL);
      });
    } else if (mode == "reset_links") {
      world->ResetEntities(physics::Base::LINK);
    } else if (mode == "set_position") {
      physics::JointPtr elbow = _model->GetJoint("elbow");
      auto state = [elbow] {
        g_log << elbow->Position(0) << "/" << elbow->GetVelocity(0) << " ";
      };
      elbow->SetPosition(0, 2.0);
      state();
      elbow->SetVelocity(0, 0.5);
      elbow->SetPosition(0, 0.2, true);
      state();
      elbow->SetPosition(0, 0.3);
      state();
    }
  }

 private:
  void Lookup(const physics::ModelPtr& _model) {
    physics::EntityPtr m = world->EntityByName("arm");
    physics::EntityPtr scoped = world->EntityByName("arm::upper");
    physics::LinkPtr link = boost::dynamic_pointer_cast<physics::Link>(scoped);
    g_log << "model=" << (boost::dynamic_pointer_cast<physics::Model>(m) == _model)
          << " link=" << (link ? link->GetName() : "null")
          << " link_is_model=" << (boost::dynamic_pointer_cast<physics::Model>(scoped) != nullptr)
          << " scoped=" << link->GetScopedName() << " world_scoped=" << link->GetScopedName(true)
          << " parent_model=" << link->GetParentModel()->GetName() << " parent=" << link->GetParent()->GetName()
          << " plain_same=" << (world->EntityByName("upper") == scoped)
          << " link_type=" << link->HasType(physics::Base::LINK) << link->HasType(physics::Base::ENTITY)
          << link->HasType(physics::Base::MODEL)
          << " joint_entity=" << (world->EntityByName("arm::elbow") != nullptr);
    physics::BasePtr joint = world->BaseByName("arm::elbow");
    g_log << " joint_base=" << (joint ? joint->GetName() : "null")
          << " joint_type=" << joint->HasType(physics::Base::JOINT) << joint->HasType(physics::Base::HINGE_JOINT)
          << joint->HasType(physics::Base::SLIDER_JOINT) << joint->HasType(physics::Base::ENTITY)
          << " merged=" << (world->EntityByName("arm::tool") != nullptr)
          << " none=" << (world->BaseByName("nothing") != nullptr)
          << " root_entity=" << (world->EntityByName(world->Name()) != nullptr);
    physics::BasePtr root = world->BaseByName(world->Name());
    g_log << " root=" << (root ? root->GetName() : "null") << " root_parent=" << (root->GetParent() != nullptr)
          << " model_parent=" << _model->GetParent()->GetName()
          << " self_model=" << (_model->GetParentModel() == _model);
  }

  physics::WorldPtr world;
  event::ConnectionPtr update;
  int steps = 0;
};
GZ_REGISTER_MODEL_PLUGIN(EntityProbe)
}  // namespace gazebo
