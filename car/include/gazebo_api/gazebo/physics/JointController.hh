// car's Gazebo 11 API (docs/PLUGINS.md): gazebo::physics::JointController, PID position and velocity control of a
// model's joints through Joint::SetForce. Joints are keyed by their scoped name ("MODEL::JOINT"); each added joint
// gets Gazebo's PIDs (p 1, i 0.1, d 0.01, i in [-1, 1], command in [-1000, 1000]).
#pragma once

#include <boost/weak_ptr.hpp>
#include <map>
#include <string>

#include "gazebo/common/PID.hh"
#include "gazebo/common/Time.hh"
#include "gazebo/physics/PhysicsTypes.hh"

namespace gazebo {
namespace physics {

class JointController {
 public:
  explicit JointController(ModelPtr _model);
  virtual ~JointController();
  void AddJoint(JointPtr _joint);
  // Clears the targets and forces.
  void Reset();
  // The forces, then the position PIDs, then the velocity PIDs, each through SetForce, with the time since the
  // last update (no update when sim time has not moved on).
  void Update();
  std::map<std::string, JointPtr> GetJoints() const;
  bool SetForce(const std::string& _jointName, const double _force);
  void SetPositionPID(const std::string& _jointName, const common::PID& _pid);
  bool SetPositionTarget(const std::string& _jointName, const double _target);
  void SetVelocityPID(const std::string& _jointName, const common::PID& _pid);
  bool SetVelocityTarget(const std::string& _jointName, const double _target);
  std::map<std::string, common::PID> GetPositionPIDs() const;
  std::map<std::string, common::PID> GetVelocityPIDs() const;
  std::map<std::string, double> GetForces() const;
  std::map<std::string, double> GetPositions() const;
  std::map<std::string, double> GetVelocities() const;
  common::Time GetLastUpdateTime() const;

 private:
  boost::weak_ptr<Model> model;
  std::map<std::string, JointPtr> joints;
  std::map<std::string, common::PID> posPids, velPids;
  std::map<std::string, double> forces, positions, velocities;
  common::Time prevUpdateTime;
};

}  // namespace physics
}  // namespace gazebo
