// Math aliases and small helpers shared by every engine layer.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

#include "service/physics/portable_math.h"

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
// any angle, and well defined as |phi| -> 0. The half angle's sine and
// cosine are portable_math.h's, not the C library's (Eigen::AngleAxis), so
// that the rotation is the same on every machine.
inline Quat QuatFromRotationVector(const Vec3& phi) {
  const double angle = phi.norm();
  if (angle < 1e-12) {
    Quat q(1.0, 0.5 * phi.x(), 0.5 * phi.y(), 0.5 * phi.z());
    return q.normalized();
  }
  const Vec3 v = portable::Sin(0.5 * angle) * (phi / angle);
  return Quat(portable::Cos(0.5 * angle), v.x(), v.y(), v.z());
}

// The rotation vector (axis * angle, angle in [0, pi]) of a unit
// quaternion, the inverse of QuatFromRotationVector; with portable_math.h's
// atan2 in place of Eigen::AngleAxis's.
inline Vec3 RotationVector(const Quat& q) {
  const double s = q.vec().norm();
  if (s == 0.0) return Vec3::Zero();
  const double angle = 2.0 * portable::Atan2(s, std::abs(q.w()));
  return (q.w() < 0.0 ? -angle : angle) / s * q.vec();
}

}  // namespace contactsim
