// Ericson, "Real-Time Collision Detection", 2005: point-segment (5.1.2) and
// segment-segment (5.1.9, ClosestPtSegmentSegment) closest points.
#include "service/collision/closest_points.h"

#include <algorithm>

namespace contactsim {
namespace {

// Squared lengths below this are degenerate segments (points); 1e-24 m^2 is
// (1e-12 m)^2, far below any shape size the server accepts.
constexpr double kDegenerateSq = 1e-24;

double Clamp01(double v) { return std::min(1.0, std::max(0.0, v)); }

}  // namespace

Vec3 ClosestPointOnSegment(const Vec3& p, const Vec3& a, const Vec3& b, double* t) {
  const Vec3 ab = b - a;
  const double len_sq = ab.squaredNorm();
  const double u = len_sq > kDegenerateSq ? Clamp01((p - a).dot(ab) / len_sq) : 0.0;
  if (t != nullptr) *t = u;
  return a + u * ab;
}

SegmentClosestPoints ClosestPointsOfSegments(const Vec3& p1, const Vec3& q1, const Vec3& p2,
                                             const Vec3& q2) {
  SegmentClosestPoints out;
  const Vec3 d1 = q1 - p1;
  const Vec3 d2 = q2 - p2;
  const Vec3 r = p1 - p2;
  const double a = d1.squaredNorm();
  const double e = d2.squaredNorm();
  const double f = d2.dot(r);
  double s = 0.0;
  double t = 0.0;
  if (a <= kDegenerateSq && e <= kDegenerateSq) {
    // both segments are points
  } else if (a <= kDegenerateSq) {
    t = Clamp01(f / e);
  } else {
    const double c = d1.dot(r);
    if (e <= kDegenerateSq) {
      s = Clamp01(-c / a);
    } else {
      const double b = d1.dot(d2);
      const double denom = a * e - b * b;  // |d1|^2 |d2|^2 sin^2(angle) >= 0
      // parallel segments (relative sin^2 below 1e-14) keep s = 0, as Ericson
      if (denom > 1e-14 * a * e) s = Clamp01((b * f - c * e) / denom);
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = Clamp01(-c / a);
      } else if (t > 1.0) {
        t = 1.0;
        s = Clamp01((b - c) / a);
      }
    }
  }
  out.s = s;
  out.t = t;
  out.c1 = p1 + s * d1;
  out.c2 = p2 + t * d2;
  return out;
}

}  // namespace contactsim
