// The Bullet world (private to the core): robots as btMultiBody (reduced coordinates, fixed joints merged),
// world models as rigid bodies and static objects, Gazebo's contact rules, and the ray scene kept in step with
// the bodies. Knows nothing of plug-ins: they act through RobotHandle, which the world implements over this.
#pragma once

#include <memory>
#include <set>
#include <string>
#include <vector>

#include "car_sim/description.hpp"
#include "car_sim/model.hpp"
#include "car_sim/raycast.hpp"
#include "car_sim/state.hpp"

class btMultiBody;
class btMultiBodyDynamicsWorld;
class btRigidBody;

namespace car_sim {
namespace physics {

// How the contact and motor rows are set up (docs/COMPAT-physics.md "Row set-up"): by Bullet; by car's set-up
// with Bullet's Featherstone pass for each row's response (Bullet's rows bit for bit: the tests' reference); by
// car's set-up with the factored mass matrix (the default).
enum class RowSetup { bullet, car_exact, factored };

struct Options {
  int solver_iterations = 10;
  double residual_threshold = 1e-9;
  double dt = 0.001;  // [s]; motors cap their impulse at effort * dt
  RowSetup rows = RowSetup::factored;
  // Skip the work Bullet would repeat bit for bit for an object at rest: its predicted transform and its bounding
  // box (IslandWorld). false: Bullet's own passes, the tests' reference.
  bool reuse_at_rest = true;
  // Islands, island manifolds and constraints put in Bullet's order by car's copy of its sort, the last step's
  // order taken again for an unchanged input (IslandWorld, IslandSort). false: Bullet's own sorts, the tests'
  // reference.
  bool own_island_sort = true;
};

class Robot;

class Physics {
 public:
  // The world's models (less the removed ones) and gravity. `desc` must outlive the Physics: the world models'
  // poses are read from it.
  Physics(const WorldDescription& desc, const Options& options, const std::set<std::string>& removed);
  ~Physics();
  Physics(const Physics&) = delete;
  Physics& operator=(const Physics&) = delete;

  // A robot from its model; driven: joints a plug-in drives (their ball casters keep friction).
  // Throws LoadError for a model the physics cannot build.
  Robot& add_robot(const RobotModel& model, const std::string& name, const Eigen::Isometry3d& pose,
                   const std::set<std::string>& driven);
  void remove_robot(const std::string& name);
  void remove_world_model(const std::string& name);
  Robot* find_robot(const std::string& name);
  const Robot* find_robot(const std::string& name) const;

  // One fixed step, no substeps.
  void step(double dt);

  // A world model's state (a static one's: where it is, at rest); nullopt for an unknown one.
  std::optional<ModelState> world_model_state(const std::string& name) const;
  // Moves a world model and its nested models (a static one's twist is ignored); false for an unknown model.
  bool set_world_model_state(const std::string& name, const ModelState& s);

  std::vector<Contact> contacts(double dt) const;

  // The ray scene over the collision geometry, every body where it is now (built on first use).
  const RayScene& rays();
  void invalidate_rays();

  // Bullet's world and a dynamic world model's link body (nullptr: static or unknown), for the gazebo_ros API
  // services (services.cpp).
  btMultiBodyDynamicsWorld& bullet();
  btRigidBody* world_model_body(const std::string& model, size_t link);

  struct Impl;  // Bullet's objects (physics_impl.hpp, private to physics/)

 private:
  std::unique_ptr<Impl> impl_;
};

// A robot's multibody, for the world's RobotHandle.
class Robot {
 public:
  virtual ~Robot() = default;
  virtual int joint(const std::string& name) const = 0;
  virtual double joint_position(int joint) const = 0;
  virtual double joint_velocity(int joint) const = 0;
  virtual int add_motor(int joint, double max_effort) = 0;
  virtual void set_motor(int motor, const MotorTarget& target) = 0;
  virtual Eigen::Isometry3d link_pose(const std::string& link) const = 0;
  virtual ModelState link_state(const std::string& link) const = 0;
  virtual ModelState root_state() const = 0;
  virtual void set_root_state(const ModelState& s) = 0;
  virtual bool has_link(const std::string& link) const = 0;

  // ---- motion and contact (issue 11; implemented in bullet_robot.cpp) ----
  // A force [N] at a world point [m] and a torque [N m], world frame, on a link's body for the coming step.
  virtual void apply_wrench(const std::string& link, const Eigen::Vector3d& force, const Eigen::Vector3d& torque,
                            const Eigen::Vector3d& point) = 0;
  // World position [m] of a link's body's centre of mass.
  virtual Eigen::Vector3d body_com(const std::string& link) const = 0;
  virtual void set_root_velocity(const Eigen::Vector3d& linear, const Eigen::Vector3d& angular) = 0;
  virtual void set_joint_position(int joint, double position) = 0;
  // Sets a joint's velocity [rad/s] or [m/s]; its position stays.
  virtual void set_joint_velocity(int joint, double velocity) = 0;
  virtual void enable_joint_wrench(int joint) = 0;
  virtual Wrench joint_wrench(int joint) const = 0;
  virtual std::vector<LinkContact> link_contacts(const std::string& link) const = 0;
  // Bullet's multibody and the index of its link that carries a robot link (-1: the base; fixed joints merge
  // links into one body), for the gazebo_ros API services (services.cpp). Throws for an unknown link.
  virtual btMultiBody* multibody() const = 0;
  virtual int body_of_link(const std::string& link) const = 0;
};

}  // namespace physics
}  // namespace car_sim
