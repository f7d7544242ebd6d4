// Test plug-in in the style of the velodyne tutorial: a P controller (p 0.1) on the model's first joint through its
// JointController, the target from <velocity> (default 0).
#include <gazebo/gazebo.hh>
#include <gazebo/physics/physics.hh>

namespace gazebo {
class VelocityPid : public ModelPlugin {
 public:
  void Load(physics::ModelPtr _model, sdf::ElementPtr _sdf) override {
    if (_model->GetJointCount() == 0) {
      std::cerr << "Invalid joint count, Velodyne plugin not loaded\n";
      return;
    }
    this->model = _model;
    this->joint = _model->GetJoints()[0];
    this->pid = common::PID(0.1, 0, 0);
    this->model->GetJointController()->SetVelocityPID(this->joint->GetScopedName(), this->pid);
    double velocity = 0;
    if (_sdf->HasElement("velocity")) velocity = _sdf->Get<double>("velocity");
    this->model->GetJointController()->SetVelocityTarget(this->joint->GetScopedName(), velocity);
  }

 private:
  physics::ModelPtr model;
  physics::JointPtr joint;
  common::PID pid;
};
GZ_REGISTER_MODEL_PLUGIN(VelocityPid)
}  // namespace gazebo
