// Plain state records of the car_sim core, shared by the world, the physics and the plug-ins. No ROS headers.
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

// The world's light and gravity, as the sensors see them.
struct Environment {
  Eigen::Vector3d gravity = Eigen::Vector3d(0, 0, -9.8);                          // [m/s^2], world frame
  Eigen::Vector3d sun_direction = Eigen::Vector3d(-0.5, 0.1, -0.9).normalized();  // light travels along it
  double ambient = 0.4;                                                          // scene ambient light
  Eigen::Vector3d background = Eigen::Vector3d(0.7, 0.7, 0.7);                  // colour where nothing is hit
};

}  // namespace car_sim
