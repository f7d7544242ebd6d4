// What the gazebo_ros API services need of the physics (private header of the core): joint positions set
// directly, wrenches and joint efforts for one step, gravity and solver iterations at run time. World's public
// API (world.hpp, "gazebo_ros API") is built on these.
#pragma once

#include <map>
#include <string>

#include "physics.hpp"

namespace car_sim {
namespace physics {

// Sets joints (multibody link index -> position [rad] or [m]) and zeroes their speeds; the base stays where it
// is. Colliders follow at once.
void set_joint_positions(Robot& robot, const std::map<int, double>& positions, bool keep_speeds = false);
// Centre of mass [m], world frame, of the body that carries `link` (fixed joints merge links into one body).
Eigen::Vector3d body_com(const Robot& robot, const std::string& link);
// Adds a wrench for the next step on the body that carries `link`: force [N] and torque [N m], world frame, at
// the body's centre of mass.
void add_link_wrench(Robot& robot, const std::string& link, const Eigen::Vector3d& force, const Eigen::Vector3d& torque);
// The same on a dynamic world model's link body (a btRigidBody).
void add_body_wrench(btRigidBody& body, const Eigen::Vector3d& force, const Eigen::Vector3d& torque);
// Adds an effort [N m] or [N] on a joint (multibody link index) for the next step.
void add_joint_effort(Robot& robot, int joint, double effort);
// Gravity [m/s^2], world frame, for every body (robots' multibodies and world rigid bodies).
void set_gravity(Physics& physics, const Eigen::Vector3d& gravity);
// Sequential-impulse iterations per step.
void set_solver_iterations(Physics& physics, int iterations);
int solver_iterations(Physics& physics);

}  // namespace physics
}  // namespace car_sim
