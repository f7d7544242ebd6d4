// car's Gazebo 11 API: the physics handles (World, Model, Link, Joint, JointController, Inertial, PhysicsEngine),
// each call one of car_sim::World's public calls (docs/PLUGINS.md). No state of their own beyond names, except
// what Gazebo's API itself keeps (a joint's GetForce sum, the joint controller's targets and PIDs).
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "car_sim/world.hpp"
#include "gazebo/common/Console.hh"
#include "gazebo/common/Exception.hh"
#include "gazebo/physics/physics.hh"
#include "hub.hpp"

using car_gazebo::eig;
using car_gazebo::ign;

namespace gazebo {
namespace physics {

namespace {

car_sim::World& core_of(const WorldPtr& w) {
  if (!w) throw std::logic_error("the model's world is gone");
  return *w->Core();
}

// The robot's model description (car's), for names, limits and mass properties.
const car_sim::RobotModel& robot_model(car_sim::World& w, const std::string& name) { return w.robot(name).model; }

}  // namespace

// ---- World -------------------------------------------------------------------------------------------------

World::World(car_sim::World* _world) : world(_world), physics(new PhysicsEngine(_world)) {}
World::~World() = default;

std::string World::Name() const { return world->description().name; }

common::Time World::SimTime() const { return car_gazebo::time_of(world->tick() + (inStep ? 1 : 0), world->dt()); }

uint64_t World::Iterations() const { return world->tick(); }

ModelPtr World::ModelByName(const std::string& _name) const {
  const auto robots = world->robot_names();
  if (std::find(robots.begin(), robots.end(), _name) == robots.end()) {
    models.erase(_name);
    return ModelPtr();
  }
  auto it = models.find(_name);
  if (it != models.end()) return it->second;
  ModelPtr m(new Model(boost::const_pointer_cast<World>(shared_from_this()), _name));
  m->Build();
  models[_name] = m;
  return m;
}

Model_V World::Models() const {
  Model_V out;
  for (const auto& n : world->robot_names()) out.push_back(ModelByName(n));
  return out;
}

unsigned int World::ModelCount() const { return static_cast<unsigned int>(world->robot_names().size()); }

ignition::math::Vector3d World::Gravity() const { return ign(world->gravity()); }

void World::SetGravity(const ignition::math::Vector3d& _gravity) { world->set_gravity(eig(_gravity)); }

PhysicsEnginePtr World::Physics() const { return physics; }

void World::AddControlled(const ModelPtr& _model) { controlled.push_back(_model); }

void World::UpdateControllers() {
  // a model deleted from the world leaves its controller (and the handles a plug-in may still hold) behind
  for (size_t k = 0; k < controlled.size();) {
    ModelPtr m = controlled[k].lock();
    if (!m || !world->has_model(m->GetName())) {
      controlled.erase(controlled.begin() + static_cast<long>(k));
      if (m) models.erase(m->GetName());
      continue;
    }
    m->UpdateController();
    ++k;
  }
}

bool World::PhysicsEnabled() const { return world->physics_enabled(); }

PhysicsEngine::PhysicsEngine(car_sim::World* _world) : world(_world) {}
PhysicsEngine::~PhysicsEngine() = default;
double PhysicsEngine::GetMaxStepSize() const { return world->dt(); }
std::string PhysicsEngine::GetType() const { return "bullet"; }

// ---- Model -------------------------------------------------------------------------------------------------

Model::Model(WorldPtr _world, const std::string& _name) : Entity(_world ? _world->Root() : BasePtr()) {
  name = _name;
  world = _world;
  AddType(MODEL);
}
Model::~Model() = default;

void Model::Build() {
  car_sim::World& w = core_of(world.lock());
  const car_sim::RobotModel& m = robot_model(w, name);
  ModelPtr self = boost::static_pointer_cast<Model>(shared_from_this());
  // the root first: Gazebo's canonical link. Not the link `world` that anchors a model (a URDF's, which Gazebo's
  // URDF import drops; car's own for a static SDF model, whose links are Gazebo's): it is no link of the model.
  for (const auto& l : m.links)
    if (!(l.name == "world" && m.root_link == "world")) links.push_back(LinkPtr(new Link(self, l.name)));
  // every joint the model loaded, fixed ones too, in the model's order (Model::LoadJoints); not car's anchors of a
  // static model. A URDF's lumped fixed joints are gone, as in Gazebo's URDF import.
  for (const auto& j : m.joints)
    if (!j.anchor) joints.push_back(JointPtr(new Joint(self, j.name)));
  sdf = std::make_shared<sdf::Element>();
  sdf->SetName("model");
  sdf->AddAttribute("name", "string", "", true);
  sdf->GetAttribute("name")->SetFromString(name);
}

const sdf::ElementPtr Model::GetSDF() { return sdf; }

LinkPtr Model::GetLink(const std::string& _name) const {
  if (_name == "canonical") return links.empty() ? LinkPtr() : links.front();
  const std::string plain = _name.rfind(name + "::", 0) == 0 ? _name.substr(name.size() + 2) : _name;
  for (const auto& l : links)
    if (l->GetName() == plain) return l;
  return LinkPtr();
}

const Link_V& Model::GetLinks() const { return links; }
LinkPtr Model::GetChildLink(const std::string& _name) const { return _name == "canonical" ? LinkPtr() : GetLink(_name); }

JointPtr Model::GetJoint(const std::string& _name) {
  const std::string plain = _name.rfind(name + "::", 0) == 0 ? _name.substr(name.size() + 2) : _name;
  for (const auto& j : joints)
    if (j->GetName() == plain) return j;
  return JointPtr();
}

const Joint_V& Model::GetJoints() const { return joints; }
unsigned int Model::GetJointCount() const { return static_cast<unsigned int>(joints.size()); }

JointControllerPtr Model::GetJointController() {
  if (!controller) {
    ModelPtr self = boost::static_pointer_cast<Model>(shared_from_this());
    controller.reset(new JointController(self));
    for (const auto& j : joints) controller->AddJoint(j);
    if (WorldPtr w = world.lock()) w->AddControlled(self);
  }
  return controller;
}

void Model::UpdateController() {
  if (controller) controller->Update();
}

ignition::math::Pose3d Model::WorldPose() const { return ign(core_of(world.lock()).model_state(name).pose); }

void Model::SetWorldPose(const ignition::math::Pose3d& _pose, bool, bool) {
  // as Gazebo's: each link's OnPoseChange enables its ODE body
  for (const LinkPtr& l : links)
    if (l) l->SetEnabled(true);
  car_sim::World& w = core_of(world.lock());
  car_sim::ModelState s = w.model_state(name);
  s.pose = eig(_pose);
  w.set_model_state(name, s);
}

ignition::math::Vector3d Model::WorldLinearVel() const { return ign(core_of(world.lock()).model_state(name).linear); }
ignition::math::Vector3d Model::WorldAngularVel() const { return ign(core_of(world.lock()).model_state(name).angular); }
ignition::math::Vector3d Model::RelativeLinearVel() const {
  const car_sim::ModelState s = core_of(world.lock()).model_state(name);
  return ign(Eigen::Vector3d(s.pose.linear().transpose() * s.linear));
}
ignition::math::Vector3d Model::RelativeAngularVel() const {
  const car_sim::ModelState s = core_of(world.lock()).model_state(name);
  return ign(Eigen::Vector3d(s.pose.linear().transpose() * s.angular));
}

void Model::SetLinearVel(const ignition::math::Vector3d& _vel) {
  if (LinkPtr root = GetLink()) root->SetLinearVel(_vel);
}
void Model::SetAngularVel(const ignition::math::Vector3d& _vel) {
  if (LinkPtr root = GetLink()) root->SetAngularVel(_vel);
}
bool Model::IsStatic() const { return robot_model(core_of(world.lock()), name).is_static; }

// ---- Link --------------------------------------------------------------------------------------------------

Link::Link(ModelPtr _model, const std::string& _name) : Entity(_model), model(_model), inertial(new Inertial) {
  name = _name;
  AddType(LINK);
  car_sim::World& w = core_of(_model->GetWorld());
  const car_sim::LinkProperties p = w.link_properties({_model->GetName(), name, true});
  inertial->mass = p.mass;
  inertial->cog = ign(p.com);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) inertial->moi(r, c) = p.inertia(r, c);
}
Link::~Link() = default;

namespace {

struct LinkAt {
  car_sim::World& w;
  car_sim::LinkRef ref;
};

LinkAt at(const boost::weak_ptr<Model>& m, const std::string& link) {
  ModelPtr model = m.lock();
  if (!model) throw std::logic_error("the link's model is gone");
  return {core_of(model->GetWorld()), {model->GetName(), link, true}};
}

}  // namespace

ModelPtr Link::GetModel() const { return model.lock(); }
InertialPtr Link::GetInertial() const { return inertial; }

ignition::math::Pose3d Link::WorldPose() const {
  LinkAt l = at(model, name);
  return ign(l.w.link_state(l.ref).pose);
}

ignition::math::Pose3d Link::WorldCoGPose() const {
  LinkAt l = at(model, name);
  Eigen::Isometry3d T = l.w.link_state(l.ref).pose;
  T.translation() = T * eig(inertial->CoG());
  return ign(T);
}

void Link::SetWorldPose(const ignition::math::Pose3d& _pose, bool, bool) {
  SetEnabled(true);  // as ODELink
  LinkAt l = at(model, name);
  car_sim::ModelState s = l.w.link_state(l.ref);
  s.pose = eig(_pose);
  l.w.set_link_state(l.ref, s);
}

ignition::math::Vector3d Link::WorldLinearVel() const {
  LinkAt l = at(model, name);
  return ign(l.w.link_state(l.ref).linear);
}

ignition::math::Vector3d Link::WorldLinearVel(const ignition::math::Vector3d& _offset) const {
  LinkAt l = at(model, name);
  const car_sim::ModelState s = l.w.link_state(l.ref);
  return ign(Eigen::Vector3d(s.linear + s.angular.cross(s.pose.linear() * eig(_offset))));
}

ignition::math::Vector3d Link::WorldCoGLinearVel() const { return WorldLinearVel(inertial->CoG()); }

ignition::math::Vector3d Link::WorldAngularVel() const {
  LinkAt l = at(model, name);
  return ign(l.w.link_state(l.ref).angular);
}

ignition::math::Vector3d Link::RelativeLinearVel() const {
  LinkAt l = at(model, name);
  const car_sim::ModelState s = l.w.link_state(l.ref);
  return ign(Eigen::Vector3d(s.pose.linear().transpose() * s.linear));
}

ignition::math::Vector3d Link::RelativeAngularVel() const {
  LinkAt l = at(model, name);
  const car_sim::ModelState s = l.w.link_state(l.ref);
  return ign(Eigen::Vector3d(s.pose.linear().transpose() * s.angular));
}

void Link::SetLinearVel(const ignition::math::Vector3d& _vel) {
  LinkAt l = at(model, name);
  l.w.set_link_velocity(l.ref, eig(_vel), l.w.link_state(l.ref).angular);
}

void Link::SetAngularVel(const ignition::math::Vector3d& _vel) {
  LinkAt l = at(model, name);
  const car_sim::ModelState s = l.w.link_state(l.ref);
  // the centre of gravity keeps its velocity
  const Eigen::Vector3d cog = s.linear + s.angular.cross(s.pose.linear() * eig(inertial->CoG()));
  l.w.set_link_velocity(l.ref, cog, eig(_vel));
}

void Link::AddForce(const ignition::math::Vector3d& _force) {
  SetEnabled(true);  // as ODELink
  LinkAt l = at(model, name);
  const Eigen::Isometry3d T = l.w.link_state(l.ref).pose;
  l.w.add_link_wrench(l.ref, eig(_force), Eigen::Vector3d::Zero(), T * eig(inertial->CoG()),
                      car_sim::World::Frame::World);
}

void Link::AddRelativeForce(const ignition::math::Vector3d& _force) {
  SetEnabled(true);  // as ODELink
  LinkAt l = at(model, name);
  l.w.add_link_wrench(l.ref, eig(_force), Eigen::Vector3d::Zero(), eig(inertial->CoG()), car_sim::World::Frame::Link);
}

void Link::AddForceAtWorldPosition(const ignition::math::Vector3d& _force, const ignition::math::Vector3d& _pos) {
  SetEnabled(true);  // as ODELink
  LinkAt l = at(model, name);
  l.w.add_link_wrench(l.ref, eig(_force), Eigen::Vector3d::Zero(), eig(_pos), car_sim::World::Frame::World);
}

void Link::AddForceAtRelativePosition(const ignition::math::Vector3d& _force,
                                      const ignition::math::Vector3d& _relPos) {
  SetEnabled(true);  // as ODELink
  LinkAt l = at(model, name);
  const Eigen::Isometry3d T = l.w.link_state(l.ref).pose;
  l.w.add_link_wrench(l.ref, eig(_force), Eigen::Vector3d::Zero(), T * eig(_relPos), car_sim::World::Frame::World);
}

void Link::AddLinkForce(const ignition::math::Vector3d& _force, const ignition::math::Vector3d& _offset) {
  SetEnabled(true);  // as ODELink
  LinkAt l = at(model, name);
  l.w.add_link_wrench(l.ref, eig(_force), Eigen::Vector3d::Zero(), eig(_offset), car_sim::World::Frame::Link);
}

void Link::AddTorque(const ignition::math::Vector3d& _torque) {
  SetEnabled(true);  // as ODELink
  LinkAt l = at(model, name);
  l.w.add_link_wrench(l.ref, Eigen::Vector3d::Zero(), eig(_torque), Eigen::Vector3d::Zero(),
                      car_sim::World::Frame::World);
}

void Link::AddRelativeTorque(const ignition::math::Vector3d& _torque) {
  SetEnabled(true);  // as ODELink
  LinkAt l = at(model, name);
  l.w.add_link_wrench(l.ref, Eigen::Vector3d::Zero(), eig(_torque), Eigen::Vector3d::Zero(),
                      car_sim::World::Frame::Link);
}

// ---- Inertial ----------------------------------------------------------------------------------------------

Inertial::Inertial() = default;
Inertial::~Inertial() = default;
double Inertial::Mass() const { return mass; }
const ignition::math::Vector3d& Inertial::CoG() const { return cog; }
double Inertial::IXX() const { return moi(0, 0); }
double Inertial::IYY() const { return moi(1, 1); }
double Inertial::IZZ() const { return moi(2, 2); }
double Inertial::IXY() const { return moi(0, 1); }
double Inertial::IXZ() const { return moi(0, 2); }
double Inertial::IYZ() const { return moi(1, 2); }
ignition::math::Vector3d Inertial::PrincipalMoments() const {
  return ignition::math::Vector3d(moi(0, 0), moi(1, 1), moi(2, 2));  // car: the diagonal (see docs/PLUGINS.md)
}
ignition::math::Matrix3d Inertial::MOI() const { return moi; }

// ---- Joint -------------------------------------------------------------------------------------------------

Joint::Joint(ModelPtr _model, const std::string& _name)
    : Base(_model),
      model(_model),
      lower(-std::numeric_limits<double>::infinity()),
      upper(std::numeric_limits<double>::infinity()),
      effort(-1.0),
      velocity(-1.0) {
  name = _name;
  AddType(JOINT);
  const car_sim::RobotModel& m = robot_model(core_of(_model->GetWorld()), _model->GetName());
  for (const auto& j : m.joints) {
    if (j.name != name) continue;
    // Gazebo's URDF import makes a continuous or revolute joint a hinge, a prismatic one a slider
    if (j.type == car_sim::JointType::Prismatic) AddType(SLIDER_JOINT);
    if (j.type == car_sim::JointType::Revolute || j.type == car_sim::JointType::Continuous) AddType(HINGE_JOINT);
    if (j.type == car_sim::JointType::Fixed) {
      AddType(FIXED_JOINT);
      fixed = true;
    }
    parent = j.parent;
    child = j.child;
    axis = ign(j.axis);
    if (j.limits) {
      if (j.type != car_sim::JointType::Continuous) {
        lower = j.limits->lower;
        upper = j.limits->upper;
      }
      effort = j.limits->effort;
      velocity = j.limits->velocity;
    }
  }
}
Joint::~Joint() = default;

namespace {

bool bad_index(unsigned int index, const std::string& joint) {
  if (index == 0) return false;
  gzerr << "Invalid joint axis index[" << index << "] of joint [" << joint << "]: car's joints have one axis\n";
  return true;
}

// Gazebo 11's warning for a call a fixed joint does not take (gazebo/physics/ode/ODEFixedJoint.cc).
void fixed_warning(const char* method) {
  gzwarn << "ODEFixedJoint: called method " << method << " that is not valid for joints of type fixed.\n";
}

}  // namespace

ModelPtr Joint::GetModel() const { return model.lock(); }
LinkPtr Joint::GetParent() const {
  ModelPtr m = model.lock();
  return m ? m->GetLink(parent) : LinkPtr();
}
LinkPtr Joint::GetChild() const {
  ModelPtr m = model.lock();
  return m ? m->GetLink(child) : LinkPtr();
}
unsigned int Joint::DOF() const { return fixed ? 0 : 1; }

// A fixed joint answers each call as Gazebo 11's ODE fixed joint (FixedJoint<ODEJoint>, DOF 0): Joint.cc and
// ODEJoint.cc's checks of the index against DOF(), and ODEFixedJoint.cc's warnings (docs/PLUGINS.md).
double Joint::Position(const unsigned int _index) const {
  if (fixed) {
    // Joint::Position: a static model's joint reads its staticPosition, 0 (a fixed joint's SetPosition never
    // stores one)
    if (model.lock()->IsStatic()) return 0.0;
    fixed_warning("PositionImpl");
    return std::numeric_limits<double>::quiet_NaN();
  }
  if (bad_index(_index, name)) return std::numeric_limits<double>::quiet_NaN();
  ModelPtr m = model.lock();
  return core_of(m->GetWorld()).joint_position(m->GetName(), name);
}

double Joint::GetVelocity(unsigned int _index) const {
  if (fixed) {
    fixed_warning("GetVelocity");
    return 0.0;
  }
  if (bad_index(_index, name)) return 0.0;
  ModelPtr m = model.lock();
  return core_of(m->GetWorld()).joint_velocity(m->GetName(), name);
}

void Joint::SetVelocity(unsigned int _index, double _vel) {
  if (fixed) {
    fixed_warning("SetVelocity");
    return;
  }
  if (bad_index(_index, name)) return;
  ModelPtr m = model.lock();
  core_of(m->GetWorld()).set_joint_velocity(m->GetName(), name, _vel);
}

void Joint::SetForce(unsigned int _index, double _effort) {
  if (fixed) {
    // ODEJoint::SetForce: CheckAndTruncateForce, SaveForce, then ODEFixedJoint::SetForceImpl
    gzerr << "Calling Joint::SetForce with an index [" << _index << "] out of range\n";
    gzerr << "Something's wrong, joint [" << GetScopedName() << "] index [" << _index << "] out of range.\n";
    fixed_warning("SetForceImpl");
    return;
  }
  if (bad_index(_index, name)) return;
  // as ODEJoint: both links enabled
  if (LinkPtr c = GetChild()) c->SetEnabled(true);
  if (LinkPtr p = GetParent()) p->SetEnabled(true);
  ModelPtr m = model.lock();
  WorldPtr w = m->GetWorld();
  const double applied = core_of(w).add_joint_force(m->GetName(), name, _effort);
  // Gazebo's record of it: summed within one sim time, started afresh at the first SetForce of a later one
  const common::Time now = w->SimTime();
  if (forceAppliedTime < now) {
    forceAppliedTime = now;
    forceApplied = 0.0;
  }
  forceApplied += applied;
}

double Joint::GetForce(unsigned int _index) {
  if (fixed) {
    gzerr << "Invalid joint index [" << _index << "] when trying to get force\n";
    return 0.0;
  }
  if (bad_index(_index, name)) return 0.0;
  return forceApplied;
}

bool Joint::SetPosition(const unsigned int _index, const double _position, const bool _preserveWorldVelocity) {
  if (fixed) {
    // Joint::SetPositionMaximal
    gzerr << "Joint axis index [" << _index << "] larger than DOF count [0].\n";
    return false;
  }
  if (bad_index(_index, name)) return false;
  // Gazebo's Joint::SetPositionMaximal: the position is held within the joint's limits first
  const double position = lower < upper ? std::clamp(_position, lower, upper) : std::clamp(_position, upper, lower);
  ModelPtr m = model.lock();
  // _preserveWorldVelocity (ODE: each moved link keeps its world velocity; Link::MoveFrame): car's joints are
  // coordinates, so the joint's speed is kept, and with it the child's angular velocity about the joint's axis
  core_of(m->GetWorld()).set_joint_positions(m->GetName(), {name}, {position}, _preserveWorldVelocity);
  return true;
}

double Joint::LowerLimit(unsigned int _index) const {
  if (fixed) {
    gzwarn << "requesting lower limit of joint index out of bound\n";
    return std::numeric_limits<double>::quiet_NaN();
  }
  return bad_index(_index, name) ? 0.0 : lower;
}
double Joint::UpperLimit(const unsigned int _index) const {
  if (fixed) {
    gzwarn << "requesting upper limit of joint index out of bound\n";
    return std::numeric_limits<double>::quiet_NaN();
  }
  return bad_index(_index, name) ? 0.0 : upper;
}
double Joint::GetEffortLimit(unsigned int _index) {
  if (fixed) {
    gzerr << "GetEffortLimit index[" << _index << "] out of range\n";
    return 0.0;
  }
  return bad_index(_index, name) ? 0.0 : effort;
}
double Joint::GetVelocityLimit(unsigned int _index) {
  if (fixed) {
    gzerr << "GetVelocityLimit index[" << _index << "] out of range\n";
    return 0.0;
  }
  return bad_index(_index, name) ? 0.0 : velocity;
}
ignition::math::Vector3d Joint::LocalAxis(const unsigned int _index) const {
  // a fixed joint: Gazebo reads an <axis> written on it; car keeps none (docs/PLUGINS.md)
  if (fixed) return ignition::math::Vector3d::Zero;
  return bad_index(_index, name) ? ignition::math::Vector3d::Zero : axis;
}

// ---- JointController ---------------------------------------------------------------------------------------

JointController::JointController(ModelPtr _model) : model(_model) {}
JointController::~JointController() = default;

void JointController::AddJoint(JointPtr _joint) {
  const std::string key = _joint->GetScopedName();
  joints[key] = _joint;
  posPids[key].Init(1, 0.1, 0.01, 1, -1, 1000, -1000);
  velPids[key].Init(1, 0.1, 0.01, 1, -1, 1000, -1000);
}

void JointController::Reset() {
  positions.clear();
  velocities.clear();
  forces.clear();
}

void JointController::Update() {
  ModelPtr m = model.lock();
  if (!m) return;
  const common::Time now = m->GetWorld()->SimTime();
  const common::Time step = now - prevUpdateTime;
  prevUpdateTime = now;
  // no update when sim time went back (a reset) or stood still
  if (!(step > common::Time::Zero)) return;
  for (const auto& [key, f] : forces) joints[key]->SetForce(0, f);
  for (const auto& [key, target] : positions)
    joints[key]->SetForce(0, posPids[key].Update(joints[key]->Position(0) - target, step));
  for (const auto& [key, target] : velocities)
    joints[key]->SetForce(0, velPids[key].Update(joints[key]->GetVelocity(0) - target, step));
}

std::map<std::string, JointPtr> JointController::GetJoints() const { return joints; }

bool JointController::SetForce(const std::string& _jointName, const double _force) {
  if (!joints.count(_jointName)) return false;
  forces[_jointName] = _force;
  return true;
}

void JointController::SetPositionPID(const std::string& _jointName, const common::PID& _pid) {
  if (joints.count(_jointName))
    posPids[_jointName] = _pid;
  else
    gzerr << "Unable to find joint with name[" << _jointName << "]\n";
}

bool JointController::SetPositionTarget(const std::string& _jointName, const double _target) {
  if (!posPids.count(_jointName)) return false;
  positions[_jointName] = _target;
  return true;
}

void JointController::SetVelocityPID(const std::string& _jointName, const common::PID& _pid) {
  if (joints.count(_jointName))
    velPids[_jointName] = _pid;
  else
    gzerr << "Unable to find joint with name[" << _jointName << "]\n";
}

bool JointController::SetVelocityTarget(const std::string& _jointName, const double _target) {
  if (!velPids.count(_jointName)) return false;
  velocities[_jointName] = _target;
  return true;
}

std::map<std::string, common::PID> JointController::GetPositionPIDs() const { return posPids; }
std::map<std::string, common::PID> JointController::GetVelocityPIDs() const { return velPids; }
std::map<std::string, double> JointController::GetForces() const { return forces; }
std::map<std::string, double> JointController::GetPositions() const { return positions; }
std::map<std::string, double> JointController::GetVelocities() const { return velocities; }
common::Time JointController::GetLastUpdateTime() const { return prevUpdateTime; }

// ---- PhysicsIface --------------------------------------------------------------------------------------------

WorldPtr get_world(const std::string& _name) {
  if (car_gazebo::Hub* h = car_gazebo::Hub::named(_name)) return h->world;
  if (_name.empty()) gzerr << "no worlds\n";
  gzerr << "Unable to find world by name in physics::get_world[" << _name << "]\n";
  gzthrow("Unable to find world by name in physics::get_world(world_name)");
}

bool has_world(const std::string& _name) { return car_gazebo::Hub::named(_name) != nullptr; }

}  // namespace physics
}  // namespace gazebo
