// Test plug-in in the style of Gazebo's plug-in parameters tutorial: reads <velocity> (default 0) from its SDF and
// pushes the model at that speed along x every world update.
#include <gazebo/gazebo.hh>
#include <gazebo/physics/physics.hh>

namespace gazebo {
class Parameters : public ModelPlugin {
 public:
  void Load(physics::ModelPtr _model, sdf::ElementPtr _sdf) override {
    this->model = _model;
    double velocity = 0;
    if (_sdf->HasElement("velocity")) velocity = _sdf->Get<double>("velocity");
    this->speed = velocity;
    this->connection = event::Events::ConnectWorldUpdateBegin(
        [this](const common::UpdateInfo&) { this->model->SetLinearVel({this->speed, 0, 0}); });
  }

 private:
  physics::ModelPtr model;
  double speed = 0;
  event::ConnectionPtr connection;
};
GZ_REGISTER_MODEL_PLUGIN(Parameters)
}  // namespace gazebo
