// Eigen <-> Bullet conversions for physics/ (private to it): vectors, rigid transforms, rotations.
#pragma once

#include <LinearMath/btQuaternion.h>
#include <LinearMath/btTransform.h>
#include <LinearMath/btVector3.h>

#include <Eigen/Geometry>

namespace car_sim {
namespace physics {

inline btVector3 bt(const Eigen::Vector3d& v) { return btVector3(v.x(), v.y(), v.z()); }
inline Eigen::Vector3d eig(const btVector3& v) { return Eigen::Vector3d(v.x(), v.y(), v.z()); }

inline btTransform bt(const Eigen::Isometry3d& T) {
  const Eigen::Quaterniond q(T.linear());
  return btTransform(btQuaternion(q.x(), q.y(), q.z(), q.w()), bt(Eigen::Vector3d(T.translation())));
}

inline Eigen::Isometry3d eig(const btTransform& t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  const btQuaternion q = t.getRotation();
  T.linear() = Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z()).normalized().toRotationMatrix();
  T.translation() = eig(t.getOrigin());
  return T;
}

inline btQuaternion bt_quat(const Eigen::Matrix3d& R) {
  const Eigen::Quaterniond q(R);
  return btQuaternion(q.x(), q.y(), q.z(), q.w());
}

inline bool is_identity(const Eigen::Isometry3d& T) {
  return T.translation().norm() < 1e-12 && (T.linear() - Eigen::Matrix3d::Identity()).norm() < 1e-12;
}

}  // namespace physics
}  // namespace car_sim
