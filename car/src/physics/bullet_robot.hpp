// BulletRobot (private to physics/): a robot as one btMultiBody (reduced coordinates, fixed joints merged), its
// colliders with their surfaces, joint limits, friction and motors, the per-step link forces, and the Robot
// interface the world drives it through. Built by Physics::add_robot; its members in bullet_robot.cpp.
#pragma once

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointFeedback.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bodies.hpp"
#include "physics_impl.hpp"

namespace car_sim {
namespace physics {

using detail::Body;
using detail::BodyTree;

class BulletRobot : public Robot {
 public:
  BulletRobot(Physics::Impl& P, const RobotModel& model, const std::string& name, const Eigen::Isometry3d& pose,
              const std::set<std::string>& driven);

  ~BulletRobot() override {
    for (auto& c : constraints_) P_.world.removeMultiBodyConstraint(c.get());
    for (auto& c : colliders_) P_.world.removeCollisionObject(c.get());
    P_.world.removeMultiBody(mb_.get());
  }

  const std::string& name() const { return name_; }
  const BodyTree& tree() const { return tree_; }
  const RobotModel& model() const { return model_; }
  btMultiBody* mb() const { return mb_.get(); }
  btMultiBody* multibody() const override { return mb_.get(); }
  int body_of_link(const std::string& link) const override {
    const auto it = tree_.body_of_link.find(link);
    if (it == tree_.body_of_link.end())
      throw std::invalid_argument("robot '" + name_ + "' has no link '" + link + "'");
    return it->second - 1;
  }

  int joint(const std::string& name) const override {
    const auto it = joint_link_.find(name);
    return it == joint_link_.end() ? -1 : it->second;
  }
  double joint_position(int j) const override { return mb_->getJointPos(j); }
  double joint_velocity(int j) const override { return mb_->getJointVel(j); }

  // A motor's effort is capped by the joint's <limit effort> (when > 0).
  int add_motor(int joint, double max_effort) override {
    const Joint* j = link_joint_.at(joint);
    if (j->limits && j->limits->effort > 0.0) max_effort = std::min(max_effort, j->limits->effort);
    auto* m = new JointMotor(mb_.get(), joint, 0, 0.0, max_effort * P_.options.dt);
    add_constraint(m);
    motors_.push_back(m);
    motor_impulse_.push_back(max_effort * P_.options.dt);
    motor_joint_.push_back(j);
    return static_cast<int>(motors_.size()) - 1;
  }

  // The target velocity is clamped by the joint's <limit velocity> (when > 0).
  void set_motor(int motor, const MotorTarget& t) override {
    btMultiBodyJointMotor* m = motors_.at(motor);
    const Joint* j = motor_joint_.at(motor);
    double v = t.velocity;
    if (j->limits && j->limits->velocity > 0.0) v = std::clamp(v, -j->limits->velocity, j->limits->velocity);
    m->setVelocityTarget(v, t.kd);
    m->setPositionTarget(t.position, t.kp);
    m->setMaxAppliedImpulse(t.enabled ? motor_impulse_.at(motor) : 0.0);
  }

  bool has_link(const std::string& link) const override { return tree_.body_of_link.count(link) > 0; }

  Eigen::Isometry3d link_pose(const std::string& link) const override {
    const auto it = tree_.body_of_link.find(link);
    if (it == tree_.body_of_link.end())
      throw std::invalid_argument("robot '" + name_ + "' has no link '" + link + "'");
    const Body& b = tree_.bodies[it->second];
    return body_com_pose(it->second) * b.top_to_com.inverse() * tree_.link_in_top.at(link);
  }

  ModelState link_state(const std::string& link) const override;

  ModelState root_state() const override {
    ModelState s;
    s.pose = eig(mb_->getBaseWorldTransform()) * tree_.bodies[0].top_to_com.inverse();
    s.angular = eig(mb_->getBaseOmega());
    const Eigen::Vector3d com = eig(mb_->getBasePos());
    // velocity of the root frame's origin
    s.linear = eig(mb_->getBaseVel()) + s.angular.cross(s.pose.translation() - com);
    return s;
  }

  void set_root_state(const ModelState& st) override {
    const Eigen::Isometry3d com = st.pose * tree_.bodies[0].top_to_com;
    mb_->setBaseWorldTransform(bt(com));
    mb_->setBaseOmega(bt(st.angular));
    mb_->setBaseVel(bt(Eigen::Vector3d(st.linear + st.angular.cross(com.translation() - st.pose.translation()))));
    update_colliders();
  }

  // Pose of a body's com frame in the world.
  Eigen::Isometry3d body_com_pose(int body) const {
    if (body == 0) return eig(mb_->getBaseWorldTransform());
    btAlignedObjectArray<btQuaternion> q;
    btAlignedObjectArray<btVector3> v;
    mb_->forwardKinematics(q, v);
    return eig(mb_->getLink(body - 1).m_cachedWorldTransform);
  }

  const btCollisionObject* collider(int body) const {
    return body == 0 ? mb_->getBaseCollider() : mb_->getLink(body - 1).m_collider;
  }

 private:
  void add_constraint(btMultiBodyConstraint* c) {
    constraints_.emplace_back(c);
    P_.world.addMultiBodyConstraint(c);
  }

  void update_colliders() {
    btAlignedObjectArray<btQuaternion> q;
    btAlignedObjectArray<btVector3> v;
    mb_->updateCollisionObjectWorldTransforms(q, v);
  }

  Physics::Impl& P_;
  RobotModel model_;
  std::string name_;
  BodyTree tree_;
  std::unique_ptr<btMultiBody> mb_;
  std::vector<std::unique_ptr<btMultiBodyLinkCollider>> colliders_;
  std::vector<std::unique_ptr<btMultiBodyConstraint>> constraints_;  // joint limits and motors
  std::vector<btMultiBodyJointMotor*> motors_;
  std::vector<double> motor_impulse_;         // motor id -> its cap [N s] or [N m s] per step
  std::map<std::string, int> joint_link_;     // non-fixed joint -> multibody link index
  std::vector<const Joint*> link_joint_;      // multibody link index -> its joint
  std::vector<const Joint*> motor_joint_;     // motor id -> its joint

  // A link's share of its body for the per-step forces: gravity off and velocity decay (dampingFactor).
  struct LinkForce {
    int body = 0;                               // 0 = base, i = multibody link i - 1
    double mass = 0.0;                          // [kg]
    Eigen::Vector3d com = Eigen::Vector3d::Zero();       // [m] link centre of mass, body com frame
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();   // [kg m^2] about the link com, body com frame
    bool no_gravity = false;
    double decay = 0.0;                         // [-] per step
  };
  std::vector<LinkForce> link_forces_;
  std::vector<std::pair<int, double>> joint_damping_;  // (multibody link, damping) for joints with damping > 0

  void collect_link_forces();

 public:
  // Forces for the coming step [N], [N m], world frame: joint damping -d q', gravity cancelled on links that
  // feel none, and ODE's per-step velocity decay v <- v (1 - f) as the force -m f v / dt.
  void apply_forces(double dt, const Eigen::Vector3d& gravity);

 public:
  // ---- motion and contact (issue 11) ----
  void apply_wrench(const std::string& link, const Eigen::Vector3d& force, const Eigen::Vector3d& torque,
                    const Eigen::Vector3d& point) override;
  Eigen::Vector3d body_com(const std::string& link) const override;
  void set_root_velocity(const Eigen::Vector3d& linear, const Eigen::Vector3d& angular) override;
  void set_joint_position(int joint, double position) override;
  void set_joint_velocity(int joint, double velocity) override { mb_->setJointVel(joint, velocity); }
  void enable_joint_wrench(int joint) override;
  Wrench joint_wrench(int joint) const override;
  std::vector<LinkContact> link_contacts(const std::string& link) const override;

 private:
  int body_index(const std::string& link) const;
  std::vector<std::unique_ptr<btMultiBodyJointFeedback>> feedback_;  // joint reaction sensors
};

}  // namespace physics
}  // namespace car_sim
