// Test plug-in: what a model plug-in sees of its model's links and joints (docs/PLUGINS.md "Fixed joints, the world
// link and static models"), logged in Load as KEY=VALUE words that the test reads through car_test_joint_list_log():
//   links=A,B,...  canonical=NAME  static=0|1  joints=J1,J2,...  count=N
//   and for each joint J: J.dof=N J.fixed=0|1 J.parent=NAME|null J.child=NAME|null
// With <probe>JOINT</probe> it then calls each Joint member on that joint and logs what it returned:
//   position, velocity, set_position, force (GetForce after SetForce(0, 5)), lower, upper, effort, vel_limit,
//   axis, set_param (SetParam("vel", 0, 1.0)), get_param (GetParam("vel", 0)).
#include <gazebo/common/common.hh>
#include <gazebo/gazebo.hh>
#include <gazebo/physics/physics.hh>

#include <sstream>
#include <string>

namespace {
std::ostringstream g_log;
std::string g_text;

template <class V, class F>
std::string names(const V& items, F name) {
  std::string out;
  for (const auto& i : items) out += (out.empty() ? "" : ",") + name(i);
  return out;
}
}  // namespace

extern "C" GZ_PLUGIN_VISIBLE const char* car_test_joint_list_log() {
  g_text = g_log.str();
  g_log.str("");
  return g_text.c_str();
}

namespace gazebo {
class JointList : public ModelPlugin {
 public:
  void Load(physics::ModelPtr _model, sdf::ElementPtr _sdf) override {
    physics::LinkPtr canonical = _model->GetLink("canonical");
    g_log << "links=" << names(_model->GetLinks(), [](const physics::LinkPtr& l) { return l->GetName(); })
          << " canonical=" << (canonical ? canonical->GetName() : "null") << " static=" << _model->IsStatic()
          << " joints=" << names(_model->GetJoints(), [](const physics::JointPtr& j) { return j->GetName(); })
          << " count=" << _model->GetJointCount();
    for (const physics::JointPtr& j : _model->GetJoints()) {
      const std::string n = j->GetName();
      g_log << " " << n << ".dof=" << j->DOF() << " " << n << ".fixed=" << j->HasType(physics::Base::FIXED_JOINT)
            << " " << n << ".parent=" << (j->GetParent() ? j->GetParent()->GetName() : "null") << " " << n
            << ".child=" << (j->GetChild() ? j->GetChild()->GetName() : "null");
    }
    if (!_sdf->HasElement("probe")) return;
    physics::JointPtr j = _model->GetJoint(_sdf->Get<std::string>("probe"));
    g_log << " position=" << j->Position(0);
    g_log << " velocity=" << j->GetVelocity(0);
    j->SetVelocity(0, 1.0);
    g_log << " set_position=" << j->SetPosition(0, 0.5);
    j->SetForce(0, 5.0);
    g_log << " force=" << j->GetForce(0);
    g_log << " lower=" << j->LowerLimit(0) << " upper=" << j->UpperLimit(0);
    g_log << " effort=" << j->GetEffortLimit(0) << " vel_limit=" << j->GetVelocityLimit(0);
    const ignition::math::Vector3d a = j->LocalAxis(0);
    g_log << " axis=" << a.X() << "," << a.Y() << "," << a.Z();
    g_log << " set_param=" << j->SetParam("vel", 0, 1.0) << " get_param=" << j->GetParam("vel", 0);
  }
};
GZ_REGISTER_MODEL_PLUGIN(JointList)
}  // namespace gazebo
