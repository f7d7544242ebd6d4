// car's Gazebo 11 API: the joint motor parameters (Joint::SetParam/GetParam), a link's gravity mode, applied
// wrench and relative pose, Model::SetLinkWorldPose and World::SetPhysicsEnabled, each one of car_sim::World's
// public calls (docs/PLUGINS.md).
#include <boost/any.hpp>
#include <boost/make_shared.hpp>
#include <stdexcept>

#include "car_sim/world.hpp"
#include "gazebo/common/Console.hh"
#include "gazebo/physics/physics.hh"
#include "hub.hpp"

using car_gazebo::eig;
using car_gazebo::ign;

namespace gazebo {
namespace physics {

namespace {

car_sim::World& core_of(const ModelPtr& m) {
  WorldPtr w = m ? m->GetWorld() : WorldPtr();
  if (!w) throw std::logic_error("the model's world is gone");
  return *w->Core();
}

}  // namespace

// ---- Joint: ODE's motor (gazebo/physics/ode/ODEJoint.cc, SetParam and Param) ---------------------------------

bool Joint::SetParam(const std::string& _key, unsigned int _index, const boost::any& _value) {
  if (_index != 0) {
    gzerr << "Invalid index[" << _index << "]\n";
    return false;
  }
  double value = 0.0;
  try {
    value = boost::any_cast<double>(_value);
  } catch (const boost::bad_any_cast& e) {
    gzerr << "SetParam(" << _key << ") boost any_cast error:" << e.what() << "\n";
    return false;
  }
  const bool motor_key = _key == "vel" || _key == "fmax" || _key == "friction";
  // a fixed joint: ODEJoint::SetParam(parameter, value), which ODEFixedJoint does not override, does nothing
  if (fixed && motor_key) return true;
  if (!motor_key) {
    gzerr << "Unable to handle joint attribute[" << _key << "] (car offers \"vel\", \"fmax\" and \"friction\")\n";
    return false;
  }
  ModelPtr m = model.lock();
  car_sim::World& w = core_of(m);
  car_sim::World::JointMotor motor = w.joint_motor(m->GetName(), name);
  if (_key == "vel") {
    motor.velocity = value;
  } else if (_key == "fmax") {
    motor.max_effort = value;
  } else {
    // "friction": Coulomb friction as ODE models it, a motor holding 0 with at most the friction
    motor.max_effort = value;
    motor.velocity = 0.0;
  }
  // as ODEJoint: both links enabled
  if (LinkPtr c = GetChild()) c->SetEnabled(true);
  if (LinkPtr p = GetParent()) p->SetEnabled(true);
  try {
    w.set_joint_motor(m->GetName(), name, motor);
  } catch (const std::invalid_argument& e) {
    gzerr << "SetParam(" << _key << ") of joint [" << name << "]: " << e.what() << "\n";
    return false;
  }
  return true;
}

double Joint::GetParam(const std::string& _key, unsigned int _index) {
  if (_index != 0) {
    gzerr << "Invalid index[" << _index << "]\n";
    return 0.0;
  }
  if (_key != "vel" && _key != "fmax" && _key != "friction") {
    gzerr << "Unable to get joint attribute[" << _key << "]\n";
    return 0.0;
  }
  // a fixed joint: ODEJoint::GetParam(parameter) of ODEFixedJoint, 0
  if (fixed) return 0.0;
  ModelPtr m = model.lock();
  const car_sim::World::JointMotor motor = core_of(m).joint_motor(m->GetName(), name);
  return _key == "vel" ? motor.velocity : motor.max_effort;
}

// ---- Link ------------------------------------------------------------------------------------------------------

ignition::math::Vector3d Link::WorldForce() const {
  ModelPtr m = model.lock();
  return ign(core_of(m).link_applied_wrench({m->GetName(), name, true}).force);
}

ignition::math::Vector3d Link::WorldTorque() const {
  ModelPtr m = model.lock();
  return ign(core_of(m).link_applied_wrench({m->GetName(), name, true}).torque);
}

ignition::math::Pose3d Link::RelativePose() const {
  ModelPtr m = model.lock();
  return WorldPose() - m->WorldPose();
}

ignition::math::Pose3d Link::DirtyPose() const { return WorldPose(); }

void Link::SetGravityMode(bool _mode) {
  ModelPtr m = model.lock();
  core_of(m).set_link_gravity({m->GetName(), name, true}, _mode);
}

bool Link::GetGravityMode() const {
  ModelPtr m = model.lock();
  return core_of(m).link_gravity({m->GetName(), name, true});
}

namespace {

// true when a link of the model other than `self` is enabled
bool other_link_enabled(const ModelPtr& m, const Link* self) {
  if (!m) return false;
  for (const LinkPtr& l : m->GetLinks())
    if (l && l.get() != self && l->GetEnabled()) return true;
  return false;
}

}  // namespace

void Link::SetEnabled(bool _enable) const {
  if (_enable) {
    disabled = false;
    islandCheck.reset();
    return;
  }
  if (disabled) return;
  disabled = true;
  ModelPtr m = model.lock();
  if (!other_link_enabled(m, this))
    gzwarn << "car: every link of model [" << (m ? m->GetName() : std::string("?"))
           << "] is disabled (Link::SetEnabled(false)); Gazebo 11's ODE holds such a model still until a contact or "
              "a force enables a link, car goes on simulating it (docs/PLUGINS.md)\n";
  // ODE's islands: in each physics step, an enabled link of the model enables this one
  if (!m) return;
  std::shared_ptr<car_gazebo::Hub> hub = car_gazebo::Hub::of(&core_of(m));
  const int id = hub->islands.connect([this] {
    if (other_link_enabled(model.lock(), this)) SetEnabled(true);
  });
  std::weak_ptr<car_gazebo::Hub> weak = hub;
  islandCheck = boost::make_shared<event::Connection>([weak, id] {
    if (auto h = weak.lock()) h->islands.disconnect(id);
  });
}

bool Link::GetEnabled() const { return !disabled; }

// ---- Model -----------------------------------------------------------------------------------------------------

void Model::SetLinkWorldPose(const ignition::math::Pose3d& _pose, std::string _linkName) {
  LinkPtr link = GetLink(_linkName);
  if (!link) {
    gzerr << "Setting Model Pose by specifying Link failed, as Link [" << _linkName << "] is not in Model ["
          << name << "]\n";
    return;
  }
  link->SetWorldPose(_pose);
}

void Model::SetLinkWorldPose(const ignition::math::Pose3d& _pose, const LinkPtr& _link) {
  if (!_link) return;
  SetLinkWorldPose(_pose, _link->GetName());
}

// ---- World -----------------------------------------------------------------------------------------------------

void World::SetPhysicsEnabled(const bool _enable) { world->set_physics_enabled(_enable); }

}  // namespace physics
}  // namespace gazebo
