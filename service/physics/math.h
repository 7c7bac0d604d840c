// Math aliases and small helpers shared by every engine layer.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace contactsim {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

// Cross-product matrix: Skew(a) * b == a.cross(b).
inline Mat3 Skew(const Vec3& a) {
  Mat3 m;
  m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return m;
}

inline bool IsFinite(const Vec3& v) { return v.allFinite(); }
inline bool IsFinite(const Quat& q) { return q.coeffs().allFinite(); }

// Rotation by the vector phi (axis * angle) as a unit quaternion; exact for
// any angle, and well defined as |phi| -> 0.
inline Quat QuatFromRotationVector(const Vec3& phi) {
  const double angle = phi.norm();
  if (angle < 1e-12) {
    Quat q(1.0, 0.5 * phi.x(), 0.5 * phi.y(), 0.5 * phi.z());
    return q.normalized();
  }
  return Quat(Eigen::AngleAxisd(angle, phi / angle));
}

}  // namespace contactsim
