// Math aliases and small helpers shared by every engine layer.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace contactsim {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

constexpr double kPi = 3.14159265358979323846;

// Cross-product matrix: Skew(a) * b == a.cross(b).
inline Mat3 Skew(const Vec3& a) {
  Mat3 m;
  m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return m;
}

// Two unit vectors that make (t1, t2, n) a right-handed orthonormal frame
// for a unit n; they depend only on n, so the same n gives the same basis
// every step (stable warm starts and joint rows).
inline void PerpendicularBasis(const Vec3& n, Vec3* t1, Vec3* t2) {
  *t1 = std::abs(n.x()) < 0.57735 ? n.cross(Vec3::UnitX()).normalized() : n.cross(Vec3::UnitY()).normalized();
  *t2 = n.cross(*t1);
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
