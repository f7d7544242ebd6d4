// car's Gazebo 11 API (docs/PLUGINS.md): gazebo::physics::Model, a handle on one of car's robots. Its links and
// joints are handles too; every call goes to car's world (car_sim::World's public API).
#pragma once
#include <ignition/math/Pose3.hh>
#include <ignition/math/Vector3.hh>
#include <sdf/sdf.hh>
#include <string>

#include "gazebo/common/CommonTypes.hh"
#include "gazebo/physics/Entity.hh"
#include "gazebo/physics/PhysicsTypes.hh"
#include "gazebo/transport/TransportTypes.hh"

namespace gazebo {
namespace physics {

class Model : public Entity {
 public:
  // car: made by the World handle for a robot of car's world.
  Model(WorldPtr _world, const std::string& _name);
  ~Model() override;

  // The model's <model> as SDF (car: its name, its links and joints by name, and the plug-ins' elements).
  const sdf::ElementPtr GetSDF();

  // A link by plain or scoped name ("MODEL::LINK"); "canonical" (the default) is the root link. Null when none.
  LinkPtr GetLink(const std::string& _name = "canonical") const;
  const Link_V& GetLinks() const;
  LinkPtr GetChildLink(const std::string& _name) const;
  // A moving joint by plain or scoped name; null when none (fixed joints are merged, as Gazebo's URDF import does).
  JointPtr GetJoint(const std::string& _name);
  const Joint_V& GetJoints() const;
  unsigned int GetJointCount() const;
  // The model's joint controller: updated every step after WorldUpdateBegin, as Gazebo's Model::Update does.
  JointControllerPtr GetJointController();

  // The model frame (its root link's frame), world frame.
  ignition::math::Pose3d WorldPose() const override;
  // Moves the model rigidly; its velocities and joints are kept. _notify and _publish have no effect in car.
  void SetWorldPose(const ignition::math::Pose3d& _pose, bool _notify = true, bool _publish = true) override;
  ignition::math::Vector3d WorldLinearVel() const override;
  ignition::math::Vector3d WorldAngularVel() const override;
  ignition::math::Vector3d RelativeLinearVel() const override;
  ignition::math::Vector3d RelativeAngularVel() const override;
  // Gazebo 11 sets every link's velocity; car sets the root link's centre of mass and moves the model rigidly
  // (joint speeds kept; docs/PLUGINS.md).
  void SetLinearVel(const ignition::math::Vector3d& _vel);
  void SetAngularVel(const ignition::math::Vector3d& _vel);
  bool IsStatic() const;
  // Moves the model rigidly so that the link lands on _pose (world frame); joints kept.
  void SetLinkWorldPose(const ignition::math::Pose3d& _pose, std::string _linkName);
  void SetLinkWorldPose(const ignition::math::Pose3d& _pose, const LinkPtr& _link);

  // car: the handles of its links, joints and controller, made once by the World handle; the controller's update,
  // called each step by car_gazebo.
  void Build();
  void UpdateController();

 private:
  Link_V links;
  Joint_V joints;
  JointControllerPtr controller;
  sdf::ElementPtr sdf;
};

}  // namespace physics
}  // namespace gazebo
