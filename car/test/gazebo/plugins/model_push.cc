// Test plug-in in the style of Gazebo's model_push tutorial: sets the model's linear velocity to (0.3, 0, 0) at
// the start of every world update.
#include <functional>
#include <gazebo/common/common.hh>
#include <gazebo/gazebo.hh>
#include <gazebo/physics/physics.hh>
#include <ignition/math/Vector3.hh>

namespace gazebo {
class ModelPush : public ModelPlugin {
 public:
  void Load(physics::ModelPtr _parent, sdf::ElementPtr /*_sdf*/) override {
    this->model = _parent;
    this->updateConnection =
        event::Events::ConnectWorldUpdateBegin(std::bind(&ModelPush::OnUpdate, this));
  }
  void OnUpdate() { this->model->SetLinearVel(ignition::math::Vector3d(.3, 0, 0)); }

 private:
  physics::ModelPtr model;
  event::ConnectionPtr updateConnection;
};
GZ_REGISTER_MODEL_PLUGIN(ModelPush)
}  // namespace gazebo
