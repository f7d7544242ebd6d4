// Helpers shared by the core tests.
#pragma once

#include <Eigen/Geometry>
#include <fstream>
#include <sstream>
#include <string>

inline std::string read_text(const std::string& rel) {
  std::ifstream in(std::string(CAR_SOURCE_DIR) + "/" + rel);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline std::string data_path(const std::string& rel) { return std::string(CAR_SOURCE_DIR) + "/test/data/" + rel; }

// A pose on the ground: (x, y) [m] and yaw [rad].
inline Eigen::Isometry3d at(double x, double y, double yaw) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(x, y, 0.0);
  T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return T;
}
