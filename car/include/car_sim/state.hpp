// Plain records of the car_sim core, shared by the world, the physics and the plug-ins: states, contacts, and what
// a robot's bodies take (motor targets, wrenches). Below both the physics and the plug-ins. No ROS headers.
#pragma once

#include <Eigen/Geometry>
#include <string>

namespace car_sim {

// Pose and twist of a frame, world frame.
struct ModelState {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();   // [m/s], world frame, of the frame's origin
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();  // [rad/s], world frame
};

struct JointState {
  std::string name;
  double position = 0.0;  // [rad] or [m]
  double velocity = 0.0;  // [rad/s] or [m/s]
};

// A contact between two bodies during the last step.
struct Contact {
  std::string a, b;                                      // "model/link" (robots: the body's top link)
  Eigen::Vector3d position = Eigen::Vector3d::Zero();    // [m], world frame, on b
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();     // unit, world frame, from b towards a
  double normal_force = 0.0;                             // [N]
};

// A motor's targets for the next step: velocity (with its gain) and position (with its gain), both optional.
struct MotorTarget {
  double velocity = 0.0;  // [rad/s] or [m/s]
  double kd = 1.0;        // [-] velocity gain (1 = hold the target as a hard constraint, capped by the effort)
  double position = 0.0;  // [rad] or [m]
  double kp = 0.0;        // [-] fraction of the position error corrected per step (0 = none)
  // false: the motor applies nothing (a joint driven by effort; an idle Bullet motor with gains 0 still resists any
  // change of velocity up to its cap)
  bool enabled = true;
};

// A force and a torque on a body (issue 11: wrench plug-ins, f3d, ft_sensor).
struct Wrench {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   // [N]
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();  // [N m]
};

// One contact point of a link with another body during the last step (the bumper's ContactState).
struct LinkContact {
  std::string other;                                   // the other body, "model::link"
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // [m], world frame
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();   // unit, world frame, from the other body into this link
  double depth = 0.0;                                  // [m] penetration, >= 0
  double normal_force = 0.0;                           // [N] along normal, on this link
};

// The world's light and gravity, as the sensors see them.
struct Environment {
  Eigen::Vector3d gravity = Eigen::Vector3d(0, 0, -9.8);                          // [m/s^2], world frame
  Eigen::Vector3d sun_direction = Eigen::Vector3d(-0.5, 0.1, -0.9).normalized();  // light travels along it
  double ambient = 0.4;                                                          // scene ambient light
  Eigen::Vector3d background = Eigen::Vector3d(0.7, 0.7, 0.7);                  // colour where nothing is hit
};

}  // namespace car_sim
